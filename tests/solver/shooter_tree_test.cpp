// The shooting hierarchy of progressive refinement (solver/shooter_tree.h) against closed forms:
// the form factor's upper bound against Lambert's formula, and the blocks' linear fit of the
// unshot radiosity against radiosity that is linear by construction.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "mesh/grid_mesh.h"
#include "solver/form_factor.h"
#include "solver/shooter_tree.h"
#include "support/scenes.h"

namespace radrecon {
namespace shooter_tree_test {

using testing_support::quad;

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
    Block block;
    block.corners = {origin, origin + a, origin + a + b, origin + b, Vec3::Zero()};
    block.corner_count = 4;
    block.center = origin + 0.5 * (a + b);
    block.area_m2 = a.cross(b).norm();
    for (int k = 0; k < 4; ++k) block.radius_m = std::max(block.radius_m, (block.corners[k] - block.center).norm());
    const Vec3 p = block.center + 3 * Vec3(u(rng), u(rng), u(rng)), n = direction();
    ConvexPolygon polygon;
    for (int k = 0; k < 4; ++k) polygon.push(block.corners[k]);
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

TEST(ShooterTree, LinearRadiosityIsFittedExactlyByEveryBlock) {
  // 7 x 4 elements: blocks of odd sizes, and blocks one element wide (a singular second moment).
  const LinearPlate plate(7);
  ASSERT_EQ(plate.side().nu, 7);
  ASSERT_EQ(plate.side().nv, 4);
  const ShooterTree tree = plate.tree();
  // Summed over channels, the norms of (2, 3), (2, 0) and (0, 3) times (1, 2, 3).
  const double full = std::sqrt(13.0) * 6, along_x = 2.0 * 6, along_y = 3.0 * 6;
  const double dx = 2.0 / 7, dy = 1.0 / 4;
  int blocks = 0, wide = 0;
  visit_blocks(tree, tree.root(), [&](const Block& b) {
    ++blocks;
    EXPECT_LT(b.fit_residual_w_m2, 1e-12) << "block " << blocks;
    double x0 = b.corners[0].x(), x1 = x0, y0 = b.corners[0].y(), y1 = y0;
    for (int k = 1; k < b.corner_count; ++k) {
      x0 = std::min(x0, b.corners[k].x()), x1 = std::max(x1, b.corners[k].x());
      y0 = std::min(y0, b.corners[k].y()), y1 = std::max(y1, b.corners[k].y());
    }
    const bool columns = x1 - x0 > 1.5 * dx, rows = y1 - y0 > 1.5 * dy;
    // A block one element wide sees the gradient along its length only (the pseudo-inverse); a
    // single element none.
    const double expected = columns && rows ? full : columns ? along_x : rows ? along_y : 0.0;
    wide += columns && rows ? 1 : 0;
    EXPECT_NEAR(b.gradient_w_m3, expected, 1e-9 * full) << "block " << blocks;
  });
  EXPECT_GT(blocks, 20);
  EXPECT_GT(wide, 2);
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

}  // namespace shooter_tree_test
}  // namespace radrecon
