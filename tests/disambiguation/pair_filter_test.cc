// The look-alike filter on hand-made databases: cameras on a ring around an
// object whose back is its front turned by 180 degrees, inside a room that
// tells the sides apart.

#include "disambiguation/pair_filter.h"

#include <sqlite3.h>

#include <cmath>
#include <map>
#include <set>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "scene/colmap_scene_fixture.h"
#include "scene/two_view_geometry_store.h"
#include "test_utils.h"
#include "util/file.h"

namespace colmap_gcn {
namespace {

using test::ExecuteSql;
using test::kColmap38Schema;
using test::QuerySqlInt;

constexpr double kFocal = 500;
constexpr int kWidth = 640;
constexpr int kHeight = 480;

struct RingCamera {
  Eigen::Matrix3d R;  // world to camera
  Eigen::Vector3d t;
  Eigen::Vector3d center;
};

RingCamera LookAtOrigin(double angle, double height) {
  RingCamera camera;
  camera.center =
      Eigen::Vector3d(8 * std::cos(angle), 8 * std::sin(angle), height);
  const Eigen::Vector3d z =
      (Eigen::Vector3d(0, 0, 1) - camera.center).normalized();
  const Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d y = z.cross(x);
  camera.R.row(0) = x;
  camera.R.row(1) = y;
  camera.R.row(2) = z;
  camera.t = -camera.R * camera.center;
  return camera;
}

bool Project(const RingCamera& camera,
             const Eigen::Vector3d& X,
             Eigen::Vector2d* pixel) {
  const Eigen::Vector3d x = camera.R * X + camera.t;
  if (x.z() <= 0.1) return false;
  *pixel = Eigen::Vector2d(kFocal * x.x() / x.z() + kWidth / 2,
                           kFocal * x.y() / x.z() + kHeight / 2);
  return pixel->x() >= 0 && pixel->x() < kWidth && pixel->y() >= 0 &&
         pixel->y() < kHeight;
}

Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

void Insert(sqlite3* db,
            const std::string& sql,
            const std::vector<std::pair<const void*, int>>& blobs) {
  sqlite3_stmt* stmt = nullptr;
  ASSERT_EQ(sqlite3_prepare_v2(db, sql.c_str(), -1, &stmt, nullptr), SQLITE_OK)
      << sqlite3_errmsg(db);
  for (size_t b = 0; b < blobs.size(); ++b) {
    sqlite3_bind_blob(stmt,
                      static_cast<int>(b + 1),
                      blobs[b].first,
                      blobs[b].second,
                      SQLITE_TRANSIENT);
  }
  ASSERT_EQ(sqlite3_step(stmt), SQLITE_DONE) << sqlite3_errmsg(db);
  sqlite3_finalize(stmt);
}

// n cameras; real pairs up to `reach` steps apart see the room and the face
// in front of them; each camera also "verifies" with the cameras facing the
// other face (n/2 steps away), through the print alone. Returns the
// look-alike pairs' image names. The pairs are verified calibrated
// (config 2, E), as COLMAP does only when both focal lengths are trusted
// (trusted_focal: prior_focal_length 1). With stored_focal_factor != 1 the
// cameras table holds the focal length times it (an EXIF focal length of a
// cropped photo) and each pair also its F: E is then what COLMAP estimates
// with the stored focal length, K_stored^T F K_stored.
std::set<std::pair<std::string, std::string>> WriteRingDatabase(
    const std::string& path,
    int n,
    int reach,
    bool trusted_focal = true,
    double stored_focal_factor = 1.0) {
  ExecuteSql(path, kColmap38Schema);
  std::vector<Eigen::Vector3d> print;  // front face, y = -1
  for (int k = 0; k < 60; ++k) {
    print.emplace_back(-1.5 + 3.0 * ((k * 37) % 60) / 60.0,
                       -1.0,
                       -0.5 + 3.0 * ((k * 11) % 60) / 60.0);
  }
  std::vector<Eigen::Vector3d> room;
  for (int k = 0; k < 720; ++k) {
    const double a = 2 * M_PI * k / 720.0;
    room.emplace_back(20 * std::cos(a),
                      20 * std::sin(a),
                      -3.0 + 8.0 * ((k * 7) % 720) / 720.0);
  }
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  // Points: print (front), turned print (back), room.
  std::vector<Eigen::Vector3d> points = print;
  for (const Eigen::Vector3d& p : print) points.push_back(turn * p);
  points.insert(points.end(), room.begin(), room.end());
  const int num_print = static_cast<int>(print.size());

  sqlite3* db = nullptr;
  EXPECT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  std::vector<RingCamera> cameras;
  std::vector<std::map<int, int>> keypoint_of(n);  // point -> keypoint
  const double params[4] = {kFocal * stored_focal_factor,
                            kFocal * stored_focal_factor,
                            kWidth / 2.0,
                            kHeight / 2.0};
  Eigen::Matrix3d K;
  K << kFocal, 0, kWidth / 2.0, 0, kFocal, kHeight / 2.0, 0, 0, 1;
  Eigen::Matrix3d K_stored = K;
  K_stored.topLeftCorner<2, 2>() *= stored_focal_factor;
  for (int i = 0; i < n; ++i) {
    // Uneven spacing and heights: no two cameras see the print from the
    // same place (a look-alike pair with no baseline has no rotation).
    cameras.push_back(LookAtOrigin(2 * M_PI * (i + 0.5 + 0.1 * (i % 3)) / n,
                                   0.8 + 0.2 * (i % 4)));
    std::vector<float> keypoints;
    for (size_t p = 0; p < points.size(); ++p) {
      // A face point shows only to the cameras in front of it.
      if (static_cast<int>(p) < 2 * num_print &&
          points[p].y() * cameras[i].center.y() <= 0) {
        continue;
      }
      Eigen::Vector2d pixel;
      if (!Project(cameras[i], points[p], &pixel)) continue;
      keypoint_of[i][static_cast<int>(p)] =
          static_cast<int>(keypoints.size() / 2);
      keypoints.push_back(static_cast<float>(pixel.x()));
      keypoints.push_back(static_cast<float>(pixel.y()));
    }
    const std::string id = std::to_string(i + 1);
    Insert(db,
           "INSERT INTO cameras VALUES (" + id + ", 1, 640, 480, ?, " +
               (trusted_focal ? "1" : "0") + ")",
           {{params, 32}});
    Insert(db,
           "INSERT INTO images (image_id, name, camera_id) VALUES (" + id +
               ", 'img" + (i < 10 ? "0" : "") + std::to_string(i) + ".jpg', " +
               id + ")",
           {});
    Insert(db,
           "INSERT INTO keypoints VALUES (" + id + ", " +
               std::to_string(keypoints.size() / 2) + ", 2, ?)",
           {{keypoints.data(), static_cast<int>(keypoints.size() * 4)}});
  }
  std::set<std::pair<std::string, std::string>> lookalikes;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      const int steps = std::min(j - i, n - (j - i));
      const bool fake = steps == n / 2;
      if (steps > reach && !fake) continue;
      // A look-alike pair matches a print point in i with its turned twin in
      // j: as if camera j stood turned by 180 degrees.
      RingCamera other = cameras[j];
      if (fake) other.R = other.R * turn;
      std::vector<uint32_t> inliers;
      for (const auto& [point, k1] : keypoint_of[i]) {
        int twin = point;
        if (fake) {
          if (point >= 2 * num_print) continue;
          twin = point < num_print ? point + num_print : point - num_print;
        }
        const auto k2 = keypoint_of[j].find(twin);
        if (k2 == keypoint_of[j].end()) continue;
        inliers.push_back(k1);
        inliers.push_back(k2->second);
      }
      if (inliers.size() < 30) continue;
      const Eigen::Matrix3d R = other.R * cameras[i].R.transpose();
      const Eigen::Vector3d t = other.t - R * cameras[i].t;
      Eigen::Matrix<double, 3, 3, Eigen::RowMajor> E = Skew(t) * R;
      const image_pair_t pair_id =
          static_cast<image_pair_t>(i + 1) * 2147483647 + (j + 1);
      if (stored_focal_factor == 1.0) {
        Insert(db,
               "INSERT INTO two_view_geometries (pair_id, rows, cols, data, "
               "config, E) VALUES (" +
                   std::to_string(pair_id) + ", " +
                   std::to_string(inliers.size() / 2) + ", 2, ?, 2, ?)",
               {{inliers.data(), static_cast<int>(inliers.size() * 4)},
                {E.data(), 72}});
      } else {
        const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> F =
            K.transpose().inverse() * E * K.inverse();
        E = K_stored.transpose() * F * K_stored;
        Insert(db,
               "INSERT INTO two_view_geometries (pair_id, rows, cols, data, "
               "config, F, E) VALUES (" +
                   std::to_string(pair_id) + ", " +
                   std::to_string(inliers.size() / 2) + ", 2, ?, 2, ?, ?)",
               {{inliers.data(), static_cast<int>(inliers.size() * 4)},
                {F.data(), 72},
                {E.data(), 72}});
      }
      if (fake) {
        lookalikes.emplace(
            "img" + std::string(i < 10 ? "0" : "") + std::to_string(i) + ".jpg",
            "img" + std::string(j < 10 ? "0" : "") + std::to_string(j) +
                ".jpg");
      }
    }
  }
  sqlite3_close(db);
  return lookalikes;
}

std::set<std::pair<std::string, std::string>> Rejected(
    const PairFilterReport& report) {
  std::set<std::pair<std::string, std::string>> pairs;
  for (const PairFilterEntry& entry : report.entries) {
    if (entry.decision.Rejected()) pairs.emplace(entry.name1, entry.name2);
  }
  return pairs;
}

PairFilterReport FilterSingleThreaded(const std::string& path) {
  PairFilterOptions options;
  options.num_threads = 1;
  return FindLookalikePairs(TwoViewGeometryStore(path), options);
}

TEST(PairFilter, FindsTheLookalikePairsOfAPrintedRing) {
  TemporaryDirectory dir("colmap_gcn_pair_filter");
  const std::string path = JoinPaths(dir.Path(), "ring.db");
  const auto lookalikes = WriteRingDatabase(path, 20, 3);
  ASSERT_EQ(lookalikes.size(), 10u);
  const PairFilterReport report = FilterSingleThreaded(path);
  EXPECT_EQ(report.num_verified_pairs, 70u);
  EXPECT_EQ(report.num_without_rotation, 0u);
  EXPECT_EQ(Rejected(report), lookalikes);
  for (const PairFilterEntry& entry : report.entries) {
    if (!entry.decision.Rejected() && !entry.decision.in_tree) {
      EXPECT_LT(entry.decision.rotation_error, 1.0);
    }
  }
}

// The same ring with focal lengths that are COLMAP's guesses and no F to
// calibrate them (every pair verified calibrated): no rotation can be
// trusted, so nothing is judged and nothing hidden.
TEST(PairFilter, GuessedFocalLengthsThatCannotBeCalibratedAreNotJudged) {
  TemporaryDirectory dir("colmap_gcn_pair_filter");
  const std::string path = JoinPaths(dir.Path(), "ring.db");
  WriteRingDatabase(path, 20, 3, /*trusted_focal=*/false);
  const PairFilterReport report = FilterSingleThreaded(path);
  EXPECT_EQ(report.num_verified_pairs, 70u);
  EXPECT_EQ(report.num_guessed_cameras, 20u);
  EXPECT_EQ(report.num_uncalibrated_cameras, 20u);
  EXPECT_EQ(report.num_without_rotation, 70u);
  EXPECT_TRUE(Rejected(report).empty());
}

TEST(PairFilter, DecisionsDoNotDependOnTheThreadCount) {
  TemporaryDirectory dir("colmap_gcn_pair_filter");
  const std::string path = JoinPaths(dir.Path(), "ring.db");
  WriteRingDatabase(path, 24, 3);
  const TwoViewGeometryStore database(path);
  PairFilterOptions options;
  options.num_threads = 1;
  const PairFilterReport one = FindLookalikePairs(database, options);
  options.num_threads = 4;
  const PairFilterReport four = FindLookalikePairs(database, options);
  ASSERT_EQ(one.entries.size(), four.entries.size());
  for (size_t e = 0; e < one.entries.size(); ++e) {
    EXPECT_EQ(one.entries[e].pair_id, four.entries[e].pair_id);
    EXPECT_EQ(one.entries[e].decision.reason, four.entries[e].decision.reason);
    EXPECT_EQ(one.entries[e].decision.rotation_error,
              four.entries[e].decision.rotation_error);
  }
}

TEST(PairFilter, HiddenPairsLeaveTheMapperAndComeBackByteForByte) {
  TemporaryDirectory dir("colmap_gcn_pair_filter");
  const std::string path = JoinPaths(dir.Path(), "ring.db");
  const auto lookalikes = WriteRingDatabase(path, 20, 3);
  const char* const kRows =
      "SELECT COUNT(*) FROM two_view_geometries WHERE config = 2 AND rows > 0";
  const char* const kChecksum =
      "SELECT SUM(pair_id * length(data) + rows + config) FROM "
      "two_view_geometries";
  const int64_t checksum = QuerySqlInt(path, kChecksum);
  ASSERT_EQ(QuerySqlInt(path, kRows), 70);

  PairFilterOptions options;
  const PairFilterReport report = FilterLookalikePairs(path, options);
  EXPECT_EQ(report.num_rejected, lookalikes.size());
  EXPECT_EQ(QuerySqlInt(path, kRows), 60);
  EXPECT_EQ(QuerySqlInt(path, "SELECT COUNT(*) FROM two_view_geometries"), 70);
  EXPECT_EQ(QuerySqlInt(path,
                        "SELECT COUNT(*) FROM gcn_lookalike_pairs WHERE "
                        "gcn_reason = 'rotation_loop'"),
            10);
  {
    const TwoViewGeometryStore database(path);
    EXPECT_EQ(database.ReadHiddenPairs().size(), 10u);
    // Hidden pairs are no longer verified: a second run finds nothing new.
    const PairFilterReport again = FindLookalikePairs(database, options);
    EXPECT_EQ(again.num_verified_pairs, 60u);
    EXPECT_EQ(again.num_rejected, 0u);
    EXPECT_EQ(again.num_already_hidden, 10u);
  }
  EXPECT_FALSE(ExistsFile(path + ".gcn-partial"));

  EXPECT_EQ(RestoreLookalikePairs(path), 10u);
  EXPECT_EQ(QuerySqlInt(path, kRows), 70);
  EXPECT_EQ(QuerySqlInt(path, kChecksum), checksum);
  EXPECT_EQ(QuerySqlInt(path,
                        "SELECT COUNT(*) FROM sqlite_master WHERE name "
                        "= 'gcn_lookalike_pairs'"),
            0);
  EXPECT_EQ(RestoreLookalikePairs(path), 0u);
}

// The ring photographed with a trusted focal length 1.5 x too short (the
// EXIF focal length of a cropped photo): every rotation is off and the
// chains drift; the loop check finds the factor, and with it the filter
// rejects the look-alike pairs and only them.
TEST(PairFilter, AWrongTrustedFocalLengthIsCheckedAgainstTheLoops) {
  TemporaryDirectory dir("colmap_gcn_pair_filter");
  const std::string path = JoinPaths(dir.Path(), "ring.db");
  const auto lookalikes =
      WriteRingDatabase(path, 20, 3, /*trusted_focal=*/true, 1 / 1.5);
  const TwoViewGeometryStore database(path);
  PairFilterOptions options;
  options.num_threads = 1;
  options.check_trusted_focal = false;
  const PairFilterReport unchecked = FindLookalikePairs(database, options);
  options.check_trusted_focal = true;
  const PairFilterReport checked = FindLookalikePairs(database, options);
  EXPECT_EQ(unchecked.trusted_focal_scale, 1.0);
  EXPECT_GT(unchecked.num_rejected, lookalikes.size());
  EXPECT_LT(checked.focal_check_failures_after,
            checked.focal_check_failures_before);
  EXPECT_NEAR(checked.trusted_focal_scale, 1.5, 0.1);
  EXPECT_EQ(Rejected(checked), lookalikes);
  // The check decides the same with any thread count.
  options.num_threads = 4;
  const PairFilterReport threaded = FindLookalikePairs(database, options);
  EXPECT_EQ(threaded.trusted_focal_scale, checked.trusted_focal_scale);
  EXPECT_EQ(Rejected(threaded), Rejected(checked));
}

TEST(PairFilter, AnOrdinaryRingLosesNothing) {
  TemporaryDirectory dir("colmap_gcn_pair_filter");
  const std::string path = JoinPaths(dir.Path(), "ring.db");
  WriteRingDatabase(path, 20, 3);
  // Without the look-alike pairs.
  ExecuteSql(path,
             "DELETE FROM two_view_geometries WHERE (pair_id % 2147483647) - "
             "(pair_id / 2147483647) = 10");
  const TwoViewGeometryStore database(path);
  const PairFilterReport report =
      FindLookalikePairs(database, PairFilterOptions());
  EXPECT_EQ(report.num_verified_pairs, 60u);
  EXPECT_EQ(report.num_rejected, 0u);
}

}  // namespace
}  // namespace colmap_gcn
