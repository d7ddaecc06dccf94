#pragma once

#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "pairing/pairs_io.h"

namespace colmap_gcn {

// The paper's rule for a matchable pair (§4.4): MO_ij >= tau_MO or
// CT_ij >= tau_CT.
struct PairLabelOptions {
  // tau_MO: minimum overlap (synthetic scenes: exact surface overlap).
  double min_overlap = 0.25;

  // tau_CT: minimum common-track ratio |P_i n P_j| / min(|P_i|, |P_j|).
  double min_common_track_ratio = 0.15;

  // Throws OptionError naming the first invalid field.
  void Check() const;
};

// What is known about one unordered pair; a negative value means that kind
// of evidence is not available for the pair.
struct PairEvidence {
  double overlap = -1;
  double common_track_ratio = -1;
};

// Ground-truth evidence for all pairs of a set of labelled images, keyed by
// image name (database ids differ between runs, names do not). A source
// provides overlaps, common-track ratios or both; for a pair of labelled
// images that was never set, an available kind reads as 0 (the images share
// nothing). Pairs with an image outside the labelled set are unlabelled.
class PairLabels {
 public:
  PairLabels() = default;
  PairLabels(const std::vector<std::string>& image_names,
             bool has_overlap,
             bool has_common_track_ratio);

  // Where the labels came from, for reports ("synthetic overlap", ...).
  std::string source;

  const std::vector<std::string>& ImageNames() const { return image_names_; }
  bool HasImage(const std::string& name) const;
  bool HasOverlap() const { return has_overlap_; }
  bool HasCommonTrackRatio() const { return has_common_track_ratio_; }

  // Throws Error if an image is not labelled or the kind is not available.
  void SetOverlap(const std::string& name1,
                  const std::string& name2,
                  double overlap);
  void SetCommonTrackRatio(const std::string& name1,
                           const std::string& name2,
                           double ratio);

  bool IsLabelled(const std::string& name1, const std::string& name2) const;
  // Both kinds -1 for an unlabelled pair.
  PairEvidence Evidence(const std::string& name1,
                        const std::string& name2) const;
  bool IsMatchable(const std::string& name1,
                   const std::string& name2,
                   const PairLabelOptions& options) const;
  // A labelled pair whose images share no surface or 3D point at all: a
  // match between them can only be wrong.
  bool SharesNothing(const std::string& name1, const std::string& name2) const;

  // All matchable pairs (name1 < name2), sorted.
  std::vector<ImageNamePair> MatchablePairs(
      const PairLabelOptions& options) const;

  // CSV cache: a "# source" line, a "# images" line per image as
  // "image,<name>", a header, then name1,name2,overlap,common_track_ratio
  // for every pair with any positive evidence.
  void Write(const std::string& path) const;
  static PairLabels Read(const std::string& path);

 private:
  static std::string Key(const std::string& name1, const std::string& name2);

  std::vector<std::string> image_names_;
  std::unordered_map<std::string, size_t> image_index_;
  bool has_overlap_ = false;
  bool has_common_track_ratio_ = false;
  std::unordered_map<std::string, PairEvidence> evidence_;
};

}  // namespace colmap_gcn
