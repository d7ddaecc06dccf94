#include "evaluation/common_tracks.h"

#include <algorithm>
#include <set>

namespace colmap_gcn {

double CommonTracks::Ratio(image_t image_id1, image_t image_id2) const {
  const auto key = std::make_pair(std::min(image_id1, image_id2),
                                  std::max(image_id1, image_id2));
  const auto shared = num_shared.find(key);
  const auto points1 = num_points.find(image_id1);
  const auto points2 = num_points.find(image_id2);
  if (shared == num_shared.end() || points1 == num_points.end() ||
      points2 == num_points.end()) {
    return 0.0;
  }
  const size_t denominator = std::min(points1->second, points2->second);
  return denominator == 0 ? 0.0
                          : static_cast<double>(shared->second) / denominator;
}

CommonTracks ComputeCommonTracks(const Reconstruction& reconstruction) {
  CommonTracks tracks;
  for (const auto& [image_id, image] : reconstruction.images) {
    tracks.num_points[image_id] = 0;
  }
  std::vector<image_t> track_images;
  for (const auto& [point3D_id, point3D] : reconstruction.points3D) {
    track_images.clear();
    for (const TrackElement& element : point3D.track) {
      if (reconstruction.images.count(element.image_id) > 0) {
        track_images.push_back(element.image_id);
      }
    }
    std::sort(track_images.begin(), track_images.end());
    track_images.erase(std::unique(track_images.begin(), track_images.end()),
                       track_images.end());
    for (size_t i = 0; i < track_images.size(); ++i) {
      ++tracks.num_points[track_images[i]];
      for (size_t j = i + 1; j < track_images.size(); ++j) {
        ++tracks.num_shared[{track_images[i], track_images[j]}];
      }
    }
  }
  return tracks;
}

PairLabels LabelsFromReconstruction(
    const Reconstruction& reconstruction,
    const std::vector<std::string>& labelled_names,
    const std::string& source) {
  PairLabels labels(labelled_names,
                    /*has_overlap=*/false,
                    /*has_common_track_ratio=*/true);
  labels.source = source;
  const CommonTracks tracks = ComputeCommonTracks(reconstruction);
  for (const auto& [pair, num_shared] : tracks.num_shared) {
    const std::string& name1 = reconstruction.images.at(pair.first).name;
    const std::string& name2 = reconstruction.images.at(pair.second).name;
    if (num_shared > 0 && labels.IsLabelled(name1, name2)) {
      labels.SetCommonTrackRatio(
          name1, name2, tracks.Ratio(pair.first, pair.second));
    }
  }
  return labels;
}

}  // namespace colmap_gcn
