#include <cmath>
#include <numbers>

#include "scene/scene.h"

namespace radrecon {

namespace {

/// A published corner, millimetres, as metres.
Vec3 mm(double x, double y, double z) { return Vec3(x, y, z) / 1000.0; }

Surface quad(const std::string& name, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, const Rgb& rho) {
  Surface s;
  s.name = name;
  s.corners = {a, b, c, d};
  s.reflectance = rho;
  return s;
}

}  // namespace

Scene cornell_scene() {
  // "Cornell Box Data", Cornell University Program of Computer Graphics,
  // https://www.graphics.cornell.edu/online/box/data.html: every corner as published there (mm,
  // here metres), in the published order, which is counter-clockwise seen from the inside of the
  // room and from outside the blocks (tests/scene/cornell_scene_test.cpp checks it). x points to
  // the red wall (the camera's left), y up, z from the open front to the back wall.
  // Reflectances and light: B. Bitterli's "Rendering Resources" cornell-box (Tungsten / Mitsuba
  // scene), docs/cornell.md.
  const Rgb white(0.725, 0.71, 0.68), red(0.63, 0.065, 0.05), green(0.14, 0.45, 0.091);

  Scene scene;
  scene.name = "cornell";
  std::vector<Surface>& s = scene.surfaces;
  s.push_back(quad("floor", mm(552.8, 0, 0), mm(0, 0, 0), mm(0, 0, 559.2), mm(549.6, 0, 559.2), white));
  // The light lies in the ceiling's plane, over the ceiling (as published: the ceiling has no
  // hole); the renderer draws the emitter on the tie.
  Surface light = quad("light", mm(343, 548.8, 227), mm(343, 548.8, 332), mm(213, 548.8, 332), mm(213, 548.8, 227),
                       Rgb::Zero());
  // Radiance (17, 12, 4) W/(m^2 sr) in Bitterli's scene; a Lambertian emitter's exitance is pi L.
  light.emission_w_m2 = std::numbers::pi * Rgb(17, 12, 4);
  // Black and uniformly emitting: its radiosity is exact on any mesh.
  light.max_divisions = 4;
  s.push_back(light);
  s.push_back(quad("ceiling", mm(556, 548.8, 0), mm(556, 548.8, 559.2), mm(0, 548.8, 559.2), mm(0, 548.8, 0), white));
  s.push_back(quad("back_wall", mm(549.6, 0, 559.2), mm(0, 0, 559.2), mm(0, 548.8, 559.2), mm(556, 548.8, 559.2),
                   white));
  s.push_back(quad("green_wall", mm(0, 0, 559.2), mm(0, 0, 0), mm(0, 548.8, 0), mm(0, 548.8, 559.2), green));
  // Warped as published (0.8 mm off its plane over 0.55 m): regularise_surfaces() splits it.
  s.push_back(quad("red_wall", mm(552.8, 0, 0), mm(549.6, 0, 559.2), mm(556, 548.8, 559.2), mm(556, 548.8, 0), red));

  // The short block: its top, then its four sides; no bottom (it stands on the floor).
  s.push_back(quad("short_top", mm(130, 165, 65), mm(82, 165, 225), mm(240, 165, 272), mm(290, 165, 114), white));
  s.push_back(quad("short_side_a", mm(290, 0, 114), mm(290, 165, 114), mm(240, 165, 272), mm(240, 0, 272), white));
  s.push_back(quad("short_side_b", mm(130, 0, 65), mm(130, 165, 65), mm(290, 165, 114), mm(290, 0, 114), white));
  s.push_back(quad("short_side_c", mm(82, 0, 225), mm(82, 165, 225), mm(130, 165, 65), mm(130, 0, 65), white));
  s.push_back(quad("short_side_d", mm(240, 0, 272), mm(240, 165, 272), mm(82, 165, 225), mm(82, 0, 225), white));
  // The tall block, likewise.
  s.push_back(quad("tall_top", mm(423, 330, 247), mm(265, 330, 296), mm(314, 330, 456), mm(472, 330, 406), white));
  s.push_back(quad("tall_side_a", mm(423, 0, 247), mm(423, 330, 247), mm(472, 330, 406), mm(472, 0, 406), white));
  s.push_back(quad("tall_side_b", mm(472, 0, 406), mm(472, 330, 406), mm(314, 330, 456), mm(314, 0, 456), white));
  s.push_back(quad("tall_side_c", mm(314, 0, 456), mm(314, 330, 456), mm(265, 330, 296), mm(265, 0, 296), white));
  s.push_back(quad("tall_side_d", mm(265, 0, 296), mm(265, 330, 296), mm(423, 330, 247), mm(423, 0, 247), white));

  // Published camera: position (278, 273, -800) mm, direction +z, up +y, focal length 35 mm on a
  // 25 mm x 25 mm film: vertical field of view 2 atan(12.5 / 35) = 39.31 degrees.
  const double published_fov_deg = 2 * std::atan(12.5 / 35.0) * 180 / std::numbers::pi;
  scene.cameras.push_back({"published", mm(278, 273, -800), mm(278, 273, 0), Vec3(0, 1, 0), published_fov_deg});
  // "blocks": from inside the front opening, above the blocks, looking down at them and their
  // shadows on the floor.
  scene.cameras.push_back({"blocks", mm(278, 450, 30), mm(278, 60, 330), Vec3(0, 1, 0), 60.0});
  // "corner": from the front right (green) corner towards the red wall's foot and the back wall.
  scene.cameras.push_back({"corner", mm(60, 400, 40), mm(500, 150, 450), Vec3(0, 1, 0), 55.0});

  // Silent: the red wall's split is documented (docs/cornell.md) and the same on every run.
  regularise_surfaces(scene, "cornell");
  return scene;
}

}  // namespace radrecon
