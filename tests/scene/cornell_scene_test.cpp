// The built-in Cornell box against the published data's own properties: valid, the red wall split
// as documented, every surface facing into the room or out of its block, the blocks closed but
// for their bottoms, the light inside the ceiling, the published camera's field of view.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "io/scene_json.h"
#include "scene/scene.h"

namespace radrecon {
namespace cornell_scene_test {

/// Vector area (m^2) of a planar polygon: half the sum of c_i x c_{i+1}; along the front normal.
Vec3 vector_area(const Surface& s) {
  const auto p = s.polygon();
  Vec3 a = Vec3::Zero();
  for (size_t i = 0; i < p.size(); ++i) a += p[i].cross(p[(i + 1) % p.size()]);
  return 0.5 * a;
}

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

TEST(CornellScene, IsValidAndSplitsOnlyTheWarpedRedWall) {
  const Scene scene = cornell_scene();
  EXPECT_NO_THROW(validate_scene(scene, "cornell"));
  // 6 room surfaces (the red wall as 2 triangles) + 2 blocks x 5 faces.
  ASSERT_EQ(scene.surfaces.size(), 17u);
  for (const Surface& s : scene.surfaces)
    EXPECT_EQ(s.is_triangle(), starts_with(s.name, "red_wall.")) << s.name;
  const Surface& a = scene.surfaces[*scene.find_surface("red_wall.a")];
  const Surface& b = scene.surfaces[*scene.find_surface("red_wall.b")];
  // Together they cover the published quad: its area from the diagonals' cross product, which is
  // exact for a planar quad and within (0.8 mm)^2-order terms for this one.
  const Vec3 c0(0.5528, 0, 0), c1(0.5496, 0, 0.5592), c2(0.556, 0.5488, 0.5592), c3(0.556, 0.5488, 0);
  const double quad_area = 0.5 * (c2 - c0).cross(c3 - c1).norm();
  EXPECT_NEAR(a.area_m2() + b.area_m2(), quad_area, 1e-5 * quad_area);
  EXPECT_EQ(load_scene("cornell").surfaces.size(), scene.surfaces.size());
}

TEST(CornellScene, RoomSurfacesFaceInwardsAndBlocksFaceOutwards) {
  const Scene scene = cornell_scene();
  const Vec3 room_centre(0.278, 0.2744, 0.2796);
  for (const std::string block : {"short", "tall"}) {
    Vec3 centroid = Vec3::Zero();
    int n = 0;
    for (const Surface& s : scene.surfaces)
      if (starts_with(s.name, block + "_"))
        for (const Vec3& c : s.polygon()) centroid += c, ++n;
    ASSERT_EQ(n, 20);
    centroid /= n;
    Vec3 total = Vec3::Zero();
    double top_area = 0;
    for (const Surface& s : scene.surfaces) {
      if (!starts_with(s.name, block + "_")) continue;
      const Vec3 face_centre = 0.25 * (s.corners[0] + s.corners[1] + s.corners[2] + s.corners[3]);
      EXPECT_GT(s.normal().dot(face_centre - centroid), 0) << s.name << " faces into its block";
      total += vector_area(s);
      if (s.name == block + "_top") top_area = s.area_m2();
    }
    // Closed but for the bottom: the five faces' vector areas sum to minus the bottom's, i.e. to
    // +y times the footprint (the top's area, the sides being vertical). Published to 1 mm.
    EXPECT_NEAR(total.x(), 0, 1e-9) << block;
    EXPECT_NEAR(total.y(), top_area, 1e-9) << block;
    EXPECT_NEAR(total.z(), 0, 1e-9) << block;
  }
  for (const Surface& s : scene.surfaces) {
    if (starts_with(s.name, "short_") || starts_with(s.name, "tall_")) continue;
    const Vec3 c = s.point(0.25, 0.25);
    EXPECT_GT(s.normal().dot(room_centre - c), 0.1) << s.name << " faces out of the room";
    EXPECT_FALSE(s.two_sided) << s.name;
  }
}

TEST(CornellScene, LightIsInsideTheCeilingAndEmitsTheCitedExitance) {
  const Scene scene = cornell_scene();
  const Surface& light = scene.surfaces[*scene.find_surface("light")];
  const Surface& ceiling = scene.surfaces[*scene.find_surface("ceiling")];
  EXPECT_NEAR(light.area_m2(), 0.130 * 0.105, 1e-12);
  for (const Vec3& c : light.polygon()) {
    EXPECT_NEAR(ceiling.normal().dot(c - ceiling.corners[0]), 0, 1e-15);
    EXPECT_TRUE(ceiling.parameters(c).has_value());
  }
  EXPECT_NEAR((light.normal() - Vec3(0, -1, 0)).norm(), 0, 1e-15);
  // pi x Bitterli's radiance (17, 12, 4) W/(m^2 sr).
  EXPECT_NEAR(light.emission_w_m2[0], 53.407, 1e-3);
  EXPECT_NEAR(light.emission_w_m2[1], 37.699, 1e-3);
  EXPECT_NEAR(light.emission_w_m2[2], 12.566, 1e-3);
}

TEST(CornellScene, PublishedCameraSeesTheWholeFrontOpening) {
  const Scene scene = cornell_scene();
  ASSERT_FALSE(scene.cameras.empty());
  const Camera& c = scene.cameras.front();
  EXPECT_EQ(c.name, "published");
  EXPECT_NEAR(c.fov_deg, 39.3077, 1e-4);
  // 35 mm lens, 25 mm film: the half-height at the front (z = 0, 0.8 m away) is 0.8 x 12.5 / 35
  // = 0.2857 m, just covering the opening's 0.2744 m half-height about y = 0.273 m.
  const double half = 0.8 * std::tan(c.fov_deg / 2 * std::numbers::pi / 180);
  EXPECT_NEAR(half, 0.8 * 12.5 / 35, 1e-12);
  EXPECT_GT(c.eye.y() + half, 0.5488);
  EXPECT_LT(c.eye.y() - half, 0.0);
}

}  // namespace cornell_scene_test
}  // namespace radrecon
