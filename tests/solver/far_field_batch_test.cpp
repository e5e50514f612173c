// far_field_radiosities() (an element's Gauss points in SIMD packets) is documented to give
// far_field_radiosity()'s values bit for bit, point by point: checked on every block of a
// shooter tree over a plate of random radiosity, from receivers near and far, at grazing angles
// (the kernel's expansion dropped: the block's mean), and behind the plate (the kernel negative).
// far_field_radiosity() itself is checked against sums over elements in shooter_tree_test.cpp.

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <random>
#include <vector>

#include "mesh/grid_mesh.h"
#include "solver/far_field.h"
#include "solver/shooter_tree.h"
#include "support/scenes.h"

namespace radrecon {
namespace far_field_batch_test {

bool same_bits(const Rgb& a, const Rgb& b) {
  for (int c = 0; c < 3; ++c)
    if (std::bit_cast<std::uint64_t>(a[c]) != std::bit_cast<std::uint64_t>(b[c])) return false;
  return true;
}

TEST(FarField, GaussPointsTogetherGiveEachPointsValueBitForBit) {
  Scene scene;
  scene.name = "plate";
  scene.surfaces.push_back(testing_support::quad("plate", {0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}, 0.5));
  const Mesh mesh = make_grid_mesh(scene, {16, 8});
  const MeshSurface& side = mesh.surfaces[0];
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> value(0, 4), coordinate(-3, 5), height(-0.5, 3), tilt(-1, 1);
  std::vector<Rgb> unshot;
  for (size_t k = 0; k < side.elements.size(); ++k) unshot.emplace_back(value(rng), value(rng), value(rng));
  const ShooterTree tree(scene.surfaces[0], side, unshot, 0, 0, side.nu, side.nv);
  const size_t blocks = ShooterTree::block_count(side, nullptr, 0, 0, side.nu, side.nv);
  size_t checked = 0, grazing = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 centre(coordinate(rng), coordinate(rng), height(rng));
    const Vec3 n = Vec3(tilt(rng), tilt(rng), -1).normalized();  // facing the plate, mostly
    for (int count = 1; count <= 4; ++count) {
      std::vector<Vec3> points;
      for (int k = 0; k < count; ++k) points.push_back(centre + 0.05 * Vec3(tilt(rng), tilt(rng), 0));
      for (int b = 0; b < static_cast<int>(blocks); ++b) {
        const Block& block = tree.block(b);
        std::vector<Rgb> together(points.size());
        far_field_radiosities(block, points, n, side.normal, together);
        for (size_t k = 0; k < points.size(); ++k) {
          const Rgb alone = far_field_radiosity(block, points[k], n, side.normal);
          ASSERT_TRUE(same_bits(together[k], alone)) << "block " << b << ", point " << k << " of " << count << ": "
                                                     << together[k].transpose() << " against " << alone.transpose();
          Vec3 g;
          grazing += !kernel_log_gradient(block, points[k], n, side.normal, g);
          ++checked;
        }
      }
    }
  }
  EXPECT_GT(grazing, checked / 20) << "some points must see blocks at grazing angles or from behind";
  EXPECT_LT(grazing, checked / 2);
}

}  // namespace far_field_batch_test
}  // namespace radrecon
