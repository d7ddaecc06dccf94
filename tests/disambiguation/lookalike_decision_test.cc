#include "disambiguation/lookalike_decision.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "disambiguation/relative_pose.h"

namespace colmap_gcn {
namespace {

// A turn about the vertical, the camera's y axis (COLMAP: x right, y down,
// z forward).
Eigen::Matrix3d RotY(double degrees) {
  return Eigen::AngleAxisd(degrees * M_PI / 180.0, Eigen::Vector3d::UnitY())
      .toRotationMatrix();
}

// A little rotation noise, deterministic per seed.
Eigen::Matrix3d Noise(std::mt19937* rng, double degrees) {
  std::normal_distribution<double> normal(0.0, degrees * M_PI / 180.0);
  const Eigen::Vector3d axis_angle(normal(*rng), normal(*rng), normal(*rng));
  if (axis_angle.norm() == 0) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(axis_angle.norm(), axis_angle.normalized())
      .toRotationMatrix();
}

struct RingGraph {
  std::vector<ViewGraphEdge> edges;
  std::vector<bool> lookalike;
};

// n cameras on a circle looking inwards at an object whose front and back
// look the same: real edges join cameras up to `reach` steps apart; with
// `twins`, every camera also verifies with the ones facing the other side
// (opposite +- 1 step), whose matches say they stand where its twin would:
// their measured rotation is off by 180 degrees about the vertical.
RingGraph MakeRing(int n, int reach, bool twins, uint64_t seed) {
  std::mt19937 rng(seed);
  RingGraph graph;
  const double step = 360.0 / n;
  auto add = [&](int i, int j, int inliers, double measured, bool fake) {
    ViewGraphEdge edge;
    edge.image1 = std::min(i, j);
    edge.image2 = std::max(i, j);
    edge.pair_id = static_cast<image_pair_t>(edge.image1) * 1000 + edge.image2;
    edge.num_inliers = inliers;
    edge.has_rotation = true;
    // Camera k has world-to-camera rotation RotY(-k * step); the measured
    // relative rotation of (image1, image2) is R2 * R1^T.
    const double angle = i < j ? measured : -measured;
    edge.rotation = Noise(&rng, 1.0) * RotY(-angle);
    graph.edges.push_back(edge);
    graph.lookalike.push_back(fake);
  };
  for (int i = 0; i < n; ++i) {
    for (int d = 1; d <= reach; ++d) {
      const int j = (i + d) % n;
      add(i, j, 400 - 60 * d, d * step, false);
    }
  }
  if (twins) {
    for (int i = 0; i < n; ++i) {
      for (int d = -1; d <= 1; ++d) {
        const int j = (i + n / 2 + d + n) % n;
        if (j <= i) continue;
        // True offset (n/2 + d) steps; the print says d steps.
        add(i, j, 150 - 20 * std::abs(d), (n / 2 + d) * step - 180.0, true);
      }
    }
  }
  return graph;
}

TEST(LookalikeDecision, RejectsEveryTwinPairOfAPrintedRingAndKeepsTheRest) {
  const RingGraph graph = MakeRing(24, 3, /*twins=*/true, 1);
  const std::vector<LookalikeDecision> decisions =
      DecideLookalikePairs(24, graph.edges, LookalikeDecisionOptions());
  ASSERT_EQ(decisions.size(), graph.edges.size());
  int num_fake = 0;
  for (size_t e = 0; e < decisions.size(); ++e) {
    EXPECT_EQ(decisions[e].Rejected(), graph.lookalike[e])
        << graph.edges[e].image1 << "-" << graph.edges[e].image2 << " error "
        << decisions[e].rotation_error;
    if (graph.lookalike[e]) {
      ++num_fake;
      EXPECT_EQ(decisions[e].reason, LookalikeReason::kRotationLoop);
      EXPECT_GT(decisions[e].rotation_error, 150.0);
    }
  }
  EXPECT_EQ(num_fake, 36);
}

TEST(LookalikeDecision, KeepsEveryPairOfAnOrdinaryRing) {
  const RingGraph graph = MakeRing(30, 4, /*twins=*/false, 2);
  const std::vector<LookalikeDecision> decisions =
      DecideLookalikePairs(30, graph.edges, LookalikeDecisionOptions());
  for (const LookalikeDecision& decision : decisions) {
    EXPECT_FALSE(decision.Rejected()) << decision.rotation_error;
    // Drift of 1-degree noise chained around the ring.
    EXPECT_LT(decision.rotation_error, 20.0);
  }
}

// path_rotation is the unwrapped turn of the tree path between a pair's
// images: on a ring it is the pair's angle the short or the long way round
// (the tree leaves one gap, and the pairs across it go the long way).
TEST(LookalikeDecision, PathRotationIsTheTurnAlongTheTree) {
  const int n = 36;
  const RingGraph ring = MakeRing(n, 3, /*twins=*/false, 5);
  const std::vector<LookalikeDecision> decisions =
      DecideLookalikePairs(n, ring.edges, LookalikeDecisionOptions());
  int long_way = 0;
  for (size_t e = 0; e < decisions.size(); ++e) {
    const double angle =
        (ring.edges[e].image2 - ring.edges[e].image1) * 360.0 / n;
    const double turn = decisions[e].path_rotation;
    EXPECT_LT(std::min(std::abs(turn - angle), std::abs(turn - (360 - angle))),
              10.0)
        << ring.edges[e].image1 << "-" << ring.edges[e].image2 << " turn "
        << turn;
    if (decisions[e].in_tree) {
      EXPECT_NEAR(turn, std::min(angle, 360 - angle), 5.0);
    }
    if (turn > 180) ++long_way;
  }
  EXPECT_GE(long_way, 3);
}

TEST(LookalikeDecision, DoesNotDependOnTheOrderOfTheEdges) {
  const RingGraph graph = MakeRing(24, 3, /*twins=*/true, 3);
  const std::vector<LookalikeDecision> decisions =
      DecideLookalikePairs(24, graph.edges, LookalikeDecisionOptions());
  std::vector<int> order(graph.edges.size());
  for (size_t e = 0; e < order.size(); ++e) order[e] = static_cast<int>(e);
  std::shuffle(order.begin(), order.end(), std::mt19937(7));
  std::vector<ViewGraphEdge> shuffled;
  for (const int e : order) shuffled.push_back(graph.edges[e]);
  const std::vector<LookalikeDecision> shuffled_decisions =
      DecideLookalikePairs(24, shuffled, LookalikeDecisionOptions());
  for (size_t k = 0; k < order.size(); ++k) {
    const LookalikeDecision& a = decisions[order[k]];
    const LookalikeDecision& b = shuffled_decisions[k];
    EXPECT_EQ(a.reason, b.reason);
    EXPECT_EQ(a.in_tree, b.in_tree);
    EXPECT_EQ(a.backbone_hops, b.backbone_hops);
    EXPECT_DOUBLE_EQ(a.rotation_error, b.rotation_error);
    EXPECT_DOUBLE_EQ(a.path_rotation, b.path_rotation);
  }
}

TEST(LookalikeDecision, PairsWithoutARotationAreKept) {
  RingGraph graph = MakeRing(24, 3, /*twins=*/true, 4);
  for (ViewGraphEdge& edge : graph.edges) edge.has_rotation = false;
  const std::vector<LookalikeDecision> decisions =
      DecideLookalikePairs(24, graph.edges, LookalikeDecisionOptions());
  for (const LookalikeDecision& decision : decisions) {
    EXPECT_FALSE(decision.Rejected());
    EXPECT_EQ(decision.rotation_error, -1);
  }
}

TEST(LookalikeDecision, APairIsKeptWhenAnyRotationItsGeometryAllowsAgrees) {
  // A twin pair's measured rotation is 180 degrees off; an alternative (a
  // homography's second decomposition) that agrees with the ring saves it,
  // alternatives that do not agree do not.
  RingGraph graph = MakeRing(24, 3, /*twins=*/true, 6);
  const Eigen::Matrix3d flip =
      Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitY()).toRotationMatrix();
  for (size_t e = 0; e < graph.edges.size(); ++e) {
    if (!graph.lookalike[e]) continue;
    ViewGraphEdge& edge = graph.edges[e];
    edge.alternatives.push_back(edge.rotation * RotY(20.0));
    if (edge.image1 % 2 == 0) {
      edge.alternatives.push_back(flip * edge.rotation);  // the true one
    }
  }
  const std::vector<LookalikeDecision> decisions =
      DecideLookalikePairs(24, graph.edges, LookalikeDecisionOptions());
  for (size_t e = 0; e < decisions.size(); ++e) {
    const bool saved = graph.edges[e].image1 % 2 == 0;
    EXPECT_EQ(decisions[e].Rejected(), graph.lookalike[e] && !saved)
        << graph.edges[e].image1 << "-" << graph.edges[e].image2;
  }
}

TEST(LookalikeDecision, PairsWithOnlyAlternativesStayOutOfTheTree) {
  RingGraph graph = MakeRing(24, 3, /*twins=*/true, 7);
  for (size_t e = 0; e < graph.edges.size(); ++e) {
    if (!graph.lookalike[e]) continue;
    // Ambiguous twins: no rotation to chain, only the (wrong) candidates.
    ViewGraphEdge& edge = graph.edges[e];
    edge.alternatives = {edge.rotation, edge.rotation * RotY(10.0)};
    edge.has_rotation = false;
    edge.num_inliers = 1000;  // stronger than every real pair
  }
  const std::vector<LookalikeDecision> decisions =
      DecideLookalikePairs(24, graph.edges, LookalikeDecisionOptions());
  for (size_t e = 0; e < decisions.size(); ++e) {
    EXPECT_EQ(decisions[e].Rejected(), graph.lookalike[e]);
    if (graph.lookalike[e]) {
      EXPECT_FALSE(decisions[e].in_tree);
    }
  }
}

TEST(LookalikeDecision, PairsWithFewInliersAreNotJudgedByTheirRotation) {
  RingGraph graph = MakeRing(24, 3, /*twins=*/true, 8);
  LookalikeDecisionOptions options;
  for (size_t e = 0; e < graph.edges.size(); ++e) {
    if (graph.lookalike[e]) {
      graph.edges[e].num_inliers = options.min_evidence_inliers - 1;
    }
  }
  const std::vector<LookalikeDecision> decisions =
      DecideLookalikePairs(24, graph.edges, options);
  for (size_t e = 0; e < decisions.size(); ++e) {
    EXPECT_FALSE(decisions[e].Rejected());
    // The evidence is still reported.
    if (graph.lookalike[e]) {
      EXPECT_GT(decisions[e].rotation_error, 150.0);
    }
  }
}

TEST(LookalikeDecision, ContextTestRejectsPairsFarApartInTheBackbone) {
  const RingGraph graph = MakeRing(24, 3, /*twins=*/true, 5);
  LookalikeDecisionOptions options;
  options.max_rotation_error = 180.0;  // rotation test off
  options.max_backbone_hops = 3;
  const std::vector<LookalikeDecision> decisions =
      DecideLookalikePairs(24, graph.edges, options);
  for (size_t e = 0; e < decisions.size(); ++e) {
    EXPECT_EQ(decisions[e].Rejected(), graph.lookalike[e]);
    if (graph.lookalike[e]) {
      EXPECT_EQ(decisions[e].reason, LookalikeReason::kContext);
    }
  }
}

// Inlier rays of a camera k on the ring of MakeRing: it sees the object at
// its image centre (camera z), whatever pair it is in.
void LookAtTheCentre(std::vector<ViewGraphEdge>* edges) {
  for (ViewGraphEdge& edge : *edges) {
    edge.has_view_rays = true;
    edge.view_ray1 = Eigen::Vector3d(0.05, -0.02, 1.0).normalized();
    edge.view_ray2 = Eigen::Vector3d(-0.05, 0.01, 1.0).normalized();
  }
}

TEST(LookalikeDecision, WeakTwinPairsFacingAwayFailTheParallaxTest) {
  RingGraph graph = MakeRing(24, 3, /*twins=*/true, 6);
  LookAtTheCentre(&graph.edges);
  // The twin pairs are too weak for their own rotation to count, and their
  // rotation is ill-determined: only where their rays point is evidence.
  for (size_t e = 0; e < graph.edges.size(); ++e) {
    if (!graph.lookalike[e]) continue;
    graph.edges[e].num_inliers = 30;
    graph.edges[e].has_rotation = false;
  }
  const std::vector<LookalikeDecision> decisions =
      DecideLookalikePairs(24, graph.edges, LookalikeDecisionOptions());
  for (size_t e = 0; e < decisions.size(); ++e) {
    EXPECT_EQ(decisions[e].Rejected(), graph.lookalike[e])
        << graph.edges[e].image1 << "-" << graph.edges[e].image2 << " parallax "
        << decisions[e].view_parallax;
    if (graph.lookalike[e]) {
      EXPECT_EQ(decisions[e].reason, LookalikeReason::kViewParallax);
      EXPECT_GT(decisions[e].view_parallax, 150.0);
    } else {
      // Real pairs up to 3 steps (45 degrees) apart.
      EXPECT_LT(decisions[e].view_parallax, 60.0);
    }
  }
  // 180 degrees turns the test off: weak pairs are then kept.
  LookalikeDecisionOptions off;
  off.max_view_parallax = 180.0;
  for (const LookalikeDecision& decision :
       DecideLookalikePairs(24, graph.edges, off)) {
    EXPECT_FALSE(decision.Rejected());
  }
}

TEST(LookalikeDecision, PairsWhoseRotationAgreesAreKeptWhateverTheirRays) {
  RingGraph graph = MakeRing(24, 3, /*twins=*/false, 9);
  LookAtTheCentre(&graph.edges);
  for (size_t e = 0; e < graph.edges.size(); ++e) {
    // Rays that say the images face away, on pairs whose rotation agrees,
    // strong and weak.
    ViewGraphEdge& edge = graph.edges[e];
    edge.view_ray2 = -edge.view_ray2;
    if (e % 2 == 1) edge.num_inliers = 30;
  }
  for (const LookalikeDecision& decision :
       DecideLookalikePairs(24, graph.edges, LookalikeDecisionOptions())) {
    EXPECT_FALSE(decision.Rejected());
    if (!decision.in_tree) {
      EXPECT_GT(decision.view_parallax, 120.0);
    }
  }
}

TEST(LookalikeDecision, BadOptionsAreNamed) {
  LookalikeDecisionOptions options;
  options.backbone_neighbors = 0;
  EXPECT_THROW(options.Check(), std::exception);
  options = LookalikeDecisionOptions();
  options.max_rotation_error = 0;
  EXPECT_THROW(options.Check(), std::exception);
  options = LookalikeDecisionOptions();
  options.min_evidence_inliers = -1;
  EXPECT_THROW(options.Check(), std::exception);
  options = LookalikeDecisionOptions();
  options.max_view_parallax = 0;
  EXPECT_THROW(options.Check(), std::exception);
}

TEST(RelativePose, RotationFromEssentialPicksThePointsInFront) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.4, Eigen::Vector3d(0.2, 1.0, 0.1).normalized())
          .toRotationMatrix();
  const Eigen::Vector3d t(-1.0, 0.1, 0.2);
  Eigen::Matrix2Xd rays1(2, 50);
  Eigen::Matrix2Xd rays2(2, 50);
  for (int i = 0; i < 50; ++i) {
    const Eigen::Vector3d X(uniform(rng), uniform(rng), 5.0 + uniform(rng));
    const Eigen::Vector3d Y = R * X + t;
    rays1.col(i) = X.hnormalized();
    rays2.col(i) = Y.hnormalized();
  }
  Eigen::Matrix3d tx;
  tx << 0, -t.z(), t.y(), t.z(), 0, -t.x(), -t.y(), t.x(), 0;
  Eigen::Matrix3d estimated;
  ASSERT_TRUE(RotationFromEssential(tx * R, rays1, rays2, &estimated));
  EXPECT_LT(RotationAngleDegrees(estimated.transpose() * R), 1e-6);
  // Scale and sign of E do not matter.
  ASSERT_TRUE(RotationFromEssential(-3.0 * tx * R, rays1, rays2, &estimated));
  EXPECT_LT(RotationAngleDegrees(estimated.transpose() * R), 1e-6);
  EXPECT_FALSE(
      RotationFromEssential(Eigen::Matrix3d::Zero(), rays1, rays2, &estimated));
}

// Points on the plane n' X = d seen by two cameras (x2 = R x1 + t): the
// homography between normalised coordinates is R + t n' / d.
TEST(RelativePose, RotationsFromHomographyIncludeTheTrueOne) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.5, Eigen::Vector3d(0.1, 1.0, 0.3).normalized())
          .toRotationMatrix();
  const Eigen::Vector3d t(-1.5, 0.2, 0.4);
  const Eigen::Vector3d n = Eigen::Vector3d(0.2, -0.1, 1.0).normalized();
  const double d = 5.0;
  Eigen::Matrix2Xd rays1(2, 60);
  Eigen::Matrix2Xd rays2(2, 60);
  for (int i = 0; i < 60; ++i) {
    // On the plane: pick x, y and solve for z.
    const double x = 2 * uniform(rng);
    const double y = 2 * uniform(rng);
    const Eigen::Vector3d X(x, y, (d - n.x() * x - n.y() * y) / n.z());
    rays1.col(i) = X.hnormalized();
    rays2.col(i) = (R * X + t).hnormalized();
  }
  const Eigen::Matrix3d H = R + t * n.transpose() / d;
  for (const double scale : {1.0, -2.5}) {
    const std::vector<Eigen::Matrix3d> rotations =
        RotationsFromHomography(scale * H, rays1, rays2);
    ASSERT_FALSE(rotations.empty());
    EXPECT_LE(rotations.size(), 2u);
    double best = 180;
    for (const Eigen::Matrix3d& rotation : rotations) {
      best = std::min(best, RotationAngleDegrees(rotation.transpose() * R));
    }
    EXPECT_LT(best, 1e-6) << scale;
  }
  // A pure rotation gives exactly that rotation.
  const std::vector<Eigen::Matrix3d> pure =
      RotationsFromHomography(3.0 * R, rays1, rays1);
  ASSERT_EQ(pure.size(), 1u);
  EXPECT_LT(RotationAngleDegrees(pure[0].transpose() * R), 1e-6);
  EXPECT_TRUE(
      RotationsFromHomography(Eigen::Matrix3d::Zero(), rays1, rays2).empty());
}

}  // namespace
}  // namespace colmap_gcn
