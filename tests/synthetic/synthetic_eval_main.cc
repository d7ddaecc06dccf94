// synthetic_eval SCENE_DIR DATABASE SPARSE_DIR
//
// Compares a COLMAP run on a gcn_synth scene with its ground truth: images
// registered in the largest model, median camera-centre error after a
// similarity alignment (relative to the scene size), and geometric
// verification of pairs by ground-truth overlap. Used to produce the numbers
// in docs/synthetic_scenes.md.
#include <cstdio>
#include <exception>
#include <string>

#include "scene/reconstruction.h"
#include "synthetic/pair_overlap.h"
#include "synthetic_evaluation.h"
#include "util/file.h"
#include "util/string.h"

int main(int argc, char** argv) {
  using namespace colmap_gcn;
  if (argc != 4) {
    std::fprintf(stderr, "usage: %s SCENE_DIR DATABASE SPARSE_DIR\n", argv[0]);
    return 2;
  }
  try {
    const std::string scene = argv[1];
    Reconstruction gt;
    gt.ReadText(JoinPaths(scene, "gt"));
    const PairOverlapTable table =
        ReadPairOverlapTable(JoinPaths(scene, "gt/pair_overlap.csv"));
    std::vector<std::string> distractors;
    for (const std::string& line : StringSplit(
             ReadTextFile(JoinPaths(scene, "gt/distractors.txt")), "\n")) {
      if (!StringTrim(line).empty()) distractors.push_back(StringTrim(line));
    }
    const OverlapAgreement agreement = CompareOverlapWithVerification(
        table, ReadTwoViewGeometries(argv[2]), distractors);
    std::printf(
        "pairs: overlap>=0.3 verified %d/%d (%.1f%%), zero-overlap verified "
        "%d/%d, 0<overlap<0.05 verified %d/%d, distractor pairs verified "
        "%d/%d, all verified %d\n",
        agreement.num_overlap_verified,
        agreement.num_overlap_pairs,
        100.0 * agreement.OverlapVerifiedFraction(),
        agreement.num_zero_verified,
        agreement.num_zero_pairs,
        agreement.num_low_verified,
        agreement.num_low_pairs,
        agreement.num_distractor_verified,
        agreement.num_distractor_pairs,
        agreement.num_verified);
    const Reconstruction model = ReadLargestModel(argv[3]);
    const PoseAlignmentResult alignment = AlignToGroundTruth(gt, model);
    std::printf(
        "registered %d/%d (%.1f%%) in the largest model (%zu images incl. "
        "distractors), median centre error %.4f = %.3f%% of scene size "
        "%.2f, max %.4f\n",
        alignment.num_registered,
        alignment.num_gt_images,
        100.0 * alignment.RegisteredFraction(),
        model.images.size(),
        alignment.median_position_error,
        100.0 * alignment.RelativeMedianError(),
        alignment.scene_size,
        alignment.max_position_error);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "ERROR: %s\n", error.what());
    return 1;
  }
  return 0;
}
