#pragma once

#include <cstddef>
#include <utility>
#include <vector>

namespace colmap_gcn {

// The statistics of the adaptive loop (docs/adaptive.md), independent of
// pairs and COLMAP: the strong-verification cut, the calibration of a prior
// score to P(strong), the log-odds offsets of propagation.

// P(strong | score) by isotonic regression (pool-adjacent-violators) on
// (score, 0/1) samples: a non-decreasing step function, each step shrunk
// by one pseudo-sample at 1/2 (then made monotone again), linear across
// the gaps between steps; below the lowest sample, the lowest step.
// Deterministic.
class IsotonicCalibration {
 public:
  void Fit(std::vector<std::pair<float, int>> samples);
  double Predict(float score) const;
  bool Empty() const { return levels_.empty(); }
  size_t NumSamples() const { return num_samples_; }

 private:
  std::vector<float> lower_;    // smallest score of each step
  std::vector<float> upper_;    // largest score of each step
  std::vector<double> levels_;  // its probability, non-decreasing
  size_t num_samples_ = 0;
};

// The collection's strong-verification cut from the inlier counts of its
// verified pairs: the Otsu split of log(inliers) when that split is bimodal
// (between-class share of the variance >= 0.75), its lower class looks
// accidental (median <= 30 inliers, twice COLMAP's default min_num_inliers)
// and at least 20 pairs verified, clamped to [min_cut, max_cut]; otherwise
// min_cut.
int LearnStrongInlierCut(const std::vector<size_t>& verified_inliers,
                         int min_cut,
                         int max_cut);

double Logit(double p);  // p clamped to [1e-3, 1 - 1e-3]
double Sigmoid(double x);

// The log-odds offset d in [-6, 6] that maximises the likelihood of a class
// of samples (their calibrated logits, num_positive of them positive) under
// a Gaussian prior of weight 2 on d.
double FitLogOddsOffset(const std::vector<double>& logits, double num_positive);

// Each group's log-odds offset over the one all groups share: the shared
// offset is fitted on every group's samples (logits, num_positive[g] of
// group g's positive), then each group's own on its samples shifted by it.
// A group with fewer than min_samples samples gets 0, and so does every
// group when all of them have fewer. Used for the strong components of the
// adaptive loop, whose later rounds take the pairs predicted most probable
// and so fall short of the prediction in every group alike.
std::vector<double> RelativeLogOddsOffsets(
    std::vector<std::vector<double>> logits,
    const std::vector<double>& num_positive,
    size_t min_samples);

// The stopping rule's parts (AdaptiveStopRule::kEnough).

// Whether a verified pair with `inliers` is strong relative to its images:
// at least `ratio` times the smaller of the two images' best verified pairs'
// inliers (CT-like: shared structure over the weaker image's). An image
// without a verified pair (best 0) asks nothing.
bool IsRelativelyStrong(size_t inliers,
                        size_t best_inliers1,
                        size_t best_inliers2,
                        double ratio);

// How many more candidates an image tries: the strong partners it still
// lacks (min_partners - strong_partners), at most the attempts its patience
// has left (patience - failures); 0 when it has enough or is out of
// patience.
int PartnersStillWanted(int strong_partners,
                        int failures,
                        int min_partners,
                        int patience);

// Connected components of a graph given as neighbour lists (an isolated
// vertex is a component).
size_t CountComponents(const std::vector<std::vector<int>>& neighbours);

// Each vertex's component, labelled by the smallest vertex in it.
std::vector<int> ComponentLabels(
    const std::vector<std::vector<int>>& neighbours);

// The models an incremental mapper could grow over a graph: from each seed
// edge (strongest first) whose two vertices are in no cluster yet, the
// cluster adds every vertex with at least `min_views` neighbours in it,
// until none is left (bootstrap percolation). Each vertex's cluster,
// labelled by its seed's first vertex; a vertex in no cluster is labelled
// by itself. A chain of triangles sharing single vertices is one connected
// component but not one cluster at min_views 2.
std::vector<int> GrowthClusters(const std::vector<std::vector<int>>& neighbours,
                                const std::vector<std::pair<int, int>>& seeds,
                                int min_views);

}  // namespace colmap_gcn
