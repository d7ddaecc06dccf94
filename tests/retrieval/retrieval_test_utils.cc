#include "retrieval_test_utils.h"

#include <sqlite3.h>

#include <random>

#include "test_utils.h"
#include "util/error.h"

namespace colmap_gcn {
namespace test {
namespace {

// A 3.8 database with one SIMPLE_PINHOLE camera (f 500, principal point
// (320, 240)): COLMAP aborts on a camera without its parameters.
const std::string kSchema =
    std::string(kColmap38Schema) +
    "INSERT INTO cameras VALUES (1, 0, 640, 480, "
    "x'0000000000407F4000000000000074400000000000006E40', 0);\n";

void Check(int code, sqlite3* db) {
  if (code != SQLITE_OK && code != SQLITE_DONE && code != SQLITE_ROW) {
    ThrowError("sqlite: ", sqlite3_errmsg(db));
  }
}

void WriteBlob(sqlite3* db,
               const char* sql,
               image_t image_id,
               int rows,
               int cols,
               const void* data,
               int size) {
  sqlite3_stmt* stmt = nullptr;
  Check(sqlite3_prepare_v2(db, sql, -1, &stmt, nullptr), db);
  sqlite3_bind_int64(stmt, 1, image_id);
  sqlite3_bind_int64(stmt, 2, rows);
  sqlite3_bind_int64(stmt, 3, cols);
  sqlite3_bind_blob(stmt, 4, data, size, SQLITE_TRANSIENT);
  Check(sqlite3_step(stmt), db);
  sqlite3_finalize(stmt);
}

void WriteDescriptorsRow(sqlite3* db,
                         const image_t image_id,
                         const FeatureDescriptors& descriptors) {
  WriteBlob(db,
            "INSERT INTO descriptors VALUES (?, ?, ?, ?);",
            image_id,
            static_cast<int>(descriptors.rows()),
            static_cast<int>(descriptors.cols()),
            descriptors.data(),
            static_cast<int>(descriptors.size()));
}

}  // namespace

void CreateDescriptorDatabase(
    const std::string& path,
    const std::vector<std::pair<std::string, FeatureDescriptors>>& images) {
  sqlite3* db = nullptr;
  Check(sqlite3_open(path.c_str(), &db), db);
  Check(sqlite3_exec(db, kSchema.c_str(), nullptr, nullptr, nullptr), db);
  for (size_t i = 0; i < images.size(); ++i) {
    const image_t image_id = static_cast<image_t>(i + 1);
    const std::string sql =
        "INSERT INTO images (image_id, name, camera_id) "
        "VALUES (" +
        std::to_string(image_id) + ", '" + images[i].first + "', 1);";
    Check(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr), db);
    const FeatureDescriptors& descriptors = images[i].second;
    const std::vector<float> keypoints(descriptors.rows() * 2, 0.f);
    WriteBlob(db,
              "INSERT INTO keypoints VALUES (?, ?, ?, ?);",
              image_id,
              static_cast<int>(descriptors.rows()),
              2,
              keypoints.data(),
              static_cast<int>(keypoints.size() * sizeof(float)));
    WriteDescriptorsRow(db, image_id, descriptors);
  }
  sqlite3_close(db);
}

void UpdateDescriptors(const std::string& path,
                       image_t image_id,
                       const FeatureDescriptors& descriptors) {
  sqlite3* db = nullptr;
  Check(sqlite3_open(path.c_str(), &db), db);
  const std::string sql =
      "DELETE FROM descriptors WHERE image_id = " + std::to_string(image_id);
  Check(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr), db);
  WriteDescriptorsRow(db, image_id, descriptors);
  sqlite3_close(db);
}

FeatureDescriptors RandomDescriptors(int rows, int num_modes, uint32_t seed) {
  std::mt19937 rng(seed);
  std::mt19937 mode_rng(12345);  // the same prototypes for every image
  std::vector<std::vector<int>> modes(num_modes, std::vector<int>(128));
  for (auto& mode : modes) {
    for (int& value : mode) value = mode_rng() % 60;
  }
  FeatureDescriptors descriptors(rows, 128);
  for (int r = 0; r < rows; ++r) {
    const auto& mode = modes[rng() % num_modes];
    for (int c = 0; c < 128; ++c) {
      descriptors(r, c) =
          static_cast<uint8_t>(std::min<int>(255, mode[c] + rng() % 20));
    }
  }
  return descriptors;
}

void CreateRandomDescriptorDatabase(const std::string& path,
                                    const int num_images,
                                    const int rows,
                                    const int num_modes,
                                    const uint32_t first_seed,
                                    const std::string& prefix) {
  std::vector<std::pair<std::string, FeatureDescriptors>> images;
  for (int i = 0; i < num_images; ++i) {
    images.emplace_back(prefix + std::to_string(i) + ".jpg",
                        RandomDescriptors(rows, num_modes, first_seed + i));
  }
  CreateDescriptorDatabase(path, images);
}

}  // namespace test
}  // namespace colmap_gcn
