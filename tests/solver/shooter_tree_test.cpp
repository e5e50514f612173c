// The shooting hierarchy of progressive refinement (solver/shooter_tree.h) against closed forms:
// the form factor's upper bound against Lambert's formula, and the far field of linear and of
// stepped or random radiosity against the sum of its elements' exact form factors, and what a
// receiver gathers against the same sum within its error budget.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <tuple>

#include "mesh/grid_mesh.h"
#include "solver/form_factor.h"
#include "solver/far_field.h"
#include "solver/gather.h"
#include "solver/shooter_tree.h"
#include "solver/visibility.h"
#include "support/scenes.h"
#include "support/ray_scene.h"
#include "support/occluder_lists.h"

namespace radrecon {
namespace shooter_tree_test {

using testing_support::quad;

/// A block over the parallelogram origin + s a + t b (s, t in [0, 1]), with its centre, area and
/// bounding radius, and its outline as a polygon.
struct ParallelogramBlock {
  Block block;
  ConvexPolygon outline;
};
ParallelogramBlock parallelogram_block(const Vec3& origin, const Vec3& a, const Vec3& b) {
  ParallelogramBlock out;
  Block& block = out.block;
  block.corners = {origin, origin + a, origin + a + b, origin + b, Vec3::Zero()};
  block.corner_count = 4;
  block.center = origin + 0.5 * (a + b);
  block.area_m2 = a.cross(b).norm();
  for (int k = 0; k < 4; ++k) {
    block.radius_m = std::max(block.radius_m, (block.corners[k] - block.center).norm());
    out.outline.push(block.corners[k]);
  }
  return out;
}

TEST(ShooterTree, FormFactorBoundIsAtLeastTheExactFormFactor) {
  // Random parallelograms and receiver points: the bound against the closed-form point-to-polygon
  // form factor (Lambert's formula) of the part in front of the receiver.
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-1, 1);
  const auto direction = [&] { return Vec3(u(rng), u(rng), u(rng)).normalized(); };
  int finite = 0, zero = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Vec3 origin(u(rng), u(rng), u(rng)), a = 0.5 * direction(), b0 = 0.5 * direction();
    const Vec3 normal = a.cross(b0).normalized(), b = normal.cross(a).normalized() * 0.3 + 0.2 * a;
    const auto [block, polygon] = parallelogram_block(origin, a, b);
    const Vec3 p = block.center + 3 * Vec3(u(rng), u(rng), u(rng)), n = direction();
    const double exact = normal.dot(p - origin) > 0 ? lambert_form_factor(p, n, clip_to_horizon(p, n, polygon)) : 0.0;
    const double bound = form_factor_bound(block, p, n, normal);
    if (!std::isfinite(bound)) continue;
    ++finite;
    zero += bound == 0 ? 1 : 0;
    ASSERT_LE(exact, bound * (1 + 1e-12)) << "trial " << trial;
  }
  EXPECT_GT(finite, 10000);
  EXPECT_GT(zero, 1000);  // points behind the block or with the block behind them
}

TEST(ShooterTree, FormFactorCeilingIsAtLeastTheExactFormFactorAnywhere) {
  // The ceiling against Lambert's formula for points anywhere, within the block's bounding sphere
  // included (where form_factor_bound() is infinite), and how close it comes: directly over a
  // small block it is the form factor to leading order, and next to a large one it is 1.
  std::mt19937_64 rng(43);
  std::uniform_real_distribution<double> u(-1, 1);
  const auto direction = [&] { return Vec3(u(rng), u(rng), u(rng)).normalized(); };
  int within_sphere = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Vec3 origin(u(rng), u(rng), u(rng)), a = 0.5 * direction(), b0 = 0.5 * direction();
    const Vec3 normal = a.cross(b0).normalized(), b = normal.cross(a).normalized() * 0.3 + 0.2 * a;
    const auto [block, polygon] = parallelogram_block(origin, a, b);
    // Half of the points within a bounding radius of the centre, half within three.
    const double reach = trial % 2 == 0 ? block.radius_m : 3.0;
    const Vec3 p = block.center + reach * Vec3(u(rng), u(rng), u(rng)) / std::sqrt(3.0), n = direction();
    const double exact = normal.dot(p - origin) > 0 ? lambert_form_factor(p, n, clip_to_horizon(p, n, polygon)) : 0.0;
    within_sphere += std::isfinite(form_factor_bound(block, p, n, normal)) ? 0 : 1;
    ASSERT_LE(exact, form_factor_ceiling(block, p, normal) * (1 + 1e-12)) << "trial " << trial;
  }
  EXPECT_GT(within_sphere, 5000);
  // A 0.1 m square at 1 m, and a 10 m square at 1 cm, each facing the point.
  for (const auto& [side, height, least_ratio] : {std::tuple{0.1, 1.0, 0.99}, std::tuple{10.0, 0.01, 0.99}}) {
    const auto [block, polygon] = parallelogram_block(Vec3(-side / 2, -side / 2, 0), Vec3(side, 0, 0), Vec3(0, side, 0));
    const Vec3 p(0, 0, height), n(0, 0, -1), up(0, 0, 1);
    const double exact = lambert_form_factor(p, n, polygon), ceiling = form_factor_ceiling(block, p, up);
    EXPECT_LE(exact, ceiling * (1 + 1e-12));
    EXPECT_GE(exact, least_ratio * ceiling) << "side " << side;
  }
}

/// A 2 m x 1 m plate in the plane z = 0, facing +z, meshed with `divisions` elements along its
/// length, and an unshot radiosity linear in (x, y) over it: B = 1 + 2x + 3y per channel, times
/// (1, 2, 3) over the channels. Kept whole: a ShooterTree refers to its parts.
struct LinearPlate {
  Scene scene;
  Mesh mesh;
  std::vector<Rgb> unshot;
  explicit LinearPlate(int divisions) {
    scene.name = "plate";
    scene.surfaces.push_back(quad("plate", {0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}, 0.5));
    mesh = make_grid_mesh(scene, {divisions, 1});
    for (const MeshElement& e : side().elements) unshot.push_back((1 + 2 * e.center.x() + 3 * e.center.y()) * Rgb(1, 2, 3));
  }
  const MeshSurface& side() const { return mesh.surfaces[0]; }
  ShooterTree tree() const { return ShooterTree(scene.surfaces[0], side(), unshot, 0, 0, side().nu, side().nv); }
};

/// The blocks of a tree, depth first.
template <typename Visit>
void visit_blocks(const ShooterTree& tree, const Block& b, Visit&& visit) {
  visit(b);
  for (int c = 0; c < b.child_count; ++c) visit_blocks(tree, tree.block(b.first_child + c), visit);
}

/// The number of blocks reachable from a tree's root (its own included).
size_t blocks_of(const ShooterTree& tree) {
  size_t n = 0;
  visit_blocks(tree, tree.root(), [&](const Block&) { ++n; });
  return n;
}

/// Whether the element centre c lies in the block (the plate's blocks are boxes in z = 0).
bool inside(const Block& b, const Vec3& c) {
  double x0 = b.corners[0].x(), x1 = x0, y0 = b.corners[0].y(), y1 = y0;
  for (int k = 1; k < b.corner_count; ++k) {
    x0 = std::min(x0, b.corners[k].x()), x1 = std::max(x1, b.corners[k].x());
    y0 = std::min(y0, b.corners[k].y()), y1 = std::max(y1, b.corners[k].y());
  }
  return c.x() > x0 && c.x() < x1 && c.y() > y0 && c.y() < y1;
}

TEST(ShooterTree, BlockMomentsAreTheSumsOverTheirElements) {
  // The tree adds its children's moments up; here every block's against the sums over its
  // elements: 7 x 4 rectangles of 2/7 x 1/4 m (own second moment diag(dx^2, dy^2, 0) / 12), with
  // random radiosity.
  LinearPlate plate(7);
  const MeshSurface& side = plate.side();
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  for (Rgb& b : plate.unshot) b = Rgb(u(rng), u(rng), u(rng));
  const double dx = 2.0 / 7, dy = 1.0 / 4;
  const Eigen::Matrix3d own = Eigen::Vector3d(dx * dx / 12, dy * dy / 12, 0).asDiagonal();
  const ShooterTree tree = plate.tree();
  int blocks = 0;
  visit_blocks(tree, tree.root(), [&](const Block& b) {
    ++blocks;
    double area = 0;
    Vec3 centre = Vec3::Zero();
    Rgb mean = Rgb::Zero();
    for (size_t k = 0; k < side.elements.size(); ++k)
      if (inside(b, side.elements[k].center)) {
        area += side.elements[k].area_m2;
        centre += side.elements[k].area_m2 * side.elements[k].center;
        mean += side.elements[k].area_m2 * plate.unshot[k];
      }
    centre /= area;
    mean /= area;
    Eigen::Matrix3d dipole = Eigen::Matrix3d::Zero(), moment = Eigen::Matrix3d::Zero();
    std::array<Eigen::Matrix3d, 3> quadrupole{Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero()};
    for (size_t k = 0; k < side.elements.size(); ++k) {
      if (!inside(b, side.elements[k].center)) continue;
      const double a = side.elements[k].area_m2 / area;
      const Vec3 t = side.elements[k].center - centre;
      const Rgb deviation = plate.unshot[k] - mean;
      dipole += a * t * deviation.matrix().transpose();
      moment += a * (t * t.transpose() + own);
      for (int c = 0; c < 3; ++c) quadrupole[static_cast<size_t>(c)] += a * deviation[c] * (t * t.transpose() + own);
    }
    EXPECT_NEAR(b.area_m2, area, 1e-12) << "block " << blocks;
    EXPECT_LT((b.center - centre).norm(), 1e-12) << "block " << blocks;
    EXPECT_LT((b.unshot_w_m2 - mean).abs().maxCoeff(), 1e-12) << "block " << blocks;
    EXPECT_LT((b.dipole - dipole).cwiseAbs().maxCoeff(), 1e-12) << "block " << blocks;
    EXPECT_LT((b.area_moment - moment).cwiseAbs().maxCoeff(), 1e-12) << "block " << blocks;
    for (int c = 0; c < 3; ++c)
      EXPECT_LT((b.quadrupole[static_cast<size_t>(c)] - quadrupole[static_cast<size_t>(c)]).cwiseAbs().maxCoeff(), 1e-12)
          << "block " << blocks << ", channel " << c;
  });
  EXPECT_GT(blocks, 20);
}

TEST(ShooterTree, FarFieldErrorIsWithinItsEstimate) {
  // Radiosity far from linear (a step across the plate; random values per element): every
  // block's far field against the sum over its elements of their exact form factors
  // (Lambert's formula) times their radiosity, from random receivers that see the whole plate;
  // the error within the spread times the form factor times far_field_error() wherever that
  // estimate is trusted (finite).
  LinearPlate plate(16);
  const MeshSurface& side = plate.side();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  for (const bool step : {true, false}) {
    for (size_t k = 0; k < side.elements.size(); ++k)
      plate.unshot[k] = step ? (side.elements[k].center.x() < 0.7 ? Rgb(5, 4, 3) : Rgb(0.1, 0.2, 0.3))
                             : Rgb(u(rng), u(rng), u(rng));
    const ShooterTree tree = plate.tree();
    int checked = 0, blocks = 0, exceeded = 0;
    double tightest = 0;  // the largest error over its estimate
    for (int trial = 0; trial < 400; ++trial) {
      const Vec3 p(4 * u(rng) - 1, 3 * u(rng) - 1, 0.3 + 3 * u(rng));
      const Vec3 n = -Vec3(u(rng) - 0.5, u(rng) - 0.5, 1.5 * u(rng) + 0.2).normalized();
      bool whole = true;  // the receiver's horizon leaves the plate whole
      for (const MeshElement& e : side.elements)
        for (int c = 0; c < 4; ++c) whole = whole && n.dot(e.corners[static_cast<size_t>(c)] - p) > 0;
      if (!whole) continue;
      visit_blocks(tree, tree.root(), [&](const Block& b) {
        Vec3 g;
        if (b.first_child < 0 || !kernel_log_gradient(b, p, n, side.normal, g)) return;
        const double curvature = far_field_error(b, p, n, side.normal, g);
        if (!std::isfinite(curvature)) return;
        Rgb sum = Rgb::Zero();
        double f_total = 0;
        for (size_t k = 0; k < side.elements.size(); ++k) {
          if (!inside(b, side.elements[k].center)) continue;
          ConvexPolygon polygon;
          for (int c = 0; c < 4; ++c) polygon.push(side.elements[k].corners[static_cast<size_t>(c)]);
          const double f = lambert_form_factor(p, n, polygon);
          sum += f * plate.unshot[k];
          f_total += f;
        }
        const double error = (f_total * far_field_radiosity(b, p, n, side.normal) - sum).abs().sum();
        const double estimate = f_total * (b.highest_w_m2 - b.lowest_w_m2).sum() * curvature;
        const double round_off = 1e-12 * sum.abs().sum();
        if (error > estimate + round_off) ++exceeded;
        if (estimate > round_off) tightest = std::max(tightest, error / estimate);
        ++checked;
      });
      ++blocks;
    }
    std::printf("%s radiosity: %d blocks checked, largest error / estimate %.3f\n", step ? "step" : "random", checked,
                tightest);
    EXPECT_EQ(exceeded, 0) << (step ? "step" : "random") << ": largest error / estimate " << tightest;
    EXPECT_GT(blocks, 100);
    EXPECT_GT(checked, 2000);
    EXPECT_GT(tightest, 0.05) << "the estimate is over 20 times the largest error";
  }
}

TEST(ShooterTree, FarFieldOfLinearRadiosityMatchesTheSumOverElements) {
  // A far block shoots with its first-order corrected radiosity: for radiosity linear over it,
  // the form-factor-weighted sum over its elements (each element's exact form factor times its
  // radiosity) to second order in size / distance.
  const LinearPlate plate(32);
  const MeshSurface& side = plate.side();
  const std::vector<Rgb>& unshot = plate.unshot;
  const ShooterTree tree = plate.tree();
  const Block& root = tree.root();
  for (const double distance_m : {4.0, 8.0, 16.0}) {
    const Vec3 p(1.0 + 0.3 * distance_m, 0.5, distance_m), n = -Vec3(0.3, 0, 1).normalized();
    Rgb sum = Rgb::Zero();
    double f_total = 0;
    for (size_t k = 0; k < side.elements.size(); ++k) {
      ConvexPolygon polygon;
      for (int c = 0; c < 4; ++c) polygon.push(side.elements[k].corners[static_cast<size_t>(c)]);
      const double f = lambert_form_factor(p, n, polygon);
      sum += f * unshot[k];
      f_total += f;
    }
    const Rgb far = f_total * far_field_radiosity(root, p, n, side.normal);
    const Rgb mean_only = f_total * root.unshot_w_m2;
    const double error = ((far - sum) / sum).abs().maxCoeff(), mean_error = ((mean_only - sum) / sum).abs().maxCoeff();
    // Second order: (radius / distance)^2 with radius ~1.1 m; the mean alone errs to first order.
    EXPECT_LT(error, 0.5 * std::pow(1.12 / distance_m, 2)) << "at " << distance_m << " m";
    EXPECT_LT(error, 0.2 * mean_error) << "at " << distance_m << " m";
  }
}

TEST(ShooterTree, GatherAtTheCentreIsWithinItsBudgetOfTheSumOverElements) {
  // gather() shares its error budget among the blocks that shoot as one, in proportion to their
  // area: at a receiver's centre it errs by no more than the budget. Against the sum over the
  // elements of their exact form factors (Lambert's formula) times their radiosity, with radiosity
  // far from smooth (a step; random per element), from receivers near the plate and far from it
  // that see all of it. Budgets of 20%, 2% (the solver's default) and 0.2% of the exact
  // irradiance; the bound is loose (the largest error here is some 5% of it).
  LinearPlate plate(32);
  const MeshSurface& side = plate.side();
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  const std::vector<const Occluder*> no_occluders;
  for (const bool step : {true, false}) {
    for (size_t k = 0; k < side.elements.size(); ++k)
      plate.unshot[k] = step ? (side.elements[k].center.x() < 0.7 ? Rgb(5, 4, 3) : Rgb(0.1, 0.2, 0.3))
                             : Rgb(u(rng), u(rng), u(rng));
    const ShooterTree tree = plate.tree();
    ConvexPolygon outline;
    for (int k = 0; k < tree.root().corner_count; ++k) outline.push(tree.root().corners[static_cast<size_t>(k)]);
    int checked = 0, near = 0;
    double worst = 0;  // the largest error over its budget
    for (int trial = 0; trial < 300; ++trial) {
      const double height = trial % 2 == 0 ? 0.01 + 0.2 * u(rng) : 0.3 + 2 * u(rng);
      Receiver r;
      r.center = Vec3(2.4 * u(rng) - 0.2, 1.4 * u(rng) - 0.2, height);
      r.normal = -Vec3(0.6 * (u(rng) - 0.5), 0.6 * (u(rng) - 0.5), 1).normalized();
      r.size_m = 1e-6;  // a point: gathered at its centre alone
      r.gauss.fill(r.center);
      r.gauss_count = 4;
      bool whole = true;  // the receiver's horizon leaves the plate whole
      for (int c = 0; c < outline.n; ++c) whole = whole && r.normal.dot(outline.v[c] - r.center) > 0;
      if (!whole) continue;
      Rgb exact = Rgb::Zero();
      for (size_t k = 0; k < side.elements.size(); ++k) {
        ConvexPolygon polygon;
        for (int c = 0; c < 4; ++c) polygon.push(side.elements[k].corners[static_cast<size_t>(c)]);
        exact += lambert_form_factor(r.center, r.normal, polygon) * plate.unshot[k];
      }
      const SeenFromCentre seen{lambert_form_factor(r.center, r.normal, outline), false};
      const ReceiverShadows shadows(r, no_occluders);
      for (const double fraction : {2e-1, 2e-2, 2e-3}) {
        const double budget = fraction * exact.sum();
        const Gathered got = gather(tree, tree.root(), r, side.normal, shadows, budget, &seen);
        const double error = (got.at_center - exact).abs().sum();
        EXPECT_LE(error, budget * (1 + 1e-9)) << (step ? "step" : "random") << ", trial " << trial << ", budget "
                                              << fraction << " of the exact irradiance";
        ++checked;
        worst = std::max(worst, error / budget);
      }
      near += height < 0.25 ? 1 : 0;
    }
    EXPECT_GT(checked, 200);
    EXPECT_GT(near, 30);
    std::printf("%s: largest error %.3g of its budget\n", step ? "step" : "random", worst);
  }
}

TEST(ShooterTree, GatherTheMeanOfALargeElementNearThePlateAgainstAFineCubature) {
  // An element large against its distance to the plate (off the midpoint rule,
  // tol::kMidpointReceiverRatio) takes its power from its mean irradiance by the 2 x 2 Gauss rule.
  // Against the mean by an 8 x 8 Gauss-Legendre cubature over the element of the exact irradiance
  // (every plate element's Lambert form factor times its radiosity): the square element faces the
  // plate from heights of 0.02-0.3 m, 0.05-0.4 m wide. With the solver's budget (2% of the
  // exact mean) the error stays within the budget plus the 2 x 2 rule's own error, and that rule
  // beats the midpoint rule (the centre's value) by a wide margin where the element is largest
  // against its height: the point collocation the Gauss rule is there to avoid.
  LinearPlate plate(32);
  const MeshSurface& side = plate.side();
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(0, 1);
  const std::vector<const Occluder*> no_occluders;
  // Gauss-Legendre on [-1, 1], 8 nodes (Abramowitz and Stegun, Table 25.4).
  const std::array<double, 4> x8 = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
  const std::array<double, 4> w8 = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
  const Vec3 down(0, 0, -1);
  const auto exact_at = [&](const Vec3& p) {
    Rgb e = Rgb::Zero();
    for (size_t k = 0; k < side.elements.size(); ++k) {
      ConvexPolygon polygon;
      for (int c = 0; c < 4; ++c) polygon.push(side.elements[k].corners[static_cast<size_t>(c)]);
      e += lambert_form_factor(p, down, polygon) * plate.unshot[k];
    }
    return e;
  };
  int checked = 0;
  double worst_over_allowed = 0, gauss_sum = 0, midpoint_sum = 0, gathered_sum = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const double height = 0.02 + 0.28 * u(rng), width = std::min(0.05 + 0.35 * u(rng), 4 * height);
    Receiver r;
    r.center = Vec3(0.3 + 1.4 * u(rng), 0.25 + 0.5 * u(rng), height);
    r.normal = down;
    r.size_m = width * std::sqrt(2.0);
    const double g = 0.5 * width / std::sqrt(3.0);
    r.gauss = {r.center + Vec3(-g, -g, 0), r.center + Vec3(g, -g, 0), r.center + Vec3(-g, g, 0), r.center + Vec3(g, g, 0)};
    r.gauss_count = 4;
    if (gathers_at_centre(plate.tree().root(), r)) continue;
    Rgb fine = Rgb::Zero(), rule = Rgb::Zero();  // the 8 x 8 cubature's mean; the 2 x 2 rule's of the exact values
    for (int i = 0; i < 8; ++i)
      for (int j = 0; j < 8; ++j) {
        const double xi = (i < 4 ? -1 : 1) * x8[static_cast<size_t>(i % 4)], yj = (j < 4 ? -1 : 1) * x8[static_cast<size_t>(j % 4)];
        const double w = w8[static_cast<size_t>(i % 4)] * w8[static_cast<size_t>(j % 4)] / 4;
        fine += w * exact_at(r.center + 0.5 * width * Vec3(xi, yj, 0));
      }
    for (const Vec3& p : r.gauss) rule += exact_at(p) / 4;
    const Rgb centre = exact_at(r.center);
    const ShooterTree tree = plate.tree();
    const ReceiverShadows shadows(r, no_occluders);
    const double budget = 2e-2 * fine.sum();
    const Gathered got = gather(tree, tree.root(), r, side.normal, shadows, budget);
    const double rule_error = (rule - fine).abs().sum();
    const double error = (got.mean - fine).abs().sum();
    EXPECT_LE(error, budget + rule_error) << "trial " << trial << ", height " << height << " m, width " << width << " m";
    EXPECT_LE(rule_error, 0.02 * fine.sum()) << "the 2 x 2 rule, trial " << trial;
    worst_over_allowed = std::max(worst_over_allowed, error / (budget + rule_error));
    gauss_sum += rule_error / fine.sum();
    gathered_sum += error / fine.sum();
    midpoint_sum += (centre - fine).abs().sum() / fine.sum();
    ++checked;
  }
  EXPECT_GT(checked, 40);
  // The midpoint rule's error is many times the 2 x 2 rule's over these elements, and the
  // gathered mean's (the 2 x 2 rule with the far field) is nearer the rule's than the midpoint's.
  EXPECT_GT(midpoint_sum, 5 * gauss_sum);
  EXPECT_LT(gathered_sum, 0.25 * midpoint_sum);
  std::printf("%d elements: largest error %.3g of what is allowed; mean relative error gathered %.2e, of the 2 x 2 "
              "rule %.2e, of the midpoint rule %.2e\n",
              checked, worst_over_allowed, gathered_sum / checked, gauss_sum / checked, midpoint_sum / checked);
}

TEST(ReceiverShadows, OccludersFoundOnFirstNeedGiveTheSameVolumes) {
  // The receiving element's occluders searched when a shadow is first needed: the search runs
  // once, and only then; every point's shadow volumes are those of the occluders given at
  // construction (one ReceiverShadows alive at a time: they share the thread's buffers); and
  // the floor's visible form factor through them at each point is the ray caster's.
  Scene scene;
  scene.surfaces.push_back(quad("floor", Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(2, 2, 0), Vec3(0, 2, 0), 0.5, 0));
  scene.surfaces.push_back(quad("box_top", Vec3(0.5, 0.5, 0.5), Vec3(1.2, 0.5, 0.5), Vec3(1.2, 1.1, 0.5), Vec3(0.5, 1.1, 0.5), 0.5, 0));
  scene.surfaces.push_back(quad("slab", Vec3(0.8, 0.2, 0.3), Vec3(1.6, 0.2, 0.3), Vec3(1.6, 1.4, 0.9), Vec3(0.8, 1.4, 0.9), 0.5, 0));
  const std::vector<Occluder> occluders = make_occluders(scene);
  const size_t floor = 0, none = scene.surfaces.size();  // the receiver lies on no surface
  const std::vector<const Occluder*> given = testing_support::all_but(occluders, floor, none);
  Receiver r;
  r.center = Vec3(1.0, 0.9, 1.5);
  r.normal = Vec3(0, 0, -1);
  r.size_m = 0.1;
  for (int k = 0; k < 4; ++k) r.gauss[static_cast<size_t>(k)] = r.center + Vec3(k % 2 ? 0.02 : -0.02, k / 2 ? 0.02 : -0.02, 0);
  r.gauss_count = 4;
  ConvexPolygon floor_polygon;
  for (const Vec3& c : scene.surfaces[floor].corners) floor_polygon.push(c);
  const Vec3 floor_normal = scene.surfaces[floor].normal();
  std::vector<std::vector<std::pair<const Occluder*, int>>> eager(5), lazy(5);
  {
    const ReceiverShadows shadows(r, given);
    for (int p = 0; p < 5; ++p)
      for (const ShadowVolume& v : shadows.at(p)) eager[static_cast<size_t>(p)].emplace_back(v.occluder, v.sides);
  }
  std::vector<const Occluder*> found;
  int calls = 0;
  const auto find = [&] {
    ++calls;
    found = given;
  };
  std::array<double, 5> seen{};
  {
    const ReceiverShadows shadows(r, found, find);
    EXPECT_EQ(calls, 0) << "no shadow asked for yet";
    for (int p = 4; p >= 0; --p) {
      for (const ShadowVolume& v : shadows.at(p)) lazy[static_cast<size_t>(p)].emplace_back(v.occluder, v.sides);
      const Vec3& at = p == 0 ? r.center : r.gauss[static_cast<size_t>(p - 1)];
      seen[static_cast<size_t>(p)] = visible_form_factor_past(at, r.normal, floor_polygon, floor_normal, shadows.at(p));
    }
  }
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(lazy, eager);
  size_t volumes = 0;
  for (const auto& v : eager) volumes += v.size();
  EXPECT_GE(volumes, 5u) << "the occluders should cast shadows toward the floor";
  for (int p = 0; p < 5; ++p) {
    const Vec3& at = p == 0 ? r.center : r.gauss[static_cast<size_t>(p - 1)];
    const double rays = testing_support::brute_force_form_factor(scene, floor, at, r.normal, none, 400);
    EXPECT_NEAR(seen[static_cast<size_t>(p)], rays, 2e-3 * rays) << "point " << p;
    EXPECT_LT(seen[static_cast<size_t>(p)], 0.9 * lambert_form_factor(at, r.normal, floor_polygon))
        << "point " << p << ": the occluders should hide part of the floor";
  }
}

TEST(ShooterTree, SplitsAtAWallsFootLeaveNoBlockAcrossIt) {
  // A 2 m x 1 m ground and a wall standing on it along x = 0.75 (y in [0.2, 0.8]), facing -x. At
  // 16 elements along the ground (1/8 m) its foot is the cell boundary u = 6: the tree splits
  // there first, so no block but the whole patch straddles the wall's plane (seen in part from
  // every receiver on the wall); at 17 it is on no boundary and gives no split.
  Scene scene;
  scene.name = "foot";
  scene.surfaces.push_back(quad("ground", {0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}, 0.5));
  scene.surfaces.push_back(quad("wall", {0.75, 0.8, 0}, {0.75, 0.2, 0}, {0.75, 0.2, 0.5}, {0.75, 0.8, 0.5}, 0.5));
  const Mesh off_grid = make_grid_mesh(scene, {17, 1});
  const ShooterSplits none = shooter_splits(scene, off_grid.surfaces[0], ContactFinder(scene));
  EXPECT_TRUE(none.u.empty() && none.v.empty());
  const Mesh mesh = make_grid_mesh(scene, {16, 1});
  const MeshSurface& ground = mesh.surfaces[0];
  ASSERT_EQ(ground.name, "ground");
  const ShooterSplits splits = shooter_splits(scene, ground, ContactFinder(scene));
  EXPECT_EQ(splits.u, std::vector<int>{6});
  EXPECT_TRUE(splits.v.empty());

  std::vector<Rgb> unshot;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  for (size_t k = 0; k < ground.elements.size(); ++k) unshot.push_back(Rgb(u(rng), u(rng), u(rng)));
  const auto straddling = [&](const ShooterTree& tree) {
    int count = 0;
    visit_blocks(tree, tree.root(), [&](const Block& b) {
      bool before = false, after = false;
      for (int k = 0; k < b.corner_count; ++k) {
        before = before || b.corners[static_cast<size_t>(k)].x() < 0.75 - 1e-12;
        after = after || b.corners[static_cast<size_t>(k)].x() > 0.75 + 1e-12;
      }
      count += before && after ? 1 : 0;
    });
    return count;
  };
  const ShooterTree plain(scene.surfaces[0], ground, unshot, 0, 0, ground.nu, ground.nv);
  const ShooterTree split(scene.surfaces[0], ground, unshot, 0, 0, ground.nu, ground.nv, {}, &splits);
  EXPECT_GT(straddling(plain), 2);  // the midpoint rule's blocks cross the foot at every level
  EXPECT_EQ(straddling(split), 1);  // the whole patch alone
  // block_count() (what the solver sizes the trees' storage by) counts the blocks built.
  EXPECT_EQ(ShooterTree::block_count(ground, nullptr, 0, 0, ground.nu, ground.nv), blocks_of(plain));
  EXPECT_EQ(ShooterTree::block_count(ground, &splits, 0, 0, ground.nu, ground.nv), blocks_of(split));

  // Receivers on the wall's front see the ground before it alone: what they gather from the
  // split tree is within its budget of the sum over those elements of their exact form factors.
  const std::vector<const Occluder*> no_occluders;
  int checked = 0;
  for (int trial = 0; trial < 50; ++trial) {
    Receiver r;
    r.center = Vec3(0.75, 0.2 + 0.6 * u(rng), 0.01 + 0.45 * u(rng));
    r.normal = Vec3(-1, 0, 0);
    r.size_m = 1e-6;
    r.gauss.fill(r.center);
    r.gauss_count = 4;
    Rgb exact = Rgb::Zero();
    for (size_t k = 0; k < ground.elements.size(); ++k) {
      ConvexPolygon polygon;
      for (int c = 0; c < 4; ++c) polygon.push(ground.elements[k].corners[static_cast<size_t>(c)]);
      exact += lambert_form_factor(r.center, r.normal, clip_to_horizon(r.center, r.normal, polygon)) * unshot[k];
    }
    const ReceiverShadows shadows(r, no_occluders);
    const double budget = 2e-2 * exact.sum();
    const Gathered got = gather(split, split.root(), r, ground.normal, shadows, budget);
    EXPECT_LE((got.at_center - exact).abs().sum(), budget) << "trial " << trial;
    ++checked;
  }
  EXPECT_EQ(checked, 50);
}

/// Whether two trees hold the same blocks, every field of every block (a block's corners past
/// its count are not read, and not compared).
void expect_same_blocks(const ShooterTree& a, const ShooterTree& b, const char* what) {
  int k = 0;
  std::vector<std::pair<const Block*, const Block*>> stack = {{&a.root(), &b.root()}};
  while (!stack.empty()) {
    const auto [x, y] = stack.back();
    stack.pop_back();
    ++k;
    ASSERT_EQ(x->corner_count, y->corner_count) << what << ", block " << k;
    for (int c = 0; c < x->corner_count; ++c)
      EXPECT_EQ(x->corners[static_cast<size_t>(c)], y->corners[static_cast<size_t>(c)]) << what << ", block " << k;
    EXPECT_EQ(x->center, y->center) << what;
    EXPECT_EQ(x->diagonal_m, y->diagonal_m) << what;
    EXPECT_EQ(x->area_m2, y->area_m2) << what;
    EXPECT_EQ(x->radius_m, y->radius_m) << what;
    EXPECT_TRUE((x->unshot_w_m2 == y->unshot_w_m2).all() && (x->lowest_w_m2 == y->lowest_w_m2).all() &&
                (x->highest_w_m2 == y->highest_w_m2).all())
        << what << ", block " << k;
    EXPECT_EQ(x->dipole, y->dipole) << what;
    EXPECT_EQ(x->area_moment, y->area_moment) << what;
    for (size_t c = 0; c < 3; ++c) EXPECT_EQ(x->quadrupole[c], y->quadrupole[c]) << what;
    EXPECT_EQ(x->uniform, y->uniform) << what;
    ASSERT_EQ(x->child_count, y->child_count) << what << ", block " << k;
    EXPECT_EQ(x->first_child < 0, y->first_child < 0) << what;
    for (int c = 0; c < x->child_count; ++c)
      stack.push_back({&a.block(x->first_child + c), &b.block(y->first_child + c)});
  }
  EXPECT_GT(k, 10) << what;
}

TEST(ShooterTree, AnEarlierTreesStorageGivesTheSameBlocksAsFreshOne) {
  // The solver builds each shot's tree in the blocks of the last (ShooterTree::release()),
  // without clearing them: a triangle's tree (cells of two elements: blocks of 3 and 5 corners)
  // built in a quad's storage and the other way round, against the same trees built fresh.
  LinearPlate plate(7);
  Scene triangles = testing_support::as_triangles(plate.scene);
  const Mesh triangle_mesh = make_grid_mesh(triangles, {13, 1});  // round(13 / sqrt 2) = 9 cells an edge
  const MeshSurface& triangle_side = triangle_mesh.surfaces[0];
  std::vector<Rgb> triangle_unshot;
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(0, 1);
  for (size_t k = 0; k < triangle_side.elements.size(); ++k) triangle_unshot.push_back(Rgb(u(rng), u(rng), u(rng)));
  const auto triangle_tree = [&](std::vector<Block> storage) {
    return ShooterTree(triangles.surfaces[0], triangle_side, triangle_unshot, 0, 0, triangle_side.nu, triangle_side.nv,
                       std::move(storage));
  };
  const auto quad_tree = [&](std::vector<Block> storage) {
    return ShooterTree(plate.scene.surfaces[0], plate.side(), plate.unshot, 0, 0, plate.side().nu, plate.side().nv,
                       std::move(storage));
  };
  {
    const ShooterTree t = triangle_tree({});
    int threes = 0, fives = 0;
    visit_blocks(t, t.root(), [&](const Block& b) {
      threes += b.corner_count == 3 ? 1 : 0;
      fives += b.corner_count == 5 ? 1 : 0;
    });
    EXPECT_GT(threes, 9);  // the lower and upper halves of cells along the hypotenuse
    EXPECT_GT(fives, 0);   // boxes cut by it
  }
  expect_same_blocks(quad_tree(triangle_tree({}).release()), quad_tree({}), "quad in a triangle's storage");
  expect_same_blocks(triangle_tree(quad_tree({}).release()), triangle_tree({}), "triangle in a quad's storage");
  EXPECT_EQ(ShooterTree::block_count(triangle_side, nullptr, 0, 0, triangle_side.nu, triangle_side.nv),
            blocks_of(triangle_tree({})));
  EXPECT_EQ(ShooterTree::block_count(plate.side(), nullptr, 0, 0, plate.side().nu, plate.side().nv),
            blocks_of(quad_tree({})));
  // A tree of one cell, then a large one, in the same storage.
  const ShooterTree one(plate.scene.surfaces[0], plate.side(), plate.unshot, 2, 1, 3, 2);
  EXPECT_EQ(one.root().child_count, 0);
  expect_same_blocks(triangle_tree(ShooterTree(one).release()), triangle_tree({}), "triangle after one cell");
}

}  // namespace shooter_tree_test
}  // namespace radrecon
