// The shooting patches of progressive refinement (solver/shooting_patches.h) against brute force:
// every element belongs to the patch whose box of patch_size x patch_size cells holds its
// centre, found from the centre's (u, v) alone, and a patch's power is the sum of its elements'
// area times unshot radiosity.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mesh/grid_mesh.h"
#include "solver/shooting_patches.h"
#include "support/scenes.h"

namespace radrecon {
namespace shooting_patches_test {

using testing_support::as_triangles;
using testing_support::closed_box;

/// The same terms summed, perhaps in another order: a few dozen of them, each positive.
constexpr double kSumRelative = 1e-13;

struct Fixture {
  Mesh mesh;
  std::vector<std::vector<Rgb>> unshot;  // W/m^2, by side and element
  std::vector<const std::vector<Rgb>*> by_side;
  std::vector<size_t> all_sides;
};

/// Quads and a triangle, with patches that do not divide the sides' cells evenly, random
/// unshot radiosity in (0, 1).
Fixture make_fixture() {
  Fixture f;
  Scene scene = closed_box(0.5, 1.0);
  scene.surfaces.push_back(as_triangles(closed_box(0.5, 1.0)).surfaces[0]);
  scene.surfaces.back().name = "lying_triangle";
  f.mesh = make_grid_mesh(scene, GridMeshOptions{11, 3});
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  f.unshot.resize(f.mesh.surfaces.size());
  for (size_t s = 0; s < f.mesh.surfaces.size(); ++s) {
    for (size_t e = 0; e < f.mesh.surfaces[s].elements.size(); ++e)
      f.unshot[s].push_back(Rgb(unit(random), unit(random), unit(random)));
    f.by_side.push_back(&f.unshot[s]);
    f.all_sides.push_back(s);
  }
  return f;
}

/// Each patch's power by brute force: each element to the patch whose cells hold its centre.
std::vector<Rgb> expected_power(const Fixture& f, const ShootingPatches& shooting) {
  std::vector<Rgb> out(shooting.patches().size(), Rgb::Zero());
  for (size_t s = 0; s < f.mesh.surfaces.size(); ++s) {
    const MeshSurface& side = f.mesh.surfaces[s];
    for (size_t e = 0; e < side.elements.size(); ++e) {
      const Vec2 c = side.elements[e].centroid();
      const int pi = static_cast<int>(std::floor(c.x() * side.nu / side.patch_size));
      const int pj = static_cast<int>(std::floor(c.y() * side.nv / side.patch_size));
      out[shooting.first_of_side(s) + static_cast<size_t>(pj * side.patches_u() + pi)] +=
          side.elements[e].area_m2 * f.unshot[s][e];
    }
  }
  return out;
}

void expect_power(const ShootingPatches& shooting, const std::vector<Rgb>& expected, size_t first, size_t last) {
  for (size_t k = first; k < last; ++k)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(shooting.patches()[k].unshot_w[c], expected[k][c], kSumRelative * expected[k][c]) << "patch " << k;
}

TEST(ShootingPatches, EverySidesPatchGridInOrderWithItsCellBoxes) {
  const Fixture f = make_fixture();
  const ShootingPatches shooting(f.mesh);
  size_t next = 0;
  for (size_t s = 0; s < f.mesh.surfaces.size(); ++s) {
    const MeshSurface& side = f.mesh.surfaces[s];
    ASSERT_EQ(shooting.first_of_side(s), next);
    for (int pj = 0; pj < side.patches_v(); ++pj)
      for (int pi = 0; pi < side.patches_u(); ++pi) {
        const ShootingPatch& p = shooting.patches()[next++];
        EXPECT_EQ(p.surface, s);
        EXPECT_EQ(p.i0, pi * side.patch_size);
        EXPECT_EQ(p.j0, pj * side.patch_size);
        EXPECT_EQ(p.i1, std::min(side.nu, (pi + 1) * side.patch_size));
        EXPECT_EQ(p.j1, std::min(side.nv, (pj + 1) * side.patch_size));
      }
  }
  EXPECT_EQ(shooting.patches().size(), next);
}

TEST(ShootingPatches, PowerIsTheSumOverTheElementsWhoseCentresLieInThePatch) {
  Fixture f = make_fixture();
  ShootingPatches shooting(f.mesh);
  shooting.sum_power(f.mesh, f.by_side, f.all_sides);
  std::vector<Rgb> expected = expected_power(f, shooting);
  expect_power(shooting, expected, 0, expected.size());
  int empty = 0;
  for (const Rgb& p : expected) empty += (p == 0).all();
  EXPECT_GT(empty, 0);  // the triangle's patches beyond its hypotenuse hold nothing, and are kept

  // Only the sides asked for are summed again: side 0's patches follow its doubled radiosity,
  // side 1's keep their sums bit for bit.
  const ShootingPatches before = shooting;
  for (Rgb& b : f.unshot[0]) b *= 2;
  for (Rgb& b : f.unshot[1]) b *= 2;
  const std::vector<size_t> side_0{0};
  shooting.sum_power(f.mesh, f.by_side, side_0);
  expected = expected_power(f, shooting);
  expect_power(shooting, expected, shooting.first_of_side(0), shooting.first_of_side(1));
  for (size_t k = shooting.first_of_side(1); k < shooting.patches().size(); ++k)
    EXPECT_TRUE((shooting.patches()[k].unshot_w == before.patches()[k].unshot_w).all()) << "patch " << k;
}

TEST(ShootingPatches, AShotPatchLosesItsElementsRadiosityAndPowerAndNoOther) {
  Fixture f = make_fixture();
  ShootingPatches shooting(f.mesh);
  shooting.sum_power(f.mesh, f.by_side, f.all_sides);
  const size_t side = 2, shot = shooting.first_of_side(side) + 1;
  const std::vector<Rgb> unshot_before = f.unshot[side];
  const ShootingPatches before = shooting;
  shooting.shoot(f.mesh, shot, f.unshot[side]);
  EXPECT_TRUE((shooting.patches()[shot].unshot_w == 0).all());
  // Its elements, by their centres, are zero; every other element is as it was.
  const MeshSurface& s = f.mesh.surfaces[side];
  const ShootingPatch& p = shooting.patches()[shot];
  int zeroed = 0;
  for (size_t e = 0; e < s.elements.size(); ++e) {
    const Vec2 c = s.elements[e].centroid();
    const bool inside = c.x() * s.nu > p.i0 && c.x() * s.nu < p.i1 && c.y() * s.nv > p.j0 && c.y() * s.nv < p.j1;
    zeroed += inside;
    EXPECT_TRUE((f.unshot[side][e] == (inside ? Rgb(Rgb::Zero()) : unshot_before[e])).all()) << "element " << e;
  }
  EXPECT_EQ(zeroed, (p.i1 - p.i0) * (p.j1 - p.j0));
  for (size_t k = 0; k < shooting.patches().size(); ++k)
    if (k != shot) EXPECT_TRUE((shooting.patches()[k].unshot_w == before.patches()[k].unshot_w).all()) << "patch " << k;
  // Summed again, the patch's power is zero and its neighbours' unchanged: the shot agrees.
  shooting.sum_power(f.mesh, f.by_side, std::vector<size_t>{side});
  for (size_t k = shooting.first_of_side(side); k < shooting.first_of_side(side + 1); ++k)
    EXPECT_TRUE((shooting.patches()[k].unshot_w == (k == shot ? Rgb(Rgb::Zero()) : before.patches()[k].unshot_w)).all());
}

}  // namespace shooting_patches_test
}  // namespace radrecon
