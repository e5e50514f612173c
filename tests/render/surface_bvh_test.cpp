// The renderer's surface hierarchy against the brute-force search over every surface: the same
// hit, bit for bit, for rays through a scene of many small triangles and quads, edges and
// corners aimed at, and lights lying in the planes of larger surfaces (the emitter-wins tie).

#include <gtest/gtest.h>

#include <random>

#include "render/renderer.h"
#include "render/surface_bvh.h"
#include "support/scenes.h"

namespace radrecon {
namespace surface_bvh_test {

using testing_support::quad;

/// 600 small random triangles and quads in a 4 m box, a floor and a ceiling with two lights
/// set into its plane (tied with it) and one 1e-3 m below it.
Scene cluttered_room(std::mt19937& rng) {
  std::uniform_real_distribution<double> at(0.0, 4.0), size(0.02, 0.4), unit(-1.0, 1.0);
  Scene scene;
  scene.surfaces.push_back(quad("floor", {0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, 0.5));
  scene.surfaces.push_back(quad("ceiling", {0, 0, 4}, {0, 4, 4}, {4, 4, 4}, {4, 0, 4}, 0.5));
  scene.surfaces.push_back(quad("light_in_plane", {1, 1, 4}, {1, 2, 4}, {2, 2, 4}, {2, 1, 4}, 0.0, 10));
  scene.surfaces.push_back(quad("light_below", {2.5, 2.5, 3.999}, {2.5, 3, 3.999}, {3, 3, 3.999}, {3, 2.5, 3.999}, 0.0, 10));
  for (int k = 0; k < 600; ++k) {
    const Vec3 c(at(rng), at(rng), 0.2 + 0.9 * at(rng));
    Vec3 e1(unit(rng), unit(rng), unit(rng)), e2(unit(rng), unit(rng), unit(rng));
    e1 = size(rng) * e1.normalized();
    e2 = size(rng) * (e2 - e2.dot(e1) / e1.squaredNorm() * e1).normalized();
    Surface s = quad("s" + std::to_string(k), c, c + e1, c + e1 + e2, c + e2, 0.5);
    if (k % 2 == 1) s.set_triangle(c, c + e1, c + e2);
    scene.surfaces.push_back(s);
  }
  return scene;
}

bool same_hit(const std::optional<SurfaceHit>& a, const std::optional<SurfaceHit>& b) {
  if (a.has_value() != b.has_value()) return false;
  return !a || (a->surface == b->surface && a->back_side == b->back_side && a->u == b->u && a->v == b->v && a->t == b->t);
}

TEST(SurfaceBvh, FindsTheBruteForceHitForRandomRaysAndRaysAtCornersAndTiedLights) {
  std::mt19937 rng(20261203);
  const Scene scene = cluttered_room(rng);
  const SurfaceBvh bvh(scene);
  std::uniform_real_distribution<double> at(-0.5, 4.5), unit(-1.0, 1.0), blend(0.0, 1.0);
  size_t hits = 0, lights = 0;
  const auto check = [&](const Vec3& o, const Vec3& d) {
    const auto brute = intersect_scene(scene, o, d);
    const auto fast = intersect_scene(scene, bvh, o, d);
    ASSERT_TRUE(same_hit(brute, fast)) << "ray from " << o.transpose() << " along " << d.transpose();
    hits += brute.has_value();
    lights += brute && brute->surface <= 3 && brute->surface >= 2;
  };
  for (int k = 0; k < 8000; ++k) {
    const Vec3 o(at(rng), at(rng), at(rng));
    check(o, Vec3(unit(rng), unit(rng), unit(rng)).normalized());
    // At a surface's corner or along its edge: the hits that round-off decides.
    const Surface& s = scene.surfaces[static_cast<size_t>(k) % scene.surfaces.size()];
    const Vec3 target = k % 3 == 0 ? s.corners[0] : s.corners[0] + blend(rng) * (s.corners[1] - s.corners[0]);
    if ((target - o).norm() > 1e-9) check(o, (target - o).normalized());
    // Straight up at the lights and the ceiling around them, and along the axes.
    check(Vec3(at(rng), at(rng), 0.1), Vec3(0, 0, 1));
    check(o, Vec3(1, 0, 0));
  }
  EXPECT_GT(hits, 12000u);  // most rays meet something: the comparison is not of two misses
  EXPECT_GT(lights, 40u);  // and many end on a light tied with the ceiling or just below it
}

TEST(SurfaceBvh, FindsTheHitsOfAQuadOffItsPlaneWithinThePlanarityTolerance) {
  // A 5 m floor quad whose corner 1 is lifted 2e-5 m (corners 5e-6 m off their mean plane, within
  // tol::kPlanarityRelative of 5 m): the plane a ray hits, through corner 0, passes 1e-5 m below
  // corner 3, outside the corners' own box. Rays graze in over the edge there.
  constexpr double kL = 5, kWarp = 2e-5;
  Scene scene;
  scene.surfaces.push_back(quad("floor", {0, 0, 0}, {kL, 0, kWarp}, {kL, kL, 0}, {0, kL, 0}, 0.5));
  for (int k = 0; k < 20; ++k)  // enough surfaces for a hierarchy of several levels
    scene.surfaces.push_back(quad("post" + std::to_string(k), {0.2 * k, 6, 0}, {0.2 * k + 0.1, 6, 0},
                                  {0.2 * k + 0.1, 6, 1}, {0.2 * k, 6, 1}, 0.5));
  const SurfaceBvh bvh(scene);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> along(0.0, 0.5), lift(1e-4, 0.05);
  size_t on_floor = 0;
  for (int k = 0; k < 4000; ++k) {
    // From outside the floor's corner 3 (x < 0, y > L), nearly level, at a point near that corner.
    const Vec3 target(along(rng), kL - along(rng), -5e-6);
    const Vec3 o(-1.0, kL + 1.0, lift(rng));
    const Vec3 d = (target - o).normalized();
    const auto brute = intersect_scene(scene, o, d);
    ASSERT_TRUE(same_hit(brute, intersect_scene(scene, bvh, o, d))) << "ray from " << o.transpose();
    on_floor += brute && brute->surface == 0;
  }
  EXPECT_GT(on_floor, 1000u);
}

}  // namespace surface_bvh_test
}  // namespace radrecon
