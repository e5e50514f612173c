// Convex solids among a scene's surfaces, and the faces of one left out of a point's shadows:
// found where they are and nowhere else, and the visible form factor unchanged by leaving them
// out (against every face kept, and against an independent ray caster).

#include <gtest/gtest.h>

#include <random>

#include "solver/convex_solids.h"
#include "solver/visibility.h"
#include "support/occluder_lists.h"
#include "support/ray_scene.h"
#include "support/scenes.h"

namespace radrecon {
namespace convex_solids_test {

Surface quad(const std::string& name, std::array<Vec3, 4> c) {
  Surface s;
  s.name = name;
  s.corners = c;
  return s;
}

using testing_support::box_faces;

Scene scene_of(std::vector<Surface> surfaces) {
  Scene s;
  s.surfaces = std::move(surfaces);
  return s;
}

TEST(ConvexSolids, AClosedBoxIsOneSolidWithOutwardFaces) {
  const Scene scene = scene_of(box_faces(Vec3(0, 0, 0), Vec3(1, 2, 3)));
  for (const Surface& f : scene.surfaces)  // the test's own box: outward as claimed
    EXPECT_GT(f.normal().dot(f.corners[0] - Vec3(0.5, 1, 1.5)), 0) << f.name;
  const auto solids = find_convex_solids(scene);
  ASSERT_EQ(solids.size(), 6u);
  ASSERT_TRUE(solids[0]);
  for (const auto& s : solids) EXPECT_EQ(s, solids[0]);
  EXPECT_FALSE(solids[0]->opening.has_value());
  EXPECT_EQ(solids[0]->faces.size(), 6u);
  EXPECT_TRUE(solids[0]->sees_from_outside(Vec3(2, 1, 1)));
  EXPECT_FALSE(solids[0]->sees_from_outside(Vec3(0.5, 1, 1)));  // inside
  EXPECT_FALSE(solids[0]->sees_from_outside(Vec3(1, 1, 1)));    // on a face
}

TEST(ConvexSolids, WhatBoundsNoConvexSolidIsNone) {
  // A room: its walls face in.
  EXPECT_FALSE(find_convex_solids(scene_of(box_faces(Vec3(0, 0, 0), Vec3(1, 1, 1), true)))[0]);
  // Open on three sides (+x, -z, +z), whose edges lie in no one plane.
  std::vector<Surface> open3 = box_faces(Vec3(0, 0, 0), Vec3(1, 1, 1));
  open3.erase(open3.begin() + 4, open3.end());
  open3.erase(open3.begin() + 1);
  for (const auto& s : find_convex_solids(scene_of(open3))) EXPECT_FALSE(s);
  // One face flipped: two edges run the same way.
  std::vector<Surface> flipped = box_faces(Vec3(0, 0, 0), Vec3(1, 1, 1));
  std::swap(flipped[2].corners[1], flipped[2].corners[3]);
  for (const auto& s : find_convex_solids(scene_of(flipped))) EXPECT_FALSE(s);
  // Two boxes sharing a face (its edges run by four faces) are no solid, nor is a flat pair of
  // triangles (no corner behind either's plane).
  std::vector<Surface> two = box_faces(Vec3(0, 0, 0), Vec3(1, 1, 1));
  for (Surface& f : box_faces(Vec3(1, 0, 0), Vec3(2, 1, 1))) two.push_back(f);
  for (const auto& s : find_convex_solids(scene_of(two))) EXPECT_FALSE(s);
  Surface a, b;
  a.set_triangle(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0));
  b.set_triangle(Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0));
  for (const auto& s : find_convex_solids(scene_of({a, b}))) EXPECT_FALSE(s);
}

/// A closed prism over a regular n-gon (radius 1, z in [0, 1]): n quads around, a fan of n
/// triangles on each end; 3n faces, outward.
std::vector<Surface> prism(int n) {
  std::vector<Vec3> bottom, top;
  for (int k = 0; k < n; ++k) {
    const double a = 2 * std::numbers::pi * k / n;
    bottom.emplace_back(std::cos(a), std::sin(a), 0.0);
    top.emplace_back(std::cos(a), std::sin(a), 1.0);
  }
  std::vector<Surface> faces;
  for (int k = 0; k < n; ++k) {
    const int j = (k + 1) % n;
    faces.push_back(quad("side", {bottom[k], bottom[j], top[j], top[k]}));
    Surface t, b;
    t.set_triangle(Vec3(0, 0, 1), top[k], top[j]);
    b.set_triangle(Vec3(0, 0, 0), bottom[j], bottom[k]);
    faces.push_back(t);
    faces.push_back(b);
  }
  return faces;
}

TEST(ConvexSolids, PrismsOfTrianglesAndQuadsUpToTheFaceLimit) {
  const auto small = find_convex_solids(scene_of(prism(8)));  // 24 faces
  ASSERT_TRUE(small[0]);
  for (const auto& s : small) EXPECT_EQ(s, small[0]);
  EXPECT_FALSE(small[0]->opening.has_value());
  EXPECT_TRUE(small[0]->sees_from_outside(Vec3(2, 0, 0.5)));
  EXPECT_FALSE(small[0]->sees_from_outside(Vec3(0, 0, 0.5)));
  static_assert(3 * 30 > kMaxSolidFaces);
  for (const auto& s : find_convex_solids(scene_of(prism(30)))) EXPECT_FALSE(s);
}

TEST(ConvexSolids, TheCornellBlocksStandOnTheirOpening) {
  const Scene scene = cornell_scene();
  const auto solids = find_convex_solids(scene);
  int in_blocks = 0;
  for (size_t k = 0; k < scene.surfaces.size(); ++k) {
    const std::string& name = scene.surfaces[k].name;
    const bool block = name.rfind("short_", 0) == 0 || name.rfind("tall_", 0) == 0;
    EXPECT_EQ(bool(solids[k]), block) << name;
    if (!block) continue;
    ++in_blocks;
    ASSERT_TRUE(solids[k]->opening.has_value());
    // The floor's plane (y = 0), facing down: out of the block.
    EXPECT_NEAR(solids[k]->opening->normal.y(), -1, 1e-12) << name;
    EXPECT_NEAR(solids[k]->opening->offset, 0, 1e-12) << name;
  }
  EXPECT_EQ(in_blocks, 10);
}

/// The scene's occluders, with the solids found (`with_solids`) or without (every face kept).
std::vector<Occluder> occluders_of(const Scene& scene, bool with_solids) {
  std::vector<Occluder> occ = make_occluders(scene);
  if (!with_solids)
    for (Occluder& o : occ) o.solid = nullptr;
  return occ;
}

/// The visible form factor from (p, n) on `receiver` to `shooter` past the occluders.
double form_factor(const Scene& scene, const std::vector<Occluder>& occ, size_t shooter, size_t receiver, const Vec3& p,
                   const Vec3& n) {
  const Surface& s = scene.surfaces[shooter];
  return visible_form_factor(p, n, testing_support::polygon_of(s), s.normal(),
                             testing_support::all_but(occ, shooter, receiver));
}

TEST(ConvexSolids, LeavingBackFacesOutChangesNoShadow) {
  // The Cornell box: points on the floor, on the walls and on the blocks' own faces (both
  // sides), shot at by the light, the ceiling and the walls. Every face kept is the reference.
  const Scene scene = cornell_scene();
  const std::vector<Occluder> solid = occluders_of(scene, true), bare = occluders_of(scene, false);
  constexpr size_t kNone = ~size_t{0};
  const std::vector<const Occluder*> all_solid = testing_support::all_but(solid, kNone, kNone),
                                    all_bare = testing_support::all_but(bare, kNone, kNone);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(0.01, 0.99);
  int compared = 0, nonzero = 0, culled_somewhere = 0;
  for (size_t receiver = 0; receiver < scene.surfaces.size(); ++receiver) {
    const Surface& r = scene.surfaces[receiver];
    for (const bool back : {false, true}) {
      const Vec3 n = back ? Vec3(-r.normal()) : r.normal();
      for (int k = 0; k < 20; ++k) {
        double u = U(rng), v = U(rng);
        if (r.is_triangle() && u + v > 1) u = 1 - u, v = 1 - v;
        const Vec3 p = r.point(u, v);
        for (size_t shooter = 0; shooter < scene.surfaces.size(); ++shooter) {
          if (shooter == receiver) continue;
          const double with = form_factor(scene, solid, shooter, receiver, p, n);
          const double without = form_factor(scene, bare, shooter, receiver, p, n);
          ASSERT_NEAR(with, without, 1e-12 * std::max(1.0, without)) << r.name << " from " << scene.surfaces[shooter].name;
          ++compared;
          nonzero += without > 1e-6 ? 1 : 0;
        }
        // How many faces the solids leave out for this point: the test must exercise it.
        std::vector<ShadowVolume> kept, plain;
        shadow_volumes(p, n, all_solid, kept);
        shadow_volumes(p, n, all_bare, plain);
        culled_somewhere += kept.size() < plain.size() ? 1 : 0;
      }
    }
  }
  EXPECT_GT(nonzero, compared / 4);
  EXPECT_GT(culled_somewhere, 100);
}

TEST(ConvexSolids, AClosedBoxSeenPastItsFrontFacesAgainstRays) {
  // A box on a floor under a light panel: points on the floor around it, inside its footprint,
  // and on its faces. The form factor to the light against the midpoint rule with an
  // independent ray caster.
  std::vector<Surface> s = box_faces(Vec3(0.3, 0, 0.3), Vec3(0.6, 0.4, 0.7));
  s.push_back(quad("floor", {Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 0, 0)}));  // faces +y
  s.push_back(quad("light", {Vec3(0.2, 1, 0.2), Vec3(0.8, 1, 0.2), Vec3(0.8, 1, 0.8), Vec3(0.2, 1, 0.8)}));  // faces -y
  const Scene scene = scene_of(s);
  const size_t floor = 6, light = 7;
  ASSERT_TRUE(find_convex_solids(scene)[0]);
  const std::vector<Occluder> occ = make_occluders(scene);
  ASSERT_LT(scene.surfaces[light].normal().y(), -0.99);  // the light faces down, the floor up
  ASSERT_GT(scene.surfaces[floor].normal().y(), 0.99);
  const auto brute = [&](const Vec3& p, const Vec3& n, size_t receiver) {
    return testing_support::brute_force_form_factor(scene, light, p, n, receiver, 300);
  };
  const std::vector<std::pair<Vec3, size_t>> points = {
      {Vec3(0.15, 0, 0.5), floor}, {Vec3(0.7, 0, 0.45), floor}, {Vec3(0.45, 0, 0.85), floor},
      {Vec3(0.45, 0, 0.5), floor},  // under the box: dark
      {Vec3(0.6, 0.2, 0.5), 1},      // on its +x face
      {Vec3(0.45, 0.4, 0.5), 3},     // on its top
  };
  for (const auto& [p, receiver] : points) {
    const Vec3 n = scene.surfaces[receiver].normal();
    const double exact = form_factor(scene, occ, light, receiver, p, n);
    EXPECT_NEAR(exact, brute(p, n, receiver), 3e-3 * std::max(exact, 0.05)) << p.transpose();
  }
  EXPECT_EQ(form_factor(scene, occ, light, floor, Vec3(0.45, 0, 0.5), Vec3::UnitY()), 0.0);
}

}  // namespace convex_solids_test
}  // namespace radrecon
