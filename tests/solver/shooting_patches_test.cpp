// The shooting patches of progressive refinement (solver/shooting_patches.h) against brute force:
// every element belongs to the one patch whose box of cells holds its centre, and a patch's
// power is the sum of its elements' area times unshot radiosity.

#include <gtest/gtest.h>

#include <random>

#include "mesh/grid_mesh.h"
#include "solver/shooting_patches.h"
#include "support/scenes.h"

namespace radrecon {
namespace shooting_patches_test {

using testing_support::as_triangles;
using testing_support::closed_box;

/// Sums of ~10^3 terms in another order.
constexpr double kSumRelative = 1e-12;

TEST(ShootingPatches, PowerIsTheSumOverTheElementsWhoseCentresLieInThePatch) {
  // Quads and triangles, with patches that do not divide the sides' cells evenly.
  Scene scene = closed_box(0.5, 1.0);
  const Scene triangles = as_triangles(closed_box(0.5, 1.0));
  scene.surfaces.push_back(triangles.surfaces[0]);
  scene.surfaces.back().name = "lying_triangle";
  const Mesh mesh = make_grid_mesh(scene, GridMeshOptions{11, 3});
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<std::vector<Rgb>> unshot(mesh.surfaces.size());
  std::vector<const std::vector<Rgb>*> by_side;
  for (size_t s = 0; s < mesh.surfaces.size(); ++s) {
    for (size_t e = 0; e < mesh.surfaces[s].elements.size(); ++e) unshot[s].push_back(Rgb(unit(random), unit(random), unit(random)));
    by_side.push_back(&unshot[s]);
  }
  ShootingPatches shooting(mesh);
  std::vector<size_t> sides(mesh.surfaces.size());
  for (size_t s = 0; s < sides.size(); ++s) sides[s] = s;
  shooting.sum_power(mesh, by_side, sides);

  // Brute force: each element to the patch whose (u, v) box holds its centre.
  std::vector<Rgb> expected(shooting.patches.size(), Rgb::Zero());
  std::vector<int> members(shooting.patches.size(), 0);
  for (size_t s = 0; s < mesh.surfaces.size(); ++s) {
    const MeshSurface& side = mesh.surfaces[s];
    for (size_t e = 0; e < side.elements.size(); ++e) {
      const Vec2 c = side.elements[e].centroid();
      int found = 0;
      for (size_t k = 0; k < shooting.patches.size(); ++k) {
        const Patch& p = shooting.patches[k];
        if (p.surface != s || c.x() < double(p.i0) / side.nu || c.x() > double(p.i1) / side.nu ||
            c.y() < double(p.j0) / side.nv || c.y() > double(p.j1) / side.nv)
          continue;
        expected[k] += side.elements[e].area_m2 * unshot[s][e];
        ++members[k];
        ++found;
      }
      ASSERT_EQ(found, 1) << side.name << " element " << e;
    }
  }
  int empty = 0;
  for (size_t k = 0; k < shooting.patches.size(); ++k) {
    empty += members[k] == 0;
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(shooting.patches[k].unshot_w[c], expected[k][c], kSumRelative * (1 + expected[k][c])) << "patch " << k;
  }
  EXPECT_GT(empty, 0);  // the triangle's patches beyond its hypotenuse hold nothing, and are kept

  // Only the sides asked for are summed again.
  const Rgb before = shooting.patches[shooting.first[1]].unshot_w;
  for (Rgb& b : unshot[0]) b *= 2;
  for (Rgb& b : unshot[1]) b *= 2;
  shooting.sum_power(mesh, by_side, {0});
  EXPECT_NEAR(shooting.patches[shooting.first[0]].unshot_w.sum(), 2 * expected[shooting.first[0]].sum(),
              kSumRelative * (1 + expected[shooting.first[0]].sum()));
  EXPECT_EQ(shooting.patches[shooting.first[1]].unshot_w.sum(), before.sum());
}

}  // namespace shooting_patches_test
}  // namespace radrecon
