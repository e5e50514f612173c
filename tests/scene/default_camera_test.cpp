// default_camera(): every corner of the scene inside its view cone, from outside the bounding
// sphere, and a camera validate_scene() accepts.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "scene/default_camera.h"

namespace radrecon {
namespace default_camera_test {

TEST(DefaultCamera, SeesEveryCornerWithinHalfTheFieldOfView) {
  Scene scene = paper_scene();
  scene.cameras.clear();
  // A far, tall extra surface, so the box is not the paper scene's alone.
  Surface mast;
  mast.name = "mast";
  mast.corners = {Vec3(-3, 7, 0), Vec3(-2, 7, 0), Vec3(-2, 7, 9), Vec3(-3, 7, 9)};
  mast.reflectance = Rgb::Constant(0.5);
  scene.surfaces.push_back(mast);
  const Camera camera = default_camera(scene);
  EXPECT_EQ(camera.name, "default");
  const Vec3 axis = (camera.target - camera.eye).normalized();
  const double half_fov = 0.5 * camera.fov_deg * std::numbers::pi / 180.0;
  double widest = 0;
  for (const Surface& s : scene.surfaces)
    for (const Vec3& c : s.polygon()) {
      const double angle = std::acos(std::clamp(axis.dot((c - camera.eye).normalized()), -1.0, 1.0));
      widest = std::max(widest, angle);
      EXPECT_LT(angle, half_fov) << s.name << " corner " << c.transpose();
    }
  EXPECT_GT(widest, 0.5 * half_fov);  // framed, not lost in the middle of the picture
  scene.cameras.push_back(camera);
  EXPECT_NO_THROW(validate_scene(scene, "default camera"));
}

}  // namespace default_camera_test
}  // namespace radrecon
