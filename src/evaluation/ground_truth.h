#pragma once

#include <string>

#include "controllers/colmap_runner.h"
#include "scene/reconstruction.h"

namespace colmap_gcn {

// Triangulates the verified matches of a database on fixed ground-truth
// cameras with `colmap point_triangulator`, the way labels are derived from
// GT cameras: wrong matches (repeated structure) do not triangulate
// consistently on the true poses, so the resulting tracks only connect
// images that really see the same points.
//
// Works in work_dir: copies the database, writes the GT intrinsics into its
// cameras (PINHOLE etc. as given), writes the GT model re-indexed to the
// database's image and camera ids (matching images by name; GT images not
// in the database are dropped) and runs point_triangulator with intrinsics
// fixed. Returns the triangulated model (also kept in
// work_dir/triangulated). Throws Error if a shared database camera would
// need two different GT intrinsics.
Reconstruction TriangulateOnGroundTruth(const ColmapRunner& colmap,
                                        const Reconstruction& ground_truth,
                                        const std::string& database_path,
                                        const std::string& work_dir);

}  // namespace colmap_gcn
