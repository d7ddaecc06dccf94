#pragma once

#include <map>
#include <string>
#include <vector>

#include "evaluation/labels.h"
#include "scene/reconstruction.h"
#include "util/types.h"

namespace colmap_gcn {

// Which 3D points the images of a model share: |P_i| for every registered
// image and |P_i n P_j| for every pair with at least one common point.
struct CommonTracks {
  std::map<image_t, size_t> num_points;                      // |P_i|
  std::map<std::pair<image_t, image_t>, size_t> num_shared;  // first < second

  // CT_ij = |P_i n P_j| / min(|P_i|, |P_j|); 0 when either image sees no
  // point or is not in the model.
  double Ratio(image_t image_id1, image_t image_id2) const;
};

// Counts over distinct points: an image observing one point twice (possible
// after merging) counts it once.
CommonTracks ComputeCommonTracks(const Reconstruction& reconstruction);

// Labels with common-track ratios from a reference or ground-truth-
// triangulated model. labelled_names are the images the labels speak for
// (usually all images with ground truth); a labelled image missing from the
// model shares nothing with anyone. Names in the model outside
// labelled_names are ignored.
PairLabels LabelsFromReconstruction(
    const Reconstruction& reconstruction,
    const std::vector<std::string>& labelled_names,
    const std::string& source);

}  // namespace colmap_gcn
