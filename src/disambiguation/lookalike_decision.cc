#include "disambiguation/lookalike_decision.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <queue>

#include <Eigen/Geometry>

#include "disambiguation/relative_pose.h"
#include "util/option_check.h"

namespace colmap_gcn {
namespace {

// Stronger first: more strength, more coverage, more inliers, then the
// smaller pair id.
bool Stronger(const ViewGraphEdge& a, const ViewGraphEdge& b) {
  if (a.strength != b.strength) return a.strength > b.strength;
  if (a.coverage != b.coverage) return a.coverage > b.coverage;
  if (a.num_inliers != b.num_inliers) return a.num_inliers > b.num_inliers;
  return a.pair_id < b.pair_id;
}

// Edge indices sorted strongest first.
std::vector<int> ByStrength(const std::vector<ViewGraphEdge>& edges) {
  std::vector<int> order(edges.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return Stronger(edges[a], edges[b]);
  });
  return order;
}

// Edges among the k strongest of both their images.
std::vector<bool> MutualStrongestEdges(int num_images,
                                       const std::vector<ViewGraphEdge>& edges,
                                       const std::vector<int>& order,
                                       int k) {
  std::vector<int> taken(num_images, 0);
  std::vector<int> votes(edges.size(), 0);
  for (const int e : order) {
    for (const int image : {edges[e].image1, edges[e].image2}) {
      if (taken[image] < k) {
        ++taken[image];
        ++votes[e];
      }
    }
  }
  std::vector<bool> mutual(edges.size());
  for (size_t e = 0; e < edges.size(); ++e) mutual[e] = votes[e] == 2;
  return mutual;
}

int Find(std::vector<int>* parent, int x) {
  while ((*parent)[x] != x) {
    (*parent)[x] = (*parent)[(*parent)[x]];
    x = (*parent)[x];
  }
  return x;
}

// Backbone hops from `source` to `target` without edge `skip`; -1 when
// unreachable. adjacency holds (neighbour, edge) per image.
int Hops(const std::vector<std::vector<std::pair<int, int>>>& adjacency,
         int source,
         int target,
         int skip,
         std::vector<int>* distance) {
  std::fill(distance->begin(), distance->end(), -1);
  std::queue<int> queue;
  (*distance)[source] = 0;
  queue.push(source);
  while (!queue.empty()) {
    const int image = queue.front();
    queue.pop();
    if (image == target) return (*distance)[image];
    for (const auto& [next, edge] : adjacency[image]) {
      if (edge == skip || (*distance)[next] >= 0) continue;
      (*distance)[next] = (*distance)[image] + 1;
      queue.push(next);
    }
  }
  return -1;
}

// A spanning forest with the absolute rotations chained along it from each
// tree's smallest image.
struct RotationForest {
  explicit RotationForest(int num_images)
      : tree(num_images),
        component(num_images, -1),
        absolute(num_images, Eigen::Matrix3d::Identity()),
        turned(num_images, Eigen::Vector3d::Zero()) {}

  void AddEdge(const std::vector<ViewGraphEdge>& edges, int e) {
    tree[edges[e].image1].emplace_back(edges[e].image2, e);
    tree[edges[e].image2].emplace_back(edges[e].image1, e);
  }

  void Chain(const std::vector<ViewGraphEdge>& edges) {
    const int num_images = static_cast<int>(tree.size());
    std::fill(component.begin(), component.end(), -1);
    for (int root = 0; root < num_images; ++root) {
      if (component[root] >= 0) continue;
      component[root] = root;
      absolute[root] = Eigen::Matrix3d::Identity();
      turned[root].setZero();
      std::queue<int> queue;
      queue.push(root);
      while (!queue.empty()) {
        const int image = queue.front();
        queue.pop();
        for (const auto& [next, e] : tree[image]) {
          if (component[next] >= 0) continue;
          component[next] = root;
          const Eigen::Matrix3d step = edges[e].image1 == image
                                           ? edges[e].rotation
                                           : edges[e].rotation.transpose();
          const Eigen::AngleAxisd turn(step);
          turned[next] = turned[image] + absolute[image].transpose() *
                                             turn.axis() * turn.angle();
          absolute[next] = step * absolute[image];
          queue.push(next);
        }
      }
    }
  }

  // Degrees between the chained rotation and the closest of an edge's
  // measured ones; -1 without a rotation or across trees.
  double Error(const ViewGraphEdge& edge) const {
    if ((!edge.has_rotation && edge.alternatives.empty()) ||
        component[edge.image1] != component[edge.image2]) {
      return -1;
    }
    const Eigen::Matrix3d chained =
        absolute[edge.image2] * absolute[edge.image1].transpose();
    double error = 180;
    if (edge.has_rotation) {
      error = RotationAngleDegrees(edge.rotation.transpose() * chained);
    }
    for (const Eigen::Matrix3d& alternative : edge.alternatives) {
      error = std::min(error,
                       RotationAngleDegrees(alternative.transpose() * chained));
    }
    return error;
  }

  // Degrees the rotations along the tree path between two images turn in
  // all, as one unwrapped turn: steps back and forth cancel, a full circle
  // counts 360; -1 across trees.
  double PathRotation(int image1, int image2) const {
    if (component[image1] != component[image2]) return -1;
    return (turned[image2] - turned[image1]).norm() * 180.0 / M_PI;
  }

  // Degrees between the edge's mean inlier rays, image 1's turned into
  // image 2's frame by the chained rotation; -1 without rays or across
  // trees.
  double Parallax(const ViewGraphEdge& edge) const {
    if (!edge.has_view_rays ||
        component[edge.image1] != component[edge.image2]) {
      return -1;
    }
    const Eigen::Matrix3d chained =
        absolute[edge.image2] * absolute[edge.image1].transpose();
    // Both rays are unit vectors, and a rotation keeps them so.
    const double cosine =
        std::clamp((chained * edge.view_ray1).dot(edge.view_ray2), -1.0, 1.0);
    return std::acos(cosine) * 180.0 / M_PI;
  }

  std::vector<std::vector<std::pair<int, int>>> tree;
  std::vector<int> component;
  std::vector<Eigen::Matrix3d> absolute;
  // The turn from the tree's root to each image: the sum of the rotation
  // vectors (axis times angle, radians, in the root's frame) of the tree
  // edges on the way, so that a path's turn is a difference.
  std::vector<Eigen::Vector3d> turned;
};

}  // namespace

void LookalikeDecisionOptions::Check() const {
  CHECK_OPTION_GE(backbone_neighbors, 1);
  CHECK_OPTION_INTERVAL(max_rotation_error, 0.0, false, 180.0, true);
  CHECK_OPTION_INTERVAL(max_view_parallax, 0.0, false, 180.0, true);
  CHECK_OPTION_GE(max_backbone_hops, 0);
  CHECK_OPTION_GE(min_evidence_inliers, 0);
}

const char* LookalikeReasonName(const LookalikeReason reason) {
  switch (reason) {
    case LookalikeReason::kKept:
      return "kept";
    case LookalikeReason::kRotationLoop:
      return "rotation_loop";
    case LookalikeReason::kContext:
      return "context";
    case LookalikeReason::kViewParallax:
      return "view_parallax";
  }
  return "unknown";
}

std::vector<LookalikeDecision> DecideLookalikePairs(
    const int num_images,
    const std::vector<ViewGraphEdge>& edges,
    const LookalikeDecisionOptions& options) {
  options.Check();
  std::vector<LookalikeDecision> decisions(edges.size());
  const std::vector<int> order = ByStrength(edges);
  const std::vector<bool> backbone = MutualStrongestEdges(
      num_images, edges, order, options.backbone_neighbors);

  std::vector<std::vector<std::pair<int, int>>> adjacency(num_images);
  for (const int e : order) {
    if (!backbone[e]) continue;
    decisions[e].in_backbone = true;
    adjacency[edges[e].image1].emplace_back(edges[e].image2, e);
    adjacency[edges[e].image2].emplace_back(edges[e].image1, e);
  }
  // Maximum spanning forest of the edges that carry a rotation: the
  // backbone's first, then the pieces it leaves are joined by their
  // strongest pairs.
  std::vector<int> parent(num_images);
  std::iota(parent.begin(), parent.end(), 0);
  RotationForest forest(num_images);
  for (const bool from_backbone : {true, false}) {
    for (const int e : order) {
      if (backbone[e] != from_backbone || !edges[e].has_rotation) continue;
      const int a = Find(&parent, edges[e].image1);
      const int b = Find(&parent, edges[e].image2);
      if (a == b) continue;
      parent[a] = b;
      forest.AddEdge(edges, e);
      decisions[e].in_tree = true;
    }
  }
  forest.Chain(edges);

  std::vector<int> distance(num_images);
  for (size_t e = 0; e < edges.size(); ++e) {
    const ViewGraphEdge& edge = edges[e];
    LookalikeDecision& decision = decisions[e];
    decision.rotation_error = forest.Error(edge);
    decision.view_parallax = forest.Parallax(edge);
    decision.path_rotation = forest.PathRotation(edge.image1, edge.image2);
    if (options.max_backbone_hops > 0) {
      decision.backbone_hops = Hops(
          adjacency, edge.image1, edge.image2, static_cast<int>(e), &distance);
    }
    if (decision.in_tree) continue;
    // A strong pair is judged by its own rotation. A weak pair's rotation
    // alone is not evidence (often ill-determined), nor are its rays alone
    // (real weak pairs see a surface across wide angles, with the right
    // rotation): both must say look-alike, or the rays when it has none.
    if (edge.num_inliers < options.min_evidence_inliers) {
      // A parallax never exceeds 180: max_view_parallax 180 turns it off.
      if (decision.view_parallax > options.max_view_parallax &&
          (decision.rotation_error < 0 ||
           decision.rotation_error > options.max_rotation_error)) {
        decision.reason = LookalikeReason::kViewParallax;
      }
    } else if (decision.rotation_error > options.max_rotation_error) {
      decision.reason = LookalikeReason::kRotationLoop;
    } else if (options.max_backbone_hops > 0 &&
               (decision.backbone_hops < 0 ||
                decision.backbone_hops > options.max_backbone_hops)) {
      decision.reason = LookalikeReason::kContext;
    }
  }
  return decisions;
}

}  // namespace colmap_gcn
