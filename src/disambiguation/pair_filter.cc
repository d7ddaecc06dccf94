#include "disambiguation/pair_filter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "disambiguation/inlier_grid.h"
#include "disambiguation/relative_pose.h"
#include "scene/database_working_copy.h"
#include "util/error.h"
#include "util/file.h"
#include "util/interrupt.h"
#include "util/logging.h"
#include "util/option_check.h"
#include "util/threading.h"
#include "util/timer.h"

namespace colmap_gcn {
namespace {

// Strong pairs the loop test rejects.
size_t LoopFailures(const std::vector<LookalikeDecision>& decisions) {
  return std::count_if(decisions.begin(),
                       decisions.end(),
                       [](const LookalikeDecision& decision) {
                         return decision.reason ==
                                LookalikeReason::kRotationLoop;
                       });
}

// The focal length check: the loop test must fail at least this many
// strong pairs for it to run; the factors tried are 2^(k/3), |k| <= 3
// (0.5-2), then the best one times 2^(+-1/6) unless it is 0.5 or 2 (the
// check declines); a factor is taken only if it leaves at most this share
// of the failures; the trials recover rotations from this many inlier rays
// (cheirality needs few: verified inliers).
constexpr size_t kFocalCheckMinFailures = 10;
constexpr double kFocalCheckMaxShare = 0.75;
constexpr int kFocalCheckRays = 10;

// Trusted focal lengths (EXIF, the user) checked against the loops of the
// verified graph. A photo cropped or resized after its EXIF was written
// keeps a focal length off by the crop factor; every rotation is then off
// a little, and chains around a turntable drift by tens of degrees
// (bm-mary-rose: 1.52 x too short, docs/lookalike.md). Every trusted
// camera's focal length is scaled by each factor in turn (rotations from F,
// the strong pairs only), and the factor under which the loop test fails
// the fewest strong pairs replaces it if it cuts them by a quarter and the
// full measurement agrees: a look-alike pair fails under any factor, a real
// pair only under a wrong one. Ties keep the factor nearest 1.
void CheckTrustedFocalLengths(const std::vector<VerifiedTwoViewGeometry>& pairs,
                              const std::vector<bool>& judged,
                              const std::map<camera_t, bool>& trusted_focal,
                              const PairFilterOptions& options,
                              PairEvidenceCameras* evidence,
                              std::vector<ViewGraphEdge>* edges,
                              std::vector<PairRotations>* rotations,
                              std::vector<LookalikeDecision>* decisions,
                              PairFilterReport* report) {
  const int num_images = static_cast<int>(evidence->image_cameras.size());
  const size_t failures = LoopFailures(*decisions);
  report->focal_check_failures_before = failures;
  report->focal_check_failures_after = failures;
  std::set<camera_t> checked;
  for (const auto& [camera, trusted] : trusted_focal) {
    if (trusted) checked.insert(camera);
  }
  if (failures < kFocalCheckMinFailures || checked.empty()) return;
  std::vector<bool> strong(pairs.size(), false);
  for (size_t p = 0; p < pairs.size(); ++p) {
    const ViewGraphEdge& edge = (*edges)[p];
    strong[p] = judged[p] &&
                edge.num_inliers >= options.decision.min_evidence_inliers &&
                (checked.count(evidence->image_cameras[edge.image1]) > 0 ||
                 checked.count(evidence->image_cameras[edge.image2]) > 0);
  }
  const auto scaled = [&](const double factor) {
    PairEvidenceCameras trial = *evidence;
    for (const camera_t camera : checked) {
      trial.intrinsics[camera].fx *= factor;
      trial.intrinsics[camera].fy *= factor;
      trial.use_colmap_E[camera] = false;
    }
    return trial;
  };
  double best_factor = 1;
  size_t best = failures;
  const auto try_factor = [&](const double factor) {
    std::vector<ViewGraphEdge> trial_edges = *edges;
    std::vector<PairRotations> trial_rotations = *rotations;
    MeasurePairEvidence(pairs,
                        scaled(factor),
                        strong,
                        kFocalCheckRays,
                        options.num_threads,
                        &trial_edges,
                        &trial_rotations);
    const size_t trial_failures = LoopFailures(
        DecideLookalikePairs(num_images, trial_edges, options.decision));
    if (trial_failures < best) {
      best = trial_failures;
      best_factor = factor;
    }
  };
  for (const int k : {1, -1, 2, -2, 3, -3}) try_factor(std::pow(2.0, k / 3.0));
  const double coarse = best_factor;
  // The fewest failures at an end of the range: no minimum inside it, a
  // sign that something else than the focal length drives them (a static
  // background behind a turntable, bm-ethiopian-head).
  if (coarse == 0.5 || coarse == 2.0) return;
  for (const int k : {1, -1}) try_factor(coarse * std::pow(2.0, k / 6.0));
  if (best > kFocalCheckMaxShare * failures) return;
  // Confirmed on every pair with all its rays, or the focal lengths stay.
  PairEvidenceCameras adopted = scaled(best_factor);
  std::vector<ViewGraphEdge> adopted_edges = *edges;
  std::vector<PairRotations> adopted_rotations = *rotations;
  MeasurePairEvidence(pairs,
                      adopted,
                      judged,
                      options.max_rays_per_pair,
                      options.num_threads,
                      &adopted_edges,
                      &adopted_rotations);
  std::vector<LookalikeDecision> adopted_decisions =
      DecideLookalikePairs(num_images, adopted_edges, options.decision);
  if (LoopFailures(adopted_decisions) > kFocalCheckMaxShare * failures) {
    return;
  }
  *evidence = std::move(adopted);
  *edges = std::move(adopted_edges);
  *rotations = std::move(adopted_rotations);
  *decisions = std::move(adopted_decisions);
  report->trusted_focal_scale = best_factor;
  report->focal_check_failures_after = LoopFailures(*decisions);
}

// Replaces the intrinsics of the cameras without a trusted focal length by
// self-calibrated ones (focal_calibration.h), from the F of the pairs
// verified calibrated or uncalibrated (planar and panoramic F say nothing
// about the focal length). Marks in *rotation_trusted the cameras whose
// focal length the calibration fixed as well.
void SelfCalibrateCameras(const std::vector<DatabaseImage>& images,
                          const std::map<image_t, int>& index,
                          const std::vector<VerifiedTwoViewGeometry>& pairs,
                          const std::map<camera_t, bool>& trusted_focal,
                          const FocalCalibrationOptions& options,
                          std::map<camera_t, PinholeIntrinsics>* cameras,
                          std::map<camera_t, bool>* rotation_trusted,
                          PairFilterReport* report) {
  std::vector<camera_t> ids;
  std::map<camera_t, int> camera_index;
  std::vector<PinholeIntrinsics> intrinsics;
  std::vector<bool> trusted;
  for (const auto& [id, camera] : *cameras) {
    camera_index[id] = static_cast<int>(ids.size());
    ids.push_back(id);
    intrinsics.push_back(camera);
    trusted.push_back(trusted_focal.at(id));
    report->num_guessed_cameras += !trusted.back();
  }
  if (report->num_guessed_cameras == 0) return;
  std::vector<int> num_images(ids.size(), 0);
  for (const DatabaseImage& image : images) {
    ++num_images[camera_index.at(image.camera_id)];
  }
  std::vector<FundamentalPair> fundamentals;
  for (const VerifiedTwoViewGeometry& pair : pairs) {
    if ((pair.config != 2 && pair.config != 3) || pair.F.norm() < 1e-12) {
      continue;
    }
    FundamentalPair f;
    f.camera1 = camera_index.at(images[index.at(pair.image_id1)].camera_id);
    f.camera2 = camera_index.at(images[index.at(pair.image_id2)].camera_id);
    f.F = pair.F;
    fundamentals.push_back(f);
  }
  const FocalCalibrationResult result = SelfCalibrateFocalLengths(
      intrinsics, trusted, num_images, fundamentals, options);
  std::vector<double> guessed_scales;
  for (size_t c = 0; c < ids.size(); ++c) {
    (*cameras)[ids[c]] = result.cameras[c];
    if (!trusted[c]) {
      (*rotation_trusted)[ids[c]] = result.calibrated[c];
      guessed_scales.push_back(result.scales[c]);
      report->num_uncalibrated_cameras += !result.calibrated[c];
    }
  }
  std::sort(guessed_scales.begin(), guessed_scales.end());
  report->median_focal_scale = guessed_scales[guessed_scales.size() / 2];
  report->focal_cost_before = result.cost_before;
  report->focal_cost_after = result.cost_after;
}

std::string CsvRotation(const bool has, const Eigen::Matrix3d& R) {
  if (!has) return ",,,";
  const Eigen::Quaterniond q(R);
  std::ostringstream out;
  out << q.w() << ',' << q.x() << ',' << q.y() << ',' << q.z();
  return out.str();
}

std::string CsvLine(const PairFilterEntry& entry) {
  std::ostringstream line;
  line << entry.name1 << ',' << entry.name2 << ',' << entry.num_inliers << ','
       << entry.covered_cells << ',' << entry.strength << ','
       << entry.decision.rotation_error << ',' << entry.decision.view_parallax
       << ',' << entry.decision.backbone_hops << ','
       << entry.decision.in_backbone << ',' << entry.decision.in_tree << ','
       << LookalikeReasonName(entry.decision.reason) << ',' << entry.config
       << ','
       << CsvRotation(entry.rotations.has_essential, entry.rotations.essential)
       << ',' << entry.rotations.homography.size();
  for (size_t i = 0; i < 2; ++i) {
    line << ','
         << CsvRotation(i < entry.rotations.homography.size(),
                        i < entry.rotations.homography.size()
                            ? entry.rotations.homography[i]
                            : Eigen::Matrix3d::Identity());
  }
  line << ',' << entry.decision.path_rotation << '\n';
  return line.str();
}

// One line per verified pair: its evidence and decision.
void WritePairsCsv(const PairFilterReport& report, const std::string& path) {
  std::string csv =
      "name1,name2,num_inliers,covered_cells,distinctive_inliers,rotation_"
      "error,view_parallax,backbone_hops,in_backbone,"
      "in_tree,decision,config,ew,ex,ey,ez,num_h,h1w,h1x,h1y,h1z,h2w,h2x,h2y,"
      "h2z,path_rotation\n";
  for (const PairFilterEntry& entry : report.entries) csv += CsvLine(entry);
  WriteFileAtomically(path, csv);
}

}  // namespace

void PairFilterOptions::Check() const {
  decision.Check();
  focal_calibration.Check();
  CHECK_OPTION_GE(min_num_inliers, 0);
  CHECK_OPTION_GE(max_rays_per_pair, 5);
  CHECK_OPTION_INTERVAL(distinctive_share, 0.0, true, 1.0, true);
  CHECK_OPTION_NUM_THREADS(num_threads);
}

PairFilterReport FindLookalikePairs(const TwoViewGeometryStore& database,
                                    const PairFilterOptions& options) {
  return FindLookalikePairs(
      database,
      database.ReadVerifiedTwoViewGeometries(options.min_num_inliers),
      options);
}

PairFilterReport FindLookalikePairs(
    const TwoViewGeometryStore& database,
    const std::vector<VerifiedTwoViewGeometry>& verified_pairs,
    const PairFilterOptions& options) {
  options.Check();
  const Timer timer;
  PairFilterReport report;
  report.database_path = database.Path();
  const std::vector<DatabaseImage> images = database.ReadAllImages();
  report.num_images = images.size();
  std::map<camera_t, PinholeIntrinsics> cameras;
  std::map<camera_t, Eigen::Vector2d> sizes;
  std::map<camera_t, bool> trusted_focal;
  for (const DatabaseCamera& camera : database.ReadAllCameras()) {
    cameras[camera.camera_id] = IntrinsicsOfCamera(camera);
    trusted_focal[camera.camera_id] =
        camera.has_prior_focal_length || !options.self_calibrate_focal;
    sizes[camera.camera_id] =
        Eigen::Vector2d(std::max<double>(1.0, camera.width),
                        std::max<double>(1.0, camera.height));
  }
  std::map<image_t, int> index;
  for (size_t i = 0; i < images.size(); ++i) {
    index[images[i].image_id] = static_cast<int>(i);
    if (cameras.count(images[i].camera_id) == 0) {
      ThrowError("database ",
                 database.Path(),
                 ": image ",
                 images[i].name,
                 " has camera ",
                 images[i].camera_id,
                 ", which is not in the cameras table");
    }
  }
  // Verified by the same rule as the database's rows, ordered by pair id.
  std::vector<VerifiedTwoViewGeometry> pairs;
  for (const VerifiedTwoViewGeometry& pair : verified_pairs) {
    if (IsVerifiedTwoViewGeometry(
            pair.config, pair.inliers.rows(), options.min_num_inliers)) {
      pairs.push_back(pair);
    }
  }
  std::sort(
      pairs.begin(),
      pairs.end(),
      [](const VerifiedTwoViewGeometry& a, const VerifiedTwoViewGeometry& b) {
        return a.pair_id < b.pair_id;
      });
  report.num_verified_pairs = pairs.size();
  report.num_already_hidden = database.ReadHiddenPairs().size();

  // Keypoint positions of the images in verified pairs (read once).
  std::vector<KeypointPositions> keypoints(images.size());
  std::vector<bool> needed(images.size(), false);
  for (const VerifiedTwoViewGeometry& pair : pairs) {
    for (const image_t id : {pair.image_id1, pair.image_id2}) {
      if (index.count(id) == 0) {
        ThrowError("database ",
                   database.Path(),
                   ": pair ",
                   pair.pair_id,
                   " names image ",
                   id,
                   ", which is not in the images table");
      }
      needed[index[id]] = true;
    }
  }
  for (size_t i = 0; i < images.size(); ++i) {
    if (needed[i])
      keypoints[i] = database.ReadKeypointPositions(images[i].image_id);
  }

  // Rotations are judged only between cameras whose focal length is
  // trusted or self-calibrated: with a guess they are wrong by tens of
  // degrees, and the loop test then hides real pairs (figurine and fox:
  // docs/lookalike.md). Such pairs are kept, like pairs without a rotation.
  std::map<camera_t, bool> rotation_trusted = trusted_focal;
  if (options.self_calibrate_focal) {
    SelfCalibrateCameras(images,
                         index,
                         pairs,
                         trusted_focal,
                         options.focal_calibration,
                         &cameras,
                         &rotation_trusted,
                         &report);
  }

  std::vector<ViewGraphEdge> edges(pairs.size());
  std::vector<PairRotations> rotations(pairs.size());
  std::vector<PairInlierCells> cells(pairs.size());
  PairEvidenceCameras evidence;
  evidence.keypoints = &keypoints;
  evidence.intrinsics = cameras;
  evidence.use_colmap_E = trusted_focal;
  std::vector<bool> judged(pairs.size(), false);
  for (const DatabaseImage& image : images) {
    evidence.image_cameras.push_back(image.camera_id);
  }
  ProgressLogger progress(pairs.size(), "look-alike filter", "pairs");
  ParallelFor(
      0, static_cast<int>(pairs.size()), options.num_threads, [&](int p) {
        const VerifiedTwoViewGeometry& pair = pairs[p];
        ViewGraphEdge& edge = edges[p];
        edge.pair_id = pair.pair_id;
        edge.image1 = index.at(pair.image_id1);
        edge.image2 = index.at(pair.image_id2);
        edge.num_inliers = static_cast<int>(pair.inliers.rows());
        const camera_t camera1 = images[edge.image1].camera_id;
        const camera_t camera2 = images[edge.image2].camera_id;
        cells[p] = ComputeInlierCells(pair,
                                      keypoints[edge.image1],
                                      keypoints[edge.image2],
                                      sizes.at(camera1),
                                      sizes.at(camera2));
        progress.Increment();
      });
  // Rotations are measured between cameras whose focal length is trusted
  // or self-calibrated (a vector<bool> is not written in parallel).
  for (size_t p = 0; p < pairs.size(); ++p) {
    judged[p] = rotation_trusted.at(images[edges[p].image1].camera_id) &&
                rotation_trusted.at(images[edges[p].image2].camera_id);
  }
  MeasurePairEvidence(pairs,
                      evidence,
                      judged,
                      options.max_rays_per_pair,
                      options.num_threads,
                      &edges,
                      &rotations);
  // The edges' strength: overlap where few of each image's partners reach
  // (inlier_grid.h), so that the backbone follows the real neighbours of an
  // image rather than the partners that match only its duplicate structure.
  InlierCellReach reach(static_cast<int>(images.size()));
  for (size_t p = 0; p < pairs.size(); ++p) {
    reach.AddPair(edges[p].image1, edges[p].image2, cells[p]);
  }
  // Only pairs strong enough to be judged rank by it: a weak pair's few
  // inliers at the edge of the view must not outrank a strong neighbour.
  for (size_t p = 0; p < pairs.size(); ++p) {
    edges[p].coverage = CoveredCells(cells[p]);
    if (edges[p].num_inliers >= options.decision.min_evidence_inliers) {
      edges[p].strength = reach.DistinctiveInliers(edges[p].image1,
                                                   edges[p].image2,
                                                   cells[p],
                                                   options.distinctive_share);
    }
  }
  std::vector<LookalikeDecision> decisions = DecideLookalikePairs(
      static_cast<int>(images.size()), edges, options.decision);
  if (options.check_trusted_focal) {
    CheckTrustedFocalLengths(pairs,
                             judged,
                             trusted_focal,
                             options,
                             &evidence,
                             &edges,
                             &rotations,
                             &decisions,
                             &report);
  }
  for (size_t p = 0; p < pairs.size(); ++p) {
    PairFilterEntry entry;
    entry.pair_id = pairs[p].pair_id;
    entry.name1 = images[edges[p].image1].name;
    entry.name2 = images[edges[p].image2].name;
    entry.num_inliers = edges[p].num_inliers;
    entry.covered_cells = edges[p].coverage;
    entry.strength = edges[p].strength;
    entry.config = pairs[p].config;
    entry.rotations = rotations[p];
    entry.decision = decisions[p];
    report.num_without_rotation +=
        !edges[p].has_rotation && edges[p].alternatives.empty();
    report.num_rejected += decisions[p].Rejected();
    report.entries.push_back(std::move(entry));
  }
  if (!options.pairs_csv_path.empty()) {
    WritePairsCsv(report, options.pairs_csv_path);
  }
  report.seconds = timer.ElapsedSeconds();
  return report;
}

std::vector<image_pair_t> RejectedPairIds(const PairFilterReport& report) {
  std::vector<image_pair_t> ids;
  for (const PairFilterEntry& entry : report.entries) {
    if (entry.decision.Rejected()) ids.push_back(entry.pair_id);
  }
  std::sort(ids.begin(), ids.end());
  return ids;
}

PairFilterReport FilterLookalikePairs(const std::string& database_path,
                                      const PairFilterOptions& options) {
  options.Check();
  const Timer timer;
  PairFilterReport report;
  {
    const TwoViewGeometryStore database(database_path);
    report = FindLookalikePairs(database, options);
  }
  report.database_path = database_path;
  if (report.num_rejected > 0) {
    std::vector<HiddenTwoViewGeometry> hidden;
    for (const PairFilterEntry& entry : report.entries) {
      if (!entry.decision.Rejected()) continue;
      HiddenTwoViewGeometry pair;
      pair.pair_id = entry.pair_id;
      pair.reason = LookalikeReasonName(entry.decision.reason);
      // The degrees that decided it.
      pair.score = entry.decision.reason == LookalikeReason::kViewParallax
                       ? entry.decision.view_parallax
                       : entry.decision.rotation_error;
      hidden.push_back(pair);
    }
    DatabaseWorkingCopy working_copy(database_path);
    working_copy.MarkWritten();
    {
      TwoViewGeometryStore copy(working_copy.Path(),
                                Database::Mode::kReadWrite);
      copy.HidePairs(hidden);
    }
    const CriticalSection critical;
    working_copy.Commit();
  }
  report.seconds = timer.ElapsedSeconds();
  return report;
}

size_t RestoreLookalikePairs(const std::string& database_path) {
  {
    const TwoViewGeometryStore database(database_path);
    if (database.ReadHiddenPairs().empty()) return 0;
  }
  DatabaseWorkingCopy working_copy(database_path);
  working_copy.MarkWritten();
  size_t num_restored = 0;
  {
    TwoViewGeometryStore copy(working_copy.Path(), Database::Mode::kReadWrite);
    num_restored = copy.RestoreHiddenPairs();
  }
  const CriticalSection critical;
  working_copy.Commit();
  return num_restored;
}

void PrintPairFilterReport(const PairFilterReport& report,
                           const bool list_pairs) {
  std::map<std::string, size_t> by_reason;
  for (const PairFilterEntry& entry : report.entries) {
    if (entry.decision.Rejected()) {
      ++by_reason[LookalikeReasonName(entry.decision.reason)];
    }
  }
  std::printf(
      "look-alike filter: %zu images, %zu verified pairs, %zu hidden as "
      "look-alikes (%zu hidden earlier), %zu without a relative rotation, "
      "%.2f s\n",
      report.num_images,
      report.num_verified_pairs,
      report.num_rejected,
      report.num_already_hidden,
      report.num_without_rotation,
      report.seconds);
  if (report.num_guessed_cameras > 0) {
    std::printf(
        "  %zu cameras without a trusted focal length: focal lengths "
        "self-calibrated (median scale %.3f, 1 = declined; essential "
        "inconsistency %.4f -> %.4f)\n",
        report.num_guessed_cameras,
        report.median_focal_scale,
        report.focal_cost_before,
        report.focal_cost_after);
  }
  if (report.trusted_focal_scale != 1) {
    std::printf(
        "  trusted focal lengths scaled by %.3f: the loop test failed %zu "
        "strong pairs with them, %zu after\n",
        report.trusted_focal_scale,
        report.focal_check_failures_before,
        report.focal_check_failures_after);
  }
  if (report.num_uncalibrated_cameras > 0) {
    std::printf(
        "  %zu cameras whose focal length is neither trusted nor "
        "self-calibrated: their pairs are kept without a judgement\n",
        report.num_uncalibrated_cameras);
  }
  for (const auto& [reason, count] : by_reason) {
    std::printf("  %-14s %zu\n", reason.c_str(), count);
  }
  if (!list_pairs) return;
  for (const PairFilterEntry& entry : report.entries) {
    if (!entry.decision.Rejected()) continue;
    std::printf("  hidden %s %s  inliers %d  rotation error %.1f deg  (%s)\n",
                entry.name1.c_str(),
                entry.name2.c_str(),
                entry.num_inliers,
                entry.decision.rotation_error,
                LookalikeReasonName(entry.decision.reason));
  }
}

}  // namespace colmap_gcn
