#pragma once

#include <set>
#include <string>
#include <vector>

#include "pairing/pairs_io.h"
#include "scene/database.h"
#include "scene/two_view_geometry_store.h"

namespace colmap_gcn {

// What a matching run did, for the picture of its view graph.
struct MatchedViewGraph {
  std::string title;                     // first line of the picture
  std::vector<std::string> image_names;  // axis order (name order)
  std::vector<ImageNamePair> attempted;  // the pairs file
  std::vector<ImageNamePair> verified;   // geometry confirmed
  // Verified by COLMAP, then hidden from the mapper by the look-alike filter
  // (disjoint from `verified`).
  std::vector<ImageNamePair> hidden;
  // Images in a sparse model; used only when registration_known.
  std::set<std::string> registered;
  bool registration_known = false;
};

// A picture of the view graph a person reads without the docs: a title, on
// the left the N x N adjacency image (images in name order on both axes,
// verified pairs green, hidden as look-alikes purple, attempted but rejected
// red, not attempted white),
// on the right a 2-D layout in which verified pairs pull their images
// together (force-directed, deterministic), images numbered by their
// position in name order and, when registration is known, registered images
// filled and the others drawn as red rings; a legend explains every colour.
// Written as PNG; throws Error if it cannot be written.
void WriteMatchedViewGraphImage(const std::string& path,
                                const MatchedViewGraph& graph);

// The view graph of a matched database: image names, its verified pairs,
// the pairs the look-alike filter hid, and the attempted pairs of the pairs
// file (none when pairs_path is empty or missing). Leaves no SQLite side
// files behind.
MatchedViewGraph ReadMatchedViewGraph(const std::string& database_path,
                                      const std::string& pairs_path,
                                      size_t min_num_inliers);

// The pairs of the database's two_view_geometries that pass
// IsVerifiedTwoViewGeometry, as image names (pairs of unknown ids are
// skipped).
std::vector<ImageNamePair> ReadVerifiedImagePairs(const Database& database,
                                                  size_t min_num_inliers);

// The pairs the look-alike filter hid whose original row passes
// IsVerifiedTwoViewGeometry, as image names.
std::vector<ImageNamePair> ReadHiddenImagePairs(
    const std::string& database_path, size_t min_num_inliers);
std::vector<ImageNamePair> ReadHiddenImagePairs(
    const TwoViewGeometryStore& database, size_t min_num_inliers);

// The images' names in name order.
std::vector<std::string> ReadImageNamesSorted(const Database& database);

// 2-D positions in [0, 1]^2 of a force-directed layout of the graph
// (Fruchterman-Reingold from a circle in index order): the same input gives
// the same output.
std::vector<std::pair<double, double>> ForceDirectedLayout(
    size_t num_nodes, const std::vector<std::pair<size_t, size_t>>& edges);

}  // namespace colmap_gcn
