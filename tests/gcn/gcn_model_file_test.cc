#include "gcn/model_file.h"

#include <gtest/gtest.h>

#include "gcn/gcn_test_utils.h"
#include "util/error.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

GcnModel MakeModel() {
  GcnModel model = InitializeGcnModel(
      test::SmallShape(12), GcnAggregation::kRowNormalized, 4);
  test::RandomizeModel(&model, 8);
  model.embedding.type = "vlad";
  model.embedding.blob = std::string("codebook\0\x01\xff bytes", 17);
  model.info.tau_mo = 0.3f;
  model.info.tau_ct = 0.2f;
  model.info.test_k1 = 20;
  model.info.test_k2 = 4;
  model.info.test_u = 6;
  model.info.threshold = 0.6f;
  model.info.notes = "trained on synthetic\nclusters";
  return model;
}

void ExpectEqual(const GcnModel& a, const GcnModel& b) {
  EXPECT_TRUE(a.shape == b.shape);
  EXPECT_EQ(a.aggregation, b.aggregation);
  EXPECT_EQ(a.input_shift, b.input_shift);
  EXPECT_EQ(a.input_scale, b.input_scale);
  EXPECT_EQ(a.params.Values(), b.params.Values());
  EXPECT_EQ(a.embedding.type, b.embedding.type);
  EXPECT_EQ(a.embedding.dim, b.embedding.dim);
  EXPECT_EQ(a.embedding.blob, b.embedding.blob);
  EXPECT_EQ(a.info.tau_mo, b.info.tau_mo);
  EXPECT_EQ(a.info.tau_ct, b.info.tau_ct);
  EXPECT_EQ(a.info.test_k1, b.info.test_k1);
  EXPECT_EQ(a.info.test_k2, b.info.test_k2);
  EXPECT_EQ(a.info.test_u, b.info.test_u);
  EXPECT_EQ(a.info.threshold, b.info.threshold);
  EXPECT_EQ(a.info.notes, b.info.notes);
}

// The Error message, checked to be a single line.
std::string ErrorOf(const std::string& bytes) {
  try {
    DeserializeGcnModel(bytes, "model.bin");
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    return message;
  }
  ADD_FAILURE() << "no error";
  return "";
}

TEST(GcnModelFile, RoundTripThroughFile) {
  const GcnModel model = MakeModel();
  TemporaryDirectory dir;
  const std::string path = JoinPaths(dir.Path(), "model.gcnmodel");
  WriteGcnModel(path, model);
  const GcnModel loaded = ReadGcnModel(path);
  ExpectEqual(model, loaded);
  EXPECT_EQ(loaded.embedding.dim, 12);
  // Byte-identical re-serialisation.
  EXPECT_EQ(SerializeGcnModel(loaded), SerializeGcnModel(model));
}

TEST(GcnModelFile, DefaultShapeRoundTrip) {
  GcnModel model =
      InitializeGcnModel(GcnShape(), GcnAggregation::kSymmetric, 1);
  model.embedding.type = "imported:netvlad";
  ExpectEqual(model, DeserializeGcnModel(SerializeGcnModel(model), "x"));
}

TEST(GcnModelFile, TruncatedForeignCorruptAndMismatched) {
  const std::string bytes = SerializeGcnModel(MakeModel());
  for (size_t size : {size_t(0),
                      size_t(5),
                      size_t(8),
                      size_t(20),
                      size_t(24),
                      size_t(100),
                      bytes.size() / 2,
                      bytes.size() - 8,
                      bytes.size() - 1}) {
    const std::string message = ErrorOf(bytes.substr(0, size));
    if (size < 8) {
      EXPECT_NE(message.find("not a GCN model file"), std::string::npos)
          << message;
    } else {
      EXPECT_NE(message.find("truncated"), std::string::npos) << message;
    }
  }
  EXPECT_NE(ErrorOf("# COLMAP pairs file\nimg1.jpg img2.jpg\n")
                .find("not a GCN model file (bad magic)"),
            std::string::npos);
  EXPECT_NE(ErrorOf(bytes + "x").find("trailing"), std::string::npos);

  std::string corrupt = bytes;
  corrupt[bytes.size() / 2] ^= 0x10;
  EXPECT_NE(ErrorOf(corrupt).find("corrupt (checksum mismatch)"),
            std::string::npos);

  std::string future = bytes;
  future[8] = 7;
  EXPECT_NE(ErrorOf(future).find("format version 7"), std::string::npos);

  EXPECT_THROW(ReadGcnModel("/nonexistent/model.gcnmodel"), Error);

  const GcnModel model = MakeModel();
  EXPECT_NO_THROW(model.CheckEmbeddingDimension(12));
  try {
    model.CheckEmbeddingDimension(256);
    ADD_FAILURE() << "no error";
  } catch (const Error& error) {
    EXPECT_STREQ(error.what(),
                 "the GCN model expects 12-dimensional embeddings (type "
                 "'vlad') but got 256-dimensional ones");
  }
}

}  // namespace
}  // namespace colmap_gcn
