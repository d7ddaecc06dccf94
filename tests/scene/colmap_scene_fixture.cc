#include "scene/colmap_scene_fixture.h"

#include <sqlite3.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>

#include <random>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "test_utils.h"
#include "util/error.h"
#include "util/file.h"
#include "util/string.h"

namespace colmap_gcn {
namespace test {
namespace {

// Sum of upsampled noise at several scales plus random shapes: corners and
// blobs at every scale give SIFT distinctive features, and the fixed seed
// keeps runs reproducible.
cv::Mat MakeTexture(const int width, const int height, const uint32_t seed) {
  cv::RNG rng(seed);
  cv::Mat texture(height, width, CV_32FC3, cv::Scalar::all(0));
  for (const int cell : {64, 24, 8, 3}) {
    cv::Mat noise(height / cell + 2, width / cell + 2, CV_32FC3);
    rng.fill(noise, cv::RNG::UNIFORM, 0.0, 1.0);
    cv::Mat upsampled;
    cv::resize(
        noise, upsampled, cv::Size(width, height), 0, 0, cv::INTER_CUBIC);
    texture += upsampled * 64.0;
  }
  for (int i = 0; i < 250; ++i) {
    const cv::Point center(rng.uniform(0, width), rng.uniform(0, height));
    const cv::Scalar color(
        rng.uniform(0, 255), rng.uniform(0, 255), rng.uniform(0, 255));
    const int size = rng.uniform(4, 40);
    if (i % 2 == 0) {
      cv::circle(texture, center, size, color, cv::FILLED);
    } else {
      cv::rectangle(texture,
                    center,
                    center + cv::Point(size, size / 2 + 2),
                    color,
                    cv::FILLED);
    }
  }
  cv::Mat image;
  texture.convertTo(image, CV_8UC3);
  return image;
}

// Runs the SQL on an open connection; on failure closes it and throws.
void ExecOrThrow(sqlite3* db, const std::string& sql) {
  char* error = nullptr;
  if (sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error) != SQLITE_OK) {
    const std::string message = error != nullptr ? error : "?";
    sqlite3_free(error);
    sqlite3_close(db);
    ThrowError("test: SQL failed: ", message);
  }
}

}  // namespace

std::vector<std::string> WriteOverlappingTestImages(
    const std::string& image_dir,
    const int num_images,
    const int width,
    const int height,
    const int step_x,
    const int step_y,
    const uint32_t seed) {
  CreateDirIfNotExists(image_dir);
  const cv::Mat texture = MakeTexture(width + step_x * (num_images - 1),
                                      height + step_y * (num_images - 1),
                                      seed);
  std::vector<std::string> names;
  for (int i = 0; i < num_images; ++i) {
    // Names deliberately not zero-padded, and written in reverse order, so
    // that tests cannot rely on ids following name order.
    const int index = num_images - 1 - i;
    const std::string name = "view_" + std::to_string(index) + ".jpg";
    const cv::Rect roi(index * step_x, index * step_y, width, height);
    if (!cv::imwrite(JoinPaths(image_dir, name),
                     texture(roi),
                     {cv::IMWRITE_JPEG_QUALITY, 95})) {
      ThrowError("cannot write test image ", name);
    }
    names.push_back(name);
  }
  return names;
}

bool RunColmapFeaturesAndMatching(const std::string& colmap_exe,
                                  const std::string& image_dir,
                                  const std::string& database_path,
                                  std::string* log) {
  const std::string extract =
      ShellQuote(colmap_exe) + " feature_extractor --database_path " +
      ShellQuote(database_path) + " --image_path " + ShellQuote(image_dir) +
      " --ImageReader.single_camera 1 --SiftExtraction.use_gpu 0"
      " --SiftExtraction.num_threads 2"
      // No 2x upsampled octave and fewer features: ~1500 keypoints per
      // image in about a second instead of five.
      " --SiftExtraction.first_octave 0"
      " --SiftExtraction.max_num_features 1000";
  if (RunShell(extract, log) != 0) {
    return false;
  }
  const std::string match = ShellQuote(colmap_exe) +
                            " exhaustive_matcher --database_path " +
                            ShellQuote(database_path) +
                            " --SiftMatching.use_gpu 0"
                            " --SiftMatching.num_threads 2";
  return RunShell(match, log) == 0;
}

int64_t QuerySqlInt(const std::string& database_path, const std::string& sql) {
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(
          database_path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) !=
      SQLITE_OK) {
    sqlite3_close(db);
    ThrowError("test: cannot open ", database_path);
  }
  // Tests poll databases that gcn_matcher or COLMAP are writing: wait for
  // the writer's lock as COLMAP's own readers do instead of failing busy.
  sqlite3_busy_timeout(db, 30000);
  sqlite3_stmt* stmt = nullptr;
  int64_t value = 0;
  if (sqlite3_prepare_v2(db, sql.c_str(), -1, &stmt, nullptr) != SQLITE_OK) {
    const std::string message = sqlite3_errmsg(db);
    sqlite3_close(db);
    ThrowError("test: bad SQL '", sql, "': ", message);
  }
  const int step = sqlite3_step(stmt);
  if (step == SQLITE_ROW) {
    value = sqlite3_column_int64(stmt, 0);
  } else if (step != SQLITE_DONE) {
    const std::string message = sqlite3_errmsg(db);
    sqlite3_finalize(stmt);
    sqlite3_close(db);
    ThrowError("test: cannot run '", sql, "': ", message);
  }
  sqlite3_finalize(stmt);
  sqlite3_close(db);
  return value;
}

void ExecuteSql(const std::string& database_path, const std::string& sql) {
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(database_path.c_str(),
                      &db,
                      SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE,
                      nullptr) != SQLITE_OK) {
    sqlite3_close(db);
    ThrowError("test: cannot open ", database_path);
  }
  // Test databases need no durability; skipping fsync keeps setup fast.
  ExecOrThrow(db, "PRAGMA synchronous=OFF;" + sql);
  sqlite3_close(db);
}

void LeaveCommittedDataInWal(const std::string& database_path,
                             const std::string& sql,
                             const std::string& crashed_path) {
  namespace fs = std::filesystem;
  sqlite3* db = nullptr;
  if (sqlite3_open(database_path.c_str(), &db) != SQLITE_OK) {
    sqlite3_close(db);
    ThrowError("test: cannot open ", database_path);
  }
  ExecOrThrow(db,
              "PRAGMA journal_mode=WAL; PRAGMA wal_autocheckpoint=0;" + sql);
  for (const std::string suffix : {"", "-wal", "-shm"}) {
    fs::copy_file(database_path + suffix,
                  crashed_path + suffix,
                  fs::copy_options::overwrite_existing);
  }
  sqlite3_close(db);
  if (fs::file_size(crashed_path + "-wal") == 0) {
    ThrowError("test: nothing was left in ", crashed_path, "-wal");
  }
}

void LeaveHotJournal(const std::string& database_path, const std::string& sql) {
  // A child process, so that the writer really dies holding the
  // transaction: its locks go with it and only the journal stays.
  const pid_t pid = fork();
  if (pid < 0) ThrowError("test: fork failed");
  if (pid == 0) {
    sqlite3* db = nullptr;
    const std::string all_sql =
        "PRAGMA journal_mode=DELETE; PRAGMA cache_size=1; BEGIN;" + sql;
    const bool ok =
        sqlite3_open(database_path.c_str(), &db) == SQLITE_OK &&
        sqlite3_exec(db, all_sql.c_str(), nullptr, nullptr, nullptr) ==
            SQLITE_OK;
    _exit(ok ? 0 : 1);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    ThrowError("test: the crashing writer failed on ", database_path);
  }
  std::error_code ec;
  if (std::filesystem::file_size(database_path + "-journal", ec) == 0 || ec) {
    ThrowError("test: no hot journal was left beside ", database_path);
  }
}

}  // namespace test
}  // namespace colmap_gcn
