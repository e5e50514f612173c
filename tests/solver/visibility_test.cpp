// Exact visible form factors against brute-force quadrature with an independent ray caster.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <span>

#include "core/tolerances.h"
#include "solver/form_factor.h"
#include "solver/shadow_subtraction.h"
#include "solver/visibility.h"
#include "support/ray_scene.h"

namespace radrecon {
namespace visibility_test {

using testing_support::visible;

/// The midpoint rule on an N x N grid has an O(1/N) error where a shadow edge cuts the shooter;
/// at N = 500 that is below 1e-3 of the unoccluded form factor here.
constexpr int kQuadratureN = 500;
constexpr double kBruteForceRelative = 2e-3;

Surface make_quad(const std::string& name, const Vec3& c0, const Vec3& c1, const Vec3& c2, const Vec3& c3) {
  Surface s;
  s.name = name;
  s.corners = {c0, c1, c2, c3};
  return s;
}

/// F(dA -> visible part of `shooter`) by the midpoint rule over the shooter, with the ray caster.
double brute_force(const Scene& scene, size_t shooter, const Vec3& p, const Vec3& n, size_t receiver) {
  return testing_support::brute_force_form_factor(scene, shooter, p, n, receiver, kQuadratureN);
}

double exact(const Scene& scene, size_t shooter, const Vec3& p, const Vec3& n, size_t receiver) {
  const std::vector<Occluder> occ = make_occluders(scene);
  std::vector<const Occluder*> others;
  for (const Occluder& o : occ)
    if (o.scene_surface != shooter && o.scene_surface != receiver) others.push_back(&o);
  ConvexPolygon poly;
  for (const Vec3& c : scene.surfaces[shooter].corners) poly.push(c);
  return visible_form_factor(p, n, poly, scene.surfaces[shooter].normal(), others);
}

/// A random rectangle centred at c with random orientation, sides in [0.2, 0.8].
Surface random_occluder(std::mt19937& rng, const Vec3& c, int index) {
  std::uniform_real_distribution<double> side(0.2, 0.8), angle(0, 2 * std::numbers::pi), tilt(-1.2, 1.2);
  const double a = side(rng), b = side(rng);
  Eigen::Matrix3d rot = (Eigen::AngleAxisd(angle(rng), Vec3::UnitZ()) * Eigen::AngleAxisd(tilt(rng), Vec3::UnitX()))
                            .toRotationMatrix();
  const Vec3 u = rot * Vec3(a / 2, 0, 0), v = rot * Vec3(0, b / 2, 0);
  return make_quad("occluder" + std::to_string(index), c - u - v, c + u - v, c + u + v, c - u + v);
}

TEST(VisibleFormFactor, MatchesBruteForceWithRandomOccluders) {
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> xy(-0.5, 1.5), occ_xy(0.0, 1.0), occ_z(0.5, 1.5);
  int occluded_cases = 0;
  for (int trial = 0; trial < 24; ++trial) {
    Scene scene;
    // Receiver plane z = 0 (facing up), shooter: unit square at z = 2 facing down.
    scene.surfaces.push_back(make_quad("floor", {-2, -2, 0}, {3, -2, 0}, {3, 3, 0}, {-2, 3, 0}));
    scene.surfaces.push_back(make_quad("light", {0, 0, 2}, {0, 1, 2}, {1, 1, 2}, {1, 0, 2}));
    const int occluders = 1 + trial % 3;
    for (int k = 0; k < occluders; ++k)
      scene.surfaces.push_back(random_occluder(rng, Vec3(occ_xy(rng), occ_xy(rng), occ_z(rng)), k));
    const Vec3 p(xy(rng), xy(rng), 0), n = Vec3::UnitZ();
    const double f_exact = exact(scene, 1, p, n, 0);
    const double f_brute = brute_force(scene, 1, p, n, 0);
    ConvexPolygon light;
    for (const Vec3& c : scene.surfaces[1].corners) light.push(c);
    const double f_open = lambert_form_factor(p, n, light);
    EXPECT_NEAR(f_exact, f_brute, kBruteForceRelative * f_open)
        << "trial " << trial << ": exact " << f_exact << ", brute force " << f_brute << ", unoccluded " << f_open;
    if (f_exact < 0.98 * f_open) ++occluded_cases;
  }
  EXPECT_GE(occluded_cases, 12) << "the random cases should mostly be partly occluded";
}

TEST(VisibleFormFactors, FourPointsAtOnceMatchBruteForceAndOneByOne) {
  // Points that see all of the light (one vectorised integral) and points partly or wholly in
  // shadow (one by one) in the same batches.
  std::mt19937 rng(77);
  std::uniform_real_distribution<double> xy(-0.5, 1.5), occ_xy(0.0, 1.0), occ_z(0.5, 1.5);
  int occluded = 0, open = 0;
  for (int trial = 0; trial < 6; ++trial) {
    Scene scene;
    scene.surfaces.push_back(make_quad("floor", {-2, -2, 0}, {3, -2, 0}, {3, 3, 0}, {-2, 3, 0}));
    scene.surfaces.push_back(make_quad("light", {0, 0, 2}, {0, 1, 2}, {1, 1, 2}, {1, 0, 2}));
    scene.surfaces.push_back(random_occluder(rng, Vec3(occ_xy(rng), occ_xy(rng), occ_z(rng)), 0));
    const std::vector<Occluder> occ = make_occluders(scene);
    const std::vector<const Occluder*> others = {&occ[2]};
    ConvexPolygon light;
    for (const Vec3& c : scene.surfaces[1].corners) light.push(c);
    const Vec3 n = Vec3::UnitZ(), down = scene.surfaces[1].normal();
    std::vector<Vec3> points(5 + trial % 3);  // a batch of four and a partial one
    for (Vec3& p : points) p = Vec3(xy(rng), xy(rng), 0);
    std::vector<double> batch(points.size());
    visible_form_factors(points, n, light, down, others, batch);
    for (size_t k = 0; k < points.size(); ++k) {
      const double one = visible_form_factor(points[k], n, light, down, others);
      const double unoccluded = lambert_form_factor(points[k], n, light);
      EXPECT_NEAR(batch[k], one, 1e-13 * unoccluded) << "trial " << trial << " point " << k;
      EXPECT_NEAR(batch[k], brute_force(scene, 1, points[k], n, 0), kBruteForceRelative * unoccluded)
          << "trial " << trial << " point " << k;
      (one < 0.98 * unoccluded ? occluded : open) += 1;
    }
  }
  EXPECT_GE(occluded, 5);
  EXPECT_GE(open, 5);
  // A point that is not a number sees nothing, in a batch as alone.
  ConvexPolygon light;
  for (const Vec3& c : {Vec3(0, 0, 2), Vec3(0, 1, 2), Vec3(1, 1, 2), Vec3(1, 0, 2)}) light.push(c);
  const std::vector<Vec3> odd = {Vec3(0.5, 0.5, 0), Vec3(std::nan(""), 0.5, 0)};
  std::vector<double> f(odd.size());
  visible_form_factors(odd, Vec3::UnitZ(), light, -Vec3::UnitZ(), {}, f);
  EXPECT_GT(f[0], 0.0);
  EXPECT_EQ(f[1], visible_form_factor(odd[1], Vec3::UnitZ(), light, -Vec3::UnitZ(), {}));
  EXPECT_EQ(f[1], 0.0);
}

TEST(VisibleFormFactor, FullyHiddenIsZeroAndUnrelatedOccluderChangesNothing) {
  Scene scene;
  scene.surfaces.push_back(make_quad("floor", {-2, -2, 0}, {3, -2, 0}, {3, 3, 0}, {-2, 3, 0}));
  scene.surfaces.push_back(make_quad("light", {0, 0, 2}, {0, 1, 2}, {1, 1, 2}, {1, 0, 2}));
  scene.surfaces.push_back(make_quad("roof", {-5, -5, 1}, {5, -5, 1}, {5, 5, 1}, {-5, 5, 1}));
  EXPECT_EQ(exact(scene, 1, Vec3(0.5, 0.5, 0), Vec3::UnitZ(), 0), 0.0);
  scene.surfaces[2] = make_quad("far", {10, 10, 1}, {11, 10, 1}, {11, 11, 1}, {10, 11, 1});
  ConvexPolygon light;
  for (const Vec3& c : scene.surfaces[1].corners) light.push(c);
  EXPECT_EQ(exact(scene, 1, Vec3(0.3, 0.2, 0), Vec3::UnitZ(), 0),
            lambert_form_factor(Vec3(0.3, 0.2, 0), Vec3::UnitZ(), light));
}

TEST(VisibleFormFactor, HalfCoveredByAnOccluderAtHalfHeight) {
  // An occluder at z = 1 covering x < 0.5 of the light's shadow cone from the point below the
  // light's centre hides exactly the half x < 0.5 of the light; by symmetry F halves.
  Scene scene;
  scene.surfaces.push_back(make_quad("floor", {-2, -2, 0}, {3, -2, 0}, {3, 3, 0}, {-2, 3, 0}));
  scene.surfaces.push_back(make_quad("light", {0, 0, 2}, {0, 1, 2}, {1, 1, 2}, {1, 0, 2}));
  scene.surfaces.push_back(make_quad("blind", {-1, -1, 1}, {0.5, -1, 1}, {0.5, 2, 1}, {-1, 2, 1}));
  const Vec3 p(0.5, 0.5, 0);
  ConvexPolygon light;
  for (const Vec3& c : scene.surfaces[1].corners) light.push(c);
  EXPECT_NEAR(exact(scene, 1, p, Vec3::UnitZ(), 0), 0.5 * lambert_form_factor(p, Vec3::UnitZ(), light), 1e-15);
}

TEST(VisibleFormFactor, ZeroBehindTheShooter) {
  ConvexPolygon light;
  for (const Vec3& c : {Vec3(0, 0, 2), Vec3(0, 1, 2), Vec3(1, 1, 2), Vec3(1, 0, 2)}) light.push(c);
  // The light faces -z; a point above it sees its back.
  EXPECT_EQ(visible_form_factor(Vec3(0.5, 0.5, 3), -Vec3::UnitZ(), light, -Vec3::UnitZ(), {}), 0.0);
}

}  // namespace visibility_test
}  // namespace radrecon

namespace radrecon {
namespace visibility_test {

TEST(VisibleFormFactor, ManyVertexFragmentsAreCutAndStayAdditive) {
  // A 36-gon shooter (near kCapacity: the general path cuts it in two before clipping) seen past
  // two overlapping occluders, against the sum over its two halves, each small enough to be
  // clipped whole: form factors add up over disjoint pieces.
  const int kSides = 36;
  ConvexPolygon disc, half_a, half_b;
  for (int i = 0; i < kSides; ++i) {
    const double a = -2 * std::numbers::pi * i / kSides;  // clockwise from above: faces down
    disc.push(Vec3(std::cos(a), std::sin(a), 2));
  }
  for (int i = 0; i <= kSides / 2; ++i) half_a.push(disc.v[i]);
  for (int i = kSides / 2; i < kSides; ++i) half_b.push(disc.v[i]);
  half_b.push(disc.v[0]);
  const Vec3 down(0, 0, -1), p(0.1, -0.05, 0), n(0, 0, 1);
  Scene scene;
  scene.surfaces.push_back(make_quad("o1", {-0.3, -0.2, 1}, {0.2, -0.2, 1}, {0.2, 0.3, 1}, {-0.3, 0.3, 1}));
  scene.surfaces.push_back(make_quad("o2", {-0.1, -0.4, 1.3}, {0.4, -0.3, 1.3}, {0.3, 0.2, 1.3}, {-0.2, 0.1, 1.3}));
  const std::vector<Occluder> occ = make_occluders(scene);
  const std::vector<const Occluder*> both = {&occ[0], &occ[1]};
  const double whole = visible_form_factor(p, n, disc, down, both);
  const double halves = visible_form_factor(p, n, half_a, down, both) + visible_form_factor(p, n, half_b, down, both);
  const double unoccluded = visible_form_factor(p, n, disc, down, {});
  EXPECT_NEAR(whole, halves, 1e-13) << "whole " << whole << ", halves " << halves;
  EXPECT_GT(whole, 0.1 * unoccluded);
  EXPECT_LT(whole, 0.9 * unoccluded);
}

TEST(VisibleFormFactor, ManySmallOccludersHideExactlyTheirProjections) {
  // 144 small tilted squares at heights 0.8 to 1.2 between p and a 2 x 2 shooter at z = 2, their
  // projections from p onto the shooter disjoint and inside it (a model's small triangles seen
  // against a light): the visible form factor is the shooter's less each projection's, each
  // by Lambert's formula on its own. The shadows' fragments are passed over where their boxes
  // miss a shadow's trace; this checks that none is passed over that the shadow cuts. The same
  // scene turned (a tilted shooter: the plane's other coordinate axes) gives the same.
  const Eigen::Matrix3d turns[2] = {Eigen::Matrix3d::Identity(),
                                    Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix()};
  for (const Eigen::Matrix3d& turn : turns) {
    const Vec3 p0(0.1, -0.05, 0);
    const Vec3 p = turn * p0, n = turn * Vec3(0, 0, 1), down = turn * Vec3(0, 0, -1);
    ConvexPolygon shooter;
    for (const Vec3& c : {Vec3(-1, -1, 2), Vec3(-1, 1, 2), Vec3(1, 1, 2), Vec3(1, -1, 2)}) shooter.push(turn * c);
    Scene scene;
    std::mt19937 rng(21);
    std::uniform_real_distribution<double> height(0.8, 1.2), angle(0, std::numbers::pi / 2), tilt(-0.4, 0.4);
    double hidden = 0;
    for (int j = 0; j < 12; ++j)
      for (int i = 0; i < 12; ++i) {
        const double z = height(rng);
        // Cell (i, j) of a 12 x 12 grid over the shooter, brought down to height z along the ray
        // from p, with room around it: the projections stay apart.
        const Vec3 target(-1 + (i + 0.5) / 6, -1 + (j + 0.5) / 6, 2);
        const Vec3 c = p0 + (z - p0.z()) / (2 - p0.z()) * (target - p0);
        const double half = 0.25 / 6 * (z - p0.z()) / (2 - p0.z());
        const Eigen::Matrix3d rot =
            (Eigen::AngleAxisd(angle(rng), Vec3::UnitZ()) * Eigen::AngleAxisd(tilt(rng), Vec3::UnitX())).toRotationMatrix();
        const Vec3 u = rot * Vec3(half, 0, 0), v = rot * Vec3(0, half, 0);
        const std::array<Vec3, 4> corners = {c - u - v, c + u - v, c + u + v, c - u + v};
        ConvexPolygon projection;
        for (const Vec3& corner : corners) projection.push(turn * (p0 + (2 - p0.z()) / (corner.z() - p0.z()) * (corner - p0)));
        hidden += lambert_form_factor(p, n, projection);
        scene.surfaces.push_back(make_quad("o" + std::to_string(scene.surfaces.size()), turn * corners[0],
                                           turn * corners[1], turn * corners[2], turn * corners[3]));
      }
    const std::vector<Occluder> occ = make_occluders(scene);
    std::vector<const Occluder*> all;
    for (const Occluder& o : occ) all.push_back(&o);
    const double unoccluded = lambert_form_factor(p, n, shooter);
    const double seen = visible_form_factor(p, n, shooter, down, all);
    EXPECT_NEAR(seen, unoccluded - hidden, 1e-12 * unoccluded) << "hidden " << hidden / unoccluded << " of it";
    EXPECT_GT(hidden, 0.05 * unoccluded);
  }
}

/// A 2 x 2 shooter at z = 2 facing down, and `count` random small squares between it and the
/// floor (heights 0.6 to 1.6, over [-1.2, 1.2]^2), overlapping one another as a model's triangles
/// do.
struct ManyOccluders {
  ConvexPolygon shooter;
  Vec3 down{0, 0, -1};
  Scene scene;  ///< the occluders as surfaces, for the ray caster
  std::vector<Occluder> occluders;
  std::vector<const Occluder*> all;
  explicit ManyOccluders(int count, unsigned seed) {
    for (const Vec3& c : {Vec3(-1, -1, 2), Vec3(-1, 1, 2), Vec3(1, 1, 2), Vec3(1, -1, 2)}) shooter.push(c);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> xy(-1.2, 1.2), z(0.6, 1.6), half(0.03, 0.12), angle(0, std::numbers::pi),
        tilt(-0.8, 0.8);
    for (int k = 0; k < count; ++k) {
      const Vec3 c(xy(rng), xy(rng), z(rng));
      const Eigen::Matrix3d rot =
          (Eigen::AngleAxisd(angle(rng), Vec3::UnitZ()) * Eigen::AngleAxisd(tilt(rng), Vec3::UnitX())).toRotationMatrix();
      const Vec3 u = rot * Vec3(half(rng), 0, 0), v = rot * Vec3(0, half(rng), 0);
      scene.surfaces.push_back(make_quad("o" + std::to_string(k), c - u - v, c + u - v, c + u + v, c - u + v));
    }
    occluders = make_occluders(scene);
    for (const Occluder& o : occluders) all.push_back(&o);
  }
  /// Cell (i, j) of an m x m grid over the shooter, in the shooter's order of corners.
  ConvexPolygon cell(int i, int j, int m) const {
    const double a = 2.0 / m;
    ConvexPolygon q;
    const double x0 = -1 + i * a, y0 = -1 + j * a;
    for (const Vec3& c : {Vec3(x0, y0, 2), Vec3(x0, y0 + a, 2), Vec3(x0 + a, y0 + a, 2), Vec3(x0 + a, y0, 2)}) q.push(c);
    return q;
  }
};

TEST(VisibleFragments, EachPartOfThePatchAsVisibleFormFactorPastFindsItAlone) {
  // The fragments the point sees of the whole shooter, clipped to each cell of 1 x 1 to 8 x 8
  // grids over it, against the shadows subtracted from each cell on its own: the same form
  // factor to round-off, and the same verdict on whether the cell is seen in part. Points
  // below the occluders, some tilted so that their horizon cuts the shooter; the cells' sums
  // give the whole shooter's (additivity).
  const ManyOccluders scene(150, 7);
  int horizon_cuts = 0;
  const std::array<std::pair<Vec3, Vec3>, 5> points = {{{Vec3(0.1, -0.05, 0), Vec3(0, 0, 1)},
                                                        {Vec3(-0.6, 0.4, 0.2), Vec3(0, 0, 1)},
                                                        {Vec3(0.3, 0.2, 0.1), Vec3(0.9, 0, 0.3).normalized()},
                                                        {Vec3(-0.2, -0.7, 0.3), Vec3(0, -0.8, 0.6)},
                                                        {Vec3(0.9, 0.9, 0.4), Vec3(-0.3, -0.4, 0.866).normalized()}}};
  int kept = 0, partly = 0, whole = 0;
  for (const auto& [p, n] : points) {
    std::vector<ShadowVolume> volumes;
    shadow_volumes(p, n, scene.all, volumes);
    VisibleFragments fragments;
    if (!fragments.find(p, n, scene.shooter, scene.down, volumes)) continue;
    ++kept;
    bool cut = false;
    for (int i = 0; i < scene.shooter.n; ++i) cut = cut || n.dot(scene.shooter.v[i] - p) < 0;
    horizon_cuts += cut;
    const double open = lambert_form_factor(p, n, clip_to_horizon(p, n, scene.shooter));
    for (int m : {1, 2, 3, 8}) {
      double sum = 0;
      for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; ++i) {
          const ConvexPolygon cell = scene.cell(i, j, m);
          bool partly_alone = false, partly_kept = false;
          const double alone = visible_form_factor_past(p, n, cell, scene.down, volumes, &partly_alone);
          const double from_kept = fragments.form_factor(cell, &partly_kept);
          EXPECT_NEAR(from_kept, alone, 1e-12 * open) << "cell " << i << "," << j << " of " << m;
          EXPECT_EQ(partly_kept, partly_alone) << "cell " << i << "," << j << " of " << m << ": " << alone;
          sum += from_kept;
          partly += partly_alone;
          whole += !partly_alone && alone > 0;
        }
      EXPECT_NEAR(sum, visible_form_factor_past(p, n, scene.shooter, scene.down, volumes), 1e-12 * open);
    }
  }
  EXPECT_EQ(kept, static_cast<int>(points.size())) << "every point should see many shadows on the shooter";
  EXPECT_GE(horizon_cuts, 2) << "some points' horizons should cut the shooter";
  EXPECT_GT(partly, 50);
  EXPECT_GT(whole, 20) << "some cells should be seen whole, between the shadows";
}

TEST(VisibleFragments, SlowEachCellAsTheRayCasterSeesIt) {
  // An independent answer: the midpoint rule over each cell with every point's visibility by the
  // ray caster (tests/support/ray_scene.h), past 150 overlapping occluders; its error is O(1/N)
  // where shadow edges cross the cell (here within 2e-4 of the unoccluded form factor). A
  // fragment lost or counted twice would show.
  constexpr int kN = 300;
  const ManyOccluders scene(150, 11);
  for (const auto& [p, n] : {std::pair{Vec3(0.1, -0.05, 0), Vec3(0, 0, 1)},
                             std::pair{Vec3(-0.4, 0.3, 0.2), Vec3(0.5, 0, 0.866).normalized()}}) {
    std::vector<ShadowVolume> volumes;
    shadow_volumes(p, n, scene.all, volumes);
    VisibleFragments fragments;
    ASSERT_TRUE(fragments.find(p, n, scene.shooter, scene.down, volumes));
    int shadowed = 0;
    for (const auto& [i, j] : {std::pair{0, 0}, std::pair{1, 2}, std::pair{2, 1}, std::pair{3, 3}}) {
      const ConvexPolygon cell = scene.cell(i, j, 4);
      Scene with_cell = scene.scene;
      with_cell.surfaces.push_back(make_quad("cell", cell.v[0], cell.v[1], cell.v[2], cell.v[3]));
      const size_t shooter = with_cell.surfaces.size() - 1, no_receiver = with_cell.surfaces.size();
      const double brute = testing_support::brute_force_form_factor(with_cell, shooter, p, n, no_receiver, kN);
      const double open = lambert_form_factor(p, n, clip_to_horizon(p, n, cell));
      const double from_kept = fragments.form_factor(cell);
      EXPECT_NEAR(from_kept, brute, 2e-3 * open) << "cell " << i << "," << j << ": unoccluded " << open;
      shadowed += from_kept < 0.95 * open;
    }
    EXPECT_GE(shadowed, 2) << "the cells should be shadowed";
  }
}

TEST(VisibleFragments, ManyVolumesButFewShadowsOnThePatchKeepNothing) {
  // 40 occluders beside the shooter's shaft (their volumes exist, their shadows miss the
  // shooter) and 5 in it: fewer than tol::kKeptFragmentsShadows shadows meet the shooter.
  ManyOccluders scene(5, 4);
  Scene beside;
  for (int k = 0; k < 40; ++k) {
    const double x = 3 + 0.1 * k;
    beside.surfaces.push_back(make_quad("b" + std::to_string(k), {x, -0.1, 1}, {x, 0.1, 1}, {x + 0.05, 0.1, 1}, {x + 0.05, -0.1, 1}));
  }
  const std::vector<Occluder> far = make_occluders(beside);
  for (const Occluder& o : far) scene.all.push_back(&o);
  const Vec3 p(0, 0, 0), n(0, 0, 1);
  std::vector<ShadowVolume> volumes;
  shadow_volumes(p, n, scene.all, volumes);
  ASSERT_GE(volumes.size(), tol::kKeptFragmentsShadows);
  VisibleFragments fragments;
  EXPECT_FALSE(fragments.find(p, n, scene.shooter, scene.down, volumes));
}

TEST(VisibleFragments, FewShadowsKeepNothingAndAPointBehindSeesNothing) {
  const ManyOccluders scene(150, 7);
  const Vec3 p(0.1, -0.05, 0), n(0, 0, 1);
  std::vector<ShadowVolume> volumes;
  shadow_volumes(p, n, scene.all, volumes);
  VisibleFragments fragments;
  // Fewer shadows than tol::kKeptFragmentsShadows on the shooter: each part costs less alone.
  const std::span<const ShadowVolume> few(volumes.data(), tol::kKeptFragmentsShadows - 1);
  EXPECT_FALSE(fragments.find(p, n, scene.shooter, scene.down, few));
  // Above the shooter's plane: every part is out of sight.
  const Vec3 above(0, 0, 2.5);
  shadow_volumes(above, n, scene.all, volumes);
  ASSERT_TRUE(fragments.find(above, n, scene.shooter, scene.down, volumes));
  bool partly = true;
  EXPECT_EQ(fragments.form_factor(scene.cell(1, 1, 4), &partly), 0.0);
  EXPECT_FALSE(partly);
}

TEST(VisibleFragments, ACellHiddenWholeGivesZeroAndIsNotSeenInPart) {
  // Many small occluders, and a large square just under the shooter's corner cell (of a 4 x 4
  // grid): that cell is wholly hidden (0, not seen in part, as visible_form_factor_past() has
  // it), its neighbour partly.
  ManyOccluders scene(60, 3);
  Scene big;
  big.surfaces.push_back(make_quad("lid", {-1.2, -1.2, 1.9}, {-1.2, -0.45, 1.9}, {-0.45, -0.45, 1.9}, {-0.45, -1.2, 1.9}));
  const std::vector<Occluder> lid = make_occluders(big);
  scene.all.push_back(&lid[0]);
  const Vec3 p(-0.7, -0.7, 0), n(0, 0, 1);
  std::vector<ShadowVolume> volumes;
  shadow_volumes(p, n, scene.all, volumes);
  VisibleFragments fragments;
  ASSERT_TRUE(fragments.find(p, n, scene.shooter, scene.down, volumes));
  bool partly = true;
  EXPECT_EQ(fragments.form_factor(scene.cell(0, 0, 4), &partly), 0.0);
  EXPECT_FALSE(partly);
  bool partly_alone = false;
  const double alone = visible_form_factor_past(p, n, scene.cell(1, 0, 4), scene.down, volumes, &partly_alone);
  EXPECT_NEAR(fragments.form_factor(scene.cell(1, 0, 4), &partly), alone, 1e-12);
  EXPECT_TRUE(partly);
  EXPECT_TRUE(partly_alone);
}

/// Howell's C-11: F between directly opposed parallel rectangles a x b (metres) at distance c.
double parallel_rectangles(double a, double b, double c) {
  const double X = a / c, Y = b / c, sx = std::sqrt(1 + X * X), sy = std::sqrt(1 + Y * Y);
  return 2 / (std::numbers::pi * X * Y) *
         (std::log(sx * sy / std::sqrt(1 + X * X + Y * Y)) + X * sy * std::atan(X / sy) + Y * sx * std::atan(Y / sx) -
          X * std::atan(X) - Y * std::atan(Y));
}

/// Howell's C-14: F from a rectangle of width w to a perpendicular one of height h sharing its
/// edge of length l (metres).
double perpendicular_rectangles(double w, double h, double l) {
  const double W = w / l, H = h / l, W2 = W * W, H2 = H * H, S = std::sqrt(W2 + H2);
  const double log_term = std::log((1 + W2) * (1 + H2) / (1 + W2 + H2)) +
                          W2 * std::log(W2 * (1 + W2 + H2) / ((1 + W2) * (W2 + H2))) +
                          H2 * std::log(H2 * (1 + H2 + W2) / ((1 + H2) * (H2 + W2)));
  return (W * std::atan(1 / W) + H * std::atan(1 / H) - S * std::atan(1 / S) + 0.25 * log_term) /
         (std::numbers::pi * W);
}

/// The cubature's tolerance in these tests, and the bound on its result: the errors of the
/// accepted squares add up, some tens of them near a shared edge's corners.
constexpr double kAreaTolerance = 1e-7;
constexpr double kAreaAbsolute = 1e-5;

TEST(AreaVisibleFormFactor, ParallelRectanglesMatchHowell) {
  const std::vector<const Occluder*> none;
  for (const auto& [a, b, c] : {std::array<double, 3>{1, 1, 1}, {2, 0.5, 0.3}, {0.1, 0.1, 0.05}, {0.5, 3, 2}}) {
    // Receiver [0,a] x [0,b] at z = 0 facing up; shooter above it at z = c facing down.
    ConvexPolygon top;
    for (const Vec3& v : {Vec3(0, 0, c), Vec3(0, b, c), Vec3(a, b, c), Vec3(a, 0, c)}) top.push(v);
    const double f = area_visible_form_factor({Vec3(0, 0, 0), Vec3(a, 0, 0), Vec3(a, b, 0), Vec3(0, b, 0)},
                                              Vec3::UnitZ(), top, -Vec3::UnitZ(), none, kAreaTolerance);
    EXPECT_NEAR(f, parallel_rectangles(a, b, c), kAreaAbsolute) << a << " x " << b << " at " << c;
  }
  EXPECT_NEAR(parallel_rectangles(1, 1, 1), 0.19982, 1e-5);  // the published value
}

TEST(AreaVisibleFormFactor, PerpendicularRectanglesSharingAnEdgeMatchHowell) {
  // Where collocation fails: the receiver touches the shooter along their common edge.
  const std::vector<const Occluder*> none;
  for (const auto& [w, h, l] : {std::array<double, 3>{1, 1, 1}, {0.1, 1, 1}, {0.25, 0.25, 0.25}, {2, 0.5, 1.5}}) {
    // Receiver: the floor x in [0, w], y in [0, l] facing up; shooter: the wall x = 0, z in [0, h].
    ConvexPolygon wall;
    for (const Vec3& v : {Vec3(0, 0, 0), Vec3(0, 0, h), Vec3(0, l, h), Vec3(0, l, 0)}) wall.push(v);
    const double f = area_visible_form_factor({Vec3(0, 0, 0), Vec3(w, 0, 0), Vec3(w, l, 0), Vec3(0, l, 0)},
                                              Vec3::UnitZ(), wall, Vec3::UnitX(), none, kAreaTolerance);
    const double expected = perpendicular_rectangles(w, h, l);
    EXPECT_NEAR(f, expected, kAreaAbsolute) << w << " x " << l << " beside " << h;
    // The centre's point form factor, which the cubature replaces, is far off here.
    if (w == h) {
      EXPECT_GT(std::abs(lambert_form_factor(Vec3(w / 2, l / 2, 0), Vec3::UnitZ(), wall) - expected), 0.005);
    }
  }
  EXPECT_NEAR(perpendicular_rectangles(1, 1, 1), 0.20004, 1e-5);  // the published value
}

TEST(AreaVisibleFormFactor, MatchesBruteForceBehindAnOccluder) {
  // A floor element beside a wall with a blind between them (F jumps where the blind's plane
  // crosses the element): the cubature against a fine midpoint rule of the point form factors,
  // which the tests above check against the independent ray caster.
  Scene scene;
  scene.surfaces.push_back(make_quad("floor", {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}));
  scene.surfaces.push_back(make_quad("wall", {0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}));
  scene.surfaces.push_back(make_quad("blind", {0.2, 0.3, 0.1}, {0.2, 0.3, 0.6}, {0.2, 0.8, 0.6}, {0.2, 0.8, 0.1}));
  const std::vector<Occluder> occ = make_occluders(scene);
  const std::vector<const Occluder*> blind = {&occ[2]};
  ConvexPolygon wall;
  for (const Vec3& c : scene.surfaces[1].corners) wall.push(c);
  const std::array<Vec3, 4> element = {Vec3(0, 0.25, 0), Vec3(0.5, 0.25, 0), Vec3(0.5, 0.75, 0), Vec3(0, 0.75, 0)};
  const double f = area_visible_form_factor(element, Vec3::UnitZ(), wall, Vec3::UnitX(), blind, kAreaTolerance);
  constexpr int kN = 40;  // 40 x 40 receiver points; the point form factor is checked above
  double sum = 0;
  for (int i = 0; i < kN; ++i)
    for (int j = 0; j < kN; ++j) {
      const double x = 0.5 * (i + 0.5) / kN, y = 0.25 + 0.5 * (j + 0.5) / kN;
      sum += exact(scene, 1, Vec3(x, y, 0), Vec3::UnitZ(), 0);
    }
  EXPECT_NEAR(f, sum / (kN * kN), 2e-3 * f);
}

}  // namespace visibility_test
}  // namespace radrecon
