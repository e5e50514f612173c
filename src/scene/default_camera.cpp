#include "scene/default_camera.h"

#include <cmath>
#include <limits>
#include <numbers>

namespace radrecon {

Camera default_camera(const Scene& scene) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Surface& s : scene.surfaces)
    for (const Vec3& c : s.polygon()) {
      lo = lo.cwiseMin(c);
      hi = hi.cwiseMax(c);
    }
  Camera camera;
  camera.name = "default";
  camera.fov_deg = 45.0;
  camera.up = Vec3(0, 0, 1);
  camera.target = 0.5 * (lo + hi);
  const double radius = 0.5 * (hi - lo).norm();
  const double distance = radius / std::sin(0.5 * camera.fov_deg * std::numbers::pi / 180.0);
  camera.eye = camera.target + distance * Vec3(1, -2, 1).normalized();
  return camera;
}

}  // namespace radrecon
