#include "gcn/model_file.h"

#include <cstring>

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

// A model with structural node features reading `dim`-D embeddings.
GcnModel MakeStructureModel(QesStructureFeatures structure, int dim) {
  const int differences = QesUsesEmbeddingDifferences(structure) ? dim : 0;
  GcnModel model = InitializeGcnModel(
      test::SmallShape(differences + QesStructureDim(structure)),
      GcnAggregation::kRowNormalized,
      4);
  test::RandomizeModel(&model, 8);
  model.embedding.type = "vlad";
  model.structure_features = structure;
  model.embedding.dim = dim;
  EXPECT_EQ(model.EmbeddingDim(), dim);
  return model;
}

void ExpectEqual(const GcnModel& a, const GcnModel& b) {
  EXPECT_TRUE(a.shape == b.shape);
  EXPECT_EQ(a.aggregation, b.aggregation);
  EXPECT_EQ(a.feature_scaling, b.feature_scaling);
  EXPECT_EQ(a.structure_features, b.structure_features);
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

// Recomputes the payload checksum of an edited model file.
void Reseal(std::string* bytes) {
  uint64_t payload_size = 0;
  std::memcpy(&payload_size, bytes->data() + 16, sizeof(payload_size));
  const uint64_t checksum = Fnv1a64(bytes->data() + 24, payload_size);
  bytes->replace(24 + payload_size,
                 sizeof(checksum),
                 reinterpret_cast<const char*>(&checksum),
                 sizeof(checksum));
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

// gcn_matcher may hold several models (--GcnMatching.model_path, the
// default one): a dimension mismatch names the file read.
TEST(GcnModelFile, EmbeddingDimensionErrorNamesTheModelFile) {
  TemporaryDirectory dir;
  const std::string path = JoinPaths(dir.Path(), "model.gcnmodel");
  WriteGcnModel(path, MakeModel());
  const GcnModel loaded = ReadGcnModel(path);
  EXPECT_EQ(loaded.source, path);
  EXPECT_NO_THROW(loaded.CheckEmbeddingDimension(12));
  try {
    loaded.CheckEmbeddingDimension(256);
    ADD_FAILURE() << "no error";
  } catch (const Error& error) {
    EXPECT_EQ(std::string(error.what()),
              "the GCN model " + path +
                  " expects 12-dimensional embeddings (type 'vlad') but got "
                  "256-dimensional ones");
  }
}

TEST(GcnModelFile, FeatureScalingRoundTripAndOnlyWrittenWhenUsed) {
  GcnModel model = MakeModel();
  const std::string plain = SerializeGcnModel(model);
  EXPECT_EQ(plain.find("FEAT"), std::string::npos);
  EXPECT_EQ(DeserializeGcnModel(plain, "x").feature_scaling,
            QesFeatureScaling::kNone);
  model.feature_scaling = QesFeatureScaling::kQueryScale;
  const std::string scaled = SerializeGcnModel(model);
  EXPECT_NE(scaled.find("FEAT"), std::string::npos);
  ExpectEqual(model, DeserializeGcnModel(scaled, "x"));
}

TEST(GcnModelFile, StructureFeaturesRoundTripAndDimensions) {
  const GcnModel model =
      MakeStructureModel(QesStructureFeatures::kReciprocal, 12);
  EXPECT_EQ(model.shape.input_dim, 12 + kQesReciprocalDim);
  const std::string bytes = SerializeGcnModel(model);
  EXPECT_NE(bytes.find("STRC"), std::string::npos);
  const GcnModel loaded = DeserializeGcnModel(bytes, "x");
  ExpectEqual(model, loaded);
  // The embeddings it reads are 12-D, not the network's 16 inputs.
  EXPECT_NO_THROW(loaded.CheckEmbeddingDimension(12));
  EXPECT_THROW(loaded.CheckEmbeddingDimension(16), Error);
  // Without the structure section the same network does not fit its
  // embeddings: refused instead of read as 16-D embeddings.
  GcnModel plain = model;
  plain.structure_features = QesStructureFeatures::kNone;
  plain.embedding.dim = 16;
  std::string edited = SerializeGcnModel(plain);
  const size_t embd = edited.find("EMBD");
  ASSERT_NE(embd, std::string::npos);
  // EMBD body: str type ("vlad": u64 length + 4 bytes), then i32 D.
  const size_t dim_offset = embd + 4 + 8 + 8 + 4;
  ASSERT_EQ(edited[dim_offset], 16);
  edited[dim_offset] = 12;
  Reseal(&edited);
  EXPECT_NE(ErrorOf(edited).find("embedding dimension 12 does not fit the "
                                 "network input 16 with none structural "
                                 "features"),
            std::string::npos);
}

TEST(GcnModelFile, StructureOnlyModelKeepsItsEmbeddingDimension) {
  // Five structural inputs, no embedding differences, 12-D embeddings.
  const GcnModel model =
      MakeStructureModel(QesStructureFeatures::kReciprocalOnly, 12);
  EXPECT_EQ(model.shape.input_dim, 1 + kQesReciprocalDim);
  EXPECT_EQ(model.DifferenceDim(), 0);
  std::string bytes = SerializeGcnModel(model);
  const GcnModel loaded = DeserializeGcnModel(bytes, "x");
  ExpectEqual(model, loaded);
  EXPECT_NO_THROW(loaded.CheckEmbeddingDimension(12));
  EXPECT_THROW(loaded.CheckEmbeddingDimension(5), Error);
  // An unknown set is refused by name.
  const size_t strc = bytes.find("STRC");
  ASSERT_NE(strc, std::string::npos);
  bytes[strc + 4 + 8] = 3;
  Reseal(&bytes);
  EXPECT_NE(ErrorOf(bytes).find("unknown structural node feature set 3"),
            std::string::npos);
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

template <typename T>
void Append(std::string* bytes, T value) {
  bytes->append(reinterpret_cast<const char*>(&value), sizeof(T));
}

void AppendSection(std::string* payload,
                   const char* tag,
                   const std::string& body) {
  payload->append(tag, 4);
  Append<uint64_t>(payload, body.size());
  payload->append(body);
}

// A header and checksum around the payload, so that only the sections are
// malformed.
std::string ModelFileAround(const std::string& payload) {
  std::string bytes = "CGCNMODL";
  Append<uint32_t>(&bytes, kGcnModelFormatVersion);
  Append<uint32_t>(&bytes, 0);
  Append<uint64_t>(&bytes, payload.size());
  bytes += payload;
  Append<uint64_t>(&bytes, Fnv1a64(payload.data(), payload.size()));
  return bytes;
}

// A shape the reader accepts (input 1, two GCN layers and FC of 65536) needs
// 8.6e9 weights; the reader allocated them (34 GB) before checking that the
// WGTS section holds them, so a 200-byte file was std::bad_alloc or an
// out-of-memory kill instead of an Error.
TEST(GcnModelFile, HugeShapeWithoutItsWeightsIsAnError) {
  GcnShape shape;
  shape.input_dim = 1;
  shape.gcn_dims = {65536, 65536};
  shape.fc_dim = 65536;
  std::string nets;
  for (int32_t value : {1, 2, 65536, 65536, 65536, 0}) Append(&nets, value);
  std::string embd;
  Append<uint64_t>(&embd, 0);
  Append<int32_t>(&embd, 1);
  Append<uint64_t>(&embd, 0);
  std::string norm;
  Append<float>(&norm, 0);
  Append<float>(&norm, 1);
  std::string wgts;
  Append<uint64_t>(&wgts, GcnParameterLayout(shape).size);
  std::string info(24, '\0');
  std::string payload;
  AppendSection(&payload, "NETS", nets);
  AppendSection(&payload, "EMBD", embd);
  AppendSection(&payload, "NORM", norm);
  AppendSection(&payload, "WGTS", wgts);
  AppendSection(&payload, "INFO", info);
  EXPECT_EQ(ErrorOf(ModelFileAround(payload)),
            "GCN model file model.bin: malformed WGTS section");

  // The same for a NORM section shorter than the input dimension says.
  std::string wide_nets;
  for (int32_t value : {1 << 20, 1, 1, 1, 0}) Append(&wide_nets, value);
  std::string wide_embd;
  Append<uint64_t>(&wide_embd, 0);
  Append<int32_t>(&wide_embd, 1 << 20);
  Append<uint64_t>(&wide_embd, 0);
  payload.clear();
  AppendSection(&payload, "NETS", wide_nets);
  AppendSection(&payload, "EMBD", wide_embd);
  AppendSection(&payload, "NORM", norm);
  AppendSection(&payload, "WGTS", wgts);
  AppendSection(&payload, "INFO", info);
  EXPECT_EQ(ErrorOf(ModelFileAround(payload)),
            "GCN model file model.bin: malformed NORM section");
}

}  // namespace
}  // namespace colmap_gcn
