// A side's reconstruction with the scene's structure: a box standing on a floor gives the floor
// four barriers and one excluded square; the square is neither sample nor query.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "sampling/solution_reconstruction.h"
#include "sampling/surface_samples.h"
#include "solver/solve.h"
#include "support/scenes.h"

namespace radrecon {
namespace solution_reconstruction_test {

using testing_support::quad;

/// A 4 m floor under a light, with a unit box standing on it over [1, 2] x [1, 2] (walls facing
/// out, and a top).
Scene box_on_floor() {
  Scene s;
  s.name = "box on floor";
  s.surfaces.push_back(quad("floor", {0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, 0.5));
  s.surfaces.push_back(quad("light", {1, 1, 3}, {1, 3, 3}, {3, 3, 3}, {3, 1, 3}, 0, 10));
  s.surfaces.push_back(quad("x0", {1, 1, 0}, {1, 1, 1}, {1, 2, 1}, {1, 2, 0}, 0.5));
  s.surfaces.push_back(quad("x1", {2, 1, 0}, {2, 2, 0}, {2, 2, 1}, {2, 1, 1}, 0.5));
  s.surfaces.push_back(quad("y0", {1, 1, 0}, {2, 1, 0}, {2, 1, 1}, {1, 1, 1}, 0.5));
  s.surfaces.push_back(quad("y1", {1, 2, 0}, {1, 2, 1}, {2, 2, 1}, {2, 2, 0}, 0.5));
  s.surfaces.push_back(quad("top", {1, 1, 1}, {2, 1, 1}, {2, 2, 1}, {1, 2, 1}, 0.5));
  for (Surface& f : s.surfaces) f.max_divisions = 8;
  s.surfaces[0].max_divisions = 16;
  return s;
}

double at(const Interpolant& f, const Vec2& q) {
  std::vector<double> v(static_cast<size_t>(f.channels()));
  f.evaluate(std::span(&q, 1), v);
  return v[0];
}

TEST(SideReconstruction, TheFloorUnderABoxIsNeitherSampleNorQuery) {
  const Scene scene = box_on_floor();
  SolveSettings settings;
  const Solution solution = solve_scene(scene, "grid:16", settings, "test");
  const SurfaceSolution& floor = require_surface(solution, "floor", "test");
  ASSERT_EQ(floor.barriers.size(), 4u);
  ASSERT_EQ(floor.excluded.size(), 1u);
  // The same solution with the cells under the box made very bright: nothing outside may change.
  SurfaceSolution bright = floor;
  for (SolutionElement& e : bright.elements) {
    const Vec2 c((e.u0 + e.u1) * 2, (e.v0 + e.v1) * 2);  // centre, metres (4 m floor)
    if (c.x() > 1 && c.x() < 2 && c.y() > 1 && c.y() < 2) e.radiosity_w_m2 = Rgb::Constant(1e3);
  }
  const std::vector<Vec2> outside = {{0.9, 1.5}, {2.05, 1.2}, {1.5, 0.8}, {1.5, 2.3}, {0.5, 0.5}, {3, 3}};
  for (const bool barriers : {true, false})  // render --no-barriers too: the region still holds
  for (Method m : all_methods()) {
    SCOPED_TRACE(method_name(m) + (barriers ? " with barriers" : " without barriers"));
    const SideSampling sampling{.barriers = barriers};
    const auto plain = reconstruct_side(floor, m, {}, sampling);
    const auto lit = reconstruct_side(bright, m, {}, sampling);
    ASSERT_TRUE(plain.ok()) << plain.reason();
    EXPECT_TRUE(std::isnan(at(*plain.value(), {1.5, 1.5})));  // under the box: no value
    if (m == Method::bicubic) continue;  // its global spline couples distant nodes (barrier_grid.h)
    for (const Vec2& q : outside) EXPECT_EQ(at(*plain.value(), q), at(*lit.value(), q)) << q.transpose();
  }
}

TEST(SolveScene, AnEnclosureAWallFacesIsExcludedOnlyWhereNoLightReachesIt) {
  // The box's walls two-sided, or one of them facing in: they face the floor under the box, but
  // the box is closed and no light reaches there; it stays excluded, as under a box of walls
  // facing out. (Two-sided, it had samples of 0 that methods without barriers blended outside.)
  for (const int variant : {0, 1, 2}) {
    Scene scene = box_on_floor();
    if (variant == 1)
      for (size_t k = 2; k <= 6; ++k) scene.surfaces[k].two_sided = true;
    if (variant == 2) scene.surfaces[3] = quad("x1", {2, 1, 0}, {2, 1, 1}, {2, 2, 1}, {2, 2, 0}, 0.5);  // facing in
    const Solution solution = solve_scene(scene, "grid:16", SolveSettings{}, "test");
    const SurfaceSolution& floor = require_surface(solution, "floor", "test");
    ASSERT_EQ(floor.excluded.size(), 1u) << variant;
    EXPECT_TRUE(in_excluded_region(floor.excluded, {1.5, 1.5})) << variant;
  }
  // A closed room, its walls facing in and standing 1e-7 m inside the floor's edge, its ceiling a
  // lamp: the floor is lit, and none of it is excluded, however coarse the mesh (grid:2 has no
  // element wholly inside the walls).
  const double a = 1e-7, b = 1 - 1e-7;
  Scene room;
  room.surfaces.push_back(quad("floor", {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, 0.5));
  room.surfaces.push_back(quad("lamp", {a, a, 1}, {a, b, 1}, {b, b, 1}, {b, a, 1}, 0.5, 10));
  room.surfaces.push_back(quad("south", {a, a, 0}, {a, a, 1}, {b, a, 1}, {b, a, 0}, 0.5));
  room.surfaces.push_back(quad("east", {b, a, 0}, {b, a, 1}, {b, b, 1}, {b, b, 0}, 0.5));
  room.surfaces.push_back(quad("north", {b, b, 0}, {b, b, 1}, {a, b, 1}, {a, b, 0}, 0.5));
  room.surfaces.push_back(quad("west", {a, b, 0}, {a, b, 1}, {a, a, 1}, {a, a, 0}, 0.5));
  for (const char* mesh : {"grid:8", "grid:2"}) {
    const Solution solution = solve_scene(room, mesh, SolveSettings{}, "test");
    const SurfaceSolution& floor = require_surface(solution, "floor", "test");
    EXPECT_EQ(floor.barriers.size(), 4u) << mesh;
    EXPECT_TRUE(floor.excluded.empty()) << mesh;
  }
}

TEST(SideReconstruction, GouraudOnASideWhoseEveryCellIsCentredInAnExcludedRegionDrawsTheCells) {
  // A region over every cell centre but not the whole side (a coarse quadtree's one ceiling leaf
  // under a lamp lying on it): the cells are drawn as they are outside the region, as constant
  // draws them, not left without a value; inside it, no value.
  const Solution solution = solve_scene(box_on_floor(), "grid:2", SolveSettings{}, "test");
  SurfaceSolution floor = require_surface(solution, "floor", "test");
  ASSERT_EQ(floor.elements.size(), 4u);
  floor.excluded = {{{0.1, 0.1}, {3.9, 0.1}, {3.9, 3.9}, {0.1, 3.9}}};
  const auto gouraud = reconstruct_side(floor, Method::gouraud, {}, SideSampling{});
  ASSERT_TRUE(gouraud.ok()) << gouraud.reason();
  // The corner (0, 0) lies in one cell: the vertex mean there is that cell's value.
  const SolutionElement& corner_cell = *std::find_if(floor.elements.begin(), floor.elements.end(),
                                                      [](const SolutionElement& e) { return e.u0 == 0 && e.v0 == 0; });
  EXPECT_NEAR(at(*gouraud.value(), {0, 0}), corner_cell.radiosity_w_m2[0], 1e-12);
  EXPECT_TRUE(std::isnan(at(*gouraud.value(), {2, 2})));
}

TEST(SideReconstruction, ATrianglesSideReconstructsInItsMetricFrame) {
  // A light over a floor of two triangles; a triangle's (s, t) is an isometry of its plane: the
  // distance between two element centroids in (s, t) is their distance in space.
  Scene scene;
  scene.name = "triangles";
  scene.surfaces.push_back(quad("floor", {0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, 0.5));
  scene.surfaces.push_back(quad("light", {1, 1, 3}, {1, 3, 3}, {3, 3, 3}, {3, 1, 3}, 0, 10));
  scene = testing_support::as_triangles(scene);
  const Solution solution = solve_scene(scene, "grid:11", SolveSettings{}, "test");  // 8 cells an edge
  const SurfaceSolution& side = require_surface(solution, "floor.b", "test");  // (0,0), (4,4), (0,4)
  ASSERT_TRUE(side.triangle);
  const ScatteredSamples centres = element_centres(side);
  ASSERT_EQ(centres.points.size(), 64u);
  for (size_t a = 0; a < side.elements.size(); a += 7)
    for (size_t b = a + 1; b < side.elements.size(); b += 5)
      EXPECT_NEAR((centres.points[a] - centres.points[b]).norm(), (side.elements[a].center - side.elements[b].center).norm(), 1e-12);
  // Piecewise constant: each element's value at its centroid and near its corners, inside.
  const InterpolantResult constant = reconstruct_side(side, Method::constant, {}, SideSampling{});
  ASSERT_TRUE(constant);
  for (const SolutionElement& e : side.elements) {
    const auto uv = e.vertices();
    for (int k = 0; k < 3; ++k) {
      const Vec2 near_corner = side.frame().st(0.9 * uv[static_cast<size_t>(k)] + 0.1 * e.centroid());
      EXPECT_EQ(at(*constant.value(), near_corner), e.radiosity_w_m2[0]);
    }
  }
  // Linear interpolation reproduces the centroids' values there (exact at the samples).
  const InterpolantResult linear = reconstruct_side(side, Method::linear, {}, SideSampling{});
  ASSERT_TRUE(linear);
  for (size_t k = 0; k < side.elements.size(); ++k)
    EXPECT_NEAR(at(*linear.value(), centres.points[k]), side.elements[k].radiosity_w_m2[0], 1e-12);
}

TEST(SideReconstruction, ThePointsBesideABlocksFootOnATwistedFloorHaveValues) {
  // The box standing on a floor that is no parallelogram (a corner drawn in by 0.4 m): the
  // floor's (s, t) follow its bilinear parameters, so the box's feet, straight in space, bend in
  // (s, t) between their corners, while the excluded square is straight there. Points of the
  // floor beside a foot, outside the box in space, fell inside it and had no value (black rays
  // along the Cornell box's blocks in every picture of `radrecon cornell`). Each method now gives
  // them one, and the middle of the box's footprint has none.
  Scene scene = box_on_floor();
  scene.surfaces[0] = quad("floor", {0, 0, 0}, {4, 0, 0}, {3.6, 4, 0}, {0, 4, 0}, 0.5);
  scene.surfaces[0].max_divisions = 16;
  const Solution solution = solve_scene(scene, "grid:16", SolveSettings{}, "test");
  const Surface& floor = scene.surfaces[0];
  ASSERT_GT(floor.frame_bend_m(), 0.1);
  // 0.1 mm outside each foot, at 41 points along it, in space; then to (s, t). The feet along
  // v bend by up to 0.33 mm.
  std::vector<Vec2> beside;
  const Vec3 corners[4] = {{1, 1, 0}, {2, 1, 0}, {2, 2, 0}, {1, 2, 0}};
  double bent_in = 0;  // how far inside the straight square the farthest of them falls, metres
  for (int e = 0; e < 4; ++e) {
    const Vec3 a = corners[e], b = corners[(e + 1) % 4], out = Vec3(0, 0, 1).cross(b - a).normalized() * -1e-4;
    for (int k = 0; k <= 40; ++k) {
      const Vec3 p = a + (k / 40.0) * (b - a) + out;
      const Vec2 st = floor.frame().st(floor.parameters(p).value());
      beside.push_back(st);
    }
  }
  const SurfaceSolution& side = require_surface(solution, "floor", "test");
  ASSERT_EQ(side.excluded.size(), 1u);
  for (const Vec2& q : beside)
    if (in_excluded_region(side.excluded, q)) bent_in += 1;
  EXPECT_GT(bent_in, 0) << "no point beside a foot falls inside the square: the test tests nothing";
  const Vec2 middle = floor.frame().st(floor.parameters(Vec3(1.5, 1.5, 0)).value());
  for (Method m : {Method::constant, Method::natural_neighbour, Method::shepard, Method::bilinear, Method::gouraud}) {
    SCOPED_TRACE(method_name(m));
    const SolutionReconstruction recon(scene, solution, m, {}, "test", SideSampling{});
    const Interpolant* f = recon.side(SideRef{0, false});
    ASSERT_NE(f, nullptr);
    for (const Vec2& q : beside) EXPECT_TRUE(std::isfinite(at(*f, q))) << q.transpose();
    EXPECT_TRUE(std::isnan(at(*f, middle)));
  }
}

}  // namespace solution_reconstruction_test
}  // namespace radrecon
