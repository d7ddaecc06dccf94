#include "evaluation/common_tracks.h"

#include <gtest/gtest.h>

namespace colmap_gcn {
namespace {

// Images 1..4; point p observed by the listed images.
Reconstruction MakeModel(const std::vector<std::vector<image_t>>& points) {
  Reconstruction model;
  for (image_t id = 1; id <= 4; ++id) {
    model.images[id].image_id = id;
    model.images[id].name = "i" + std::to_string(id);
  }
  point3D_t point_id = 1;
  for (const auto& track : points) {
    ModelPoint3D& point = model.points3D[point_id];
    for (const image_t image_id : track) {
      ModelImage& image = model.images[image_id];
      TrackElement element;
      element.image_id = image_id;
      element.point2D_idx = static_cast<point2D_t>(image.points2D.size());
      image.points2D.emplace_back(0, 0);
      image.point3D_ids.push_back(point_id);
      point.track.push_back(element);
    }
    ++point_id;
  }
  return model;
}

TEST(CommonTracks, RatioOverSmallerImage) {
  // |P1| = 4, |P2| = 2, |P3| = 3 (one point observed twice), |P4| = 0.
  const Reconstruction model =
      MakeModel({{1, 2}, {1, 2, 3}, {1, 3, 3}, {1}, {3}});
  const CommonTracks tracks = ComputeCommonTracks(model);
  EXPECT_EQ(tracks.num_points.at(1), 4u);
  EXPECT_EQ(tracks.num_points.at(2), 2u);
  EXPECT_EQ(tracks.num_points.at(3), 3u);
  EXPECT_EQ(tracks.num_points.at(4), 0u);
  EXPECT_DOUBLE_EQ(tracks.Ratio(1, 2), 2.0 / 2.0);  // shared 2, min(4,2)
  EXPECT_DOUBLE_EQ(tracks.Ratio(3, 1), 2.0 / 3.0);  // shared 2, min(4,3)
  EXPECT_DOUBLE_EQ(tracks.Ratio(2, 3), 1.0 / 2.0);  // shared 1, min(2,3)
  EXPECT_DOUBLE_EQ(tracks.Ratio(1, 4), 0.0);
  EXPECT_DOUBLE_EQ(tracks.Ratio(1, 99), 0.0);

  const PairLabels labels =
      LabelsFromReconstruction(model, {"i1", "i2", "i3", "i4", "i5"}, "test");
  EXPECT_TRUE(labels.HasCommonTrackRatio());
  EXPECT_FALSE(labels.HasOverlap());
  EXPECT_DOUBLE_EQ(labels.Evidence("i3", "i1").common_track_ratio, 2.0 / 3.0);
  EXPECT_TRUE(labels.SharesNothing("i1", "i4"));
  // i5 is labelled but not in the model: it shares nothing.
  EXPECT_TRUE(labels.SharesNothing("i1", "i5"));
  PairLabelOptions options;
  options.min_common_track_ratio = 0.6;
  EXPECT_EQ(labels.MatchablePairs(options),
            (std::vector<ImageNamePair>{{"i1", "i2"}, {"i1", "i3"}}));
}

}  // namespace
}  // namespace colmap_gcn
