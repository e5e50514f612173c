#include "scene/scene.h"

namespace radrecon {

Scene paper_scene() {
  // The experiment of the design brief (after Hinkenjann & Pietrek's Fig. 2): a ground patch lit
  // by a rectangular light, with two perpendicular walls casting shadows. The walls are not on a
  // line of the 16 x 16 grid nor of any quadtree level.
  Scene scene;
  scene.name = "paper";
  auto grey = [](double v) { return Rgb(v, v, v); };

  Surface ground;
  ground.name = "ground";
  ground.corners = {Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(4, 4, 0), Vec3(0, 4, 0)};  // faces +z
  ground.reflectance = grey(0.5);

  Surface light;
  light.name = "light";
  light.corners = {Vec3(1, 1, 2.5), Vec3(1, 2, 2.5), Vec3(2, 2, 2.5), Vec3(2, 1, 2.5)};  // faces -z
  light.emission_w_m2 = grey(40.0);
  // Black and uniformly emitting: its radiosity is exact on any mesh, so a coarse one suffices.
  light.max_divisions = 4;

  Surface wall1;
  wall1.name = "wall1";  // plane x = 2.6, front faces -x (towards the light)
  wall1.corners = {Vec3(2.6, 2.6, 0), Vec3(2.6, 0.6, 0), Vec3(2.6, 0.6, 1), Vec3(2.6, 2.6, 1)};
  wall1.reflectance = grey(0.5);
  wall1.two_sided = true;
  // The ground is the surface under study; 3 cm elements on the walls (64 x 32) are ample for
  // the light they reflect onto it, and keep the 400 x 400 reference fast.
  wall1.max_divisions = 64;

  Surface wall2;
  wall2.name = "wall2";  // plane y = 2.6, front faces -y (towards the light)
  wall2.corners = {Vec3(0.6, 2.6, 0), Vec3(2.6, 2.6, 0), Vec3(2.6, 2.6, 1), Vec3(0.6, 2.6, 1)};
  wall2.reflectance = grey(0.5);
  wall2.two_sided = true;
  wall2.max_divisions = 64;

  scene.surfaces = {ground, light, wall1, wall2};

  // "view": from outside the L, above, looking at the walls, their shadows and their feet.
  scene.cameras.push_back({"view", Vec3(5.6, 5.0, 3.2), Vec3(2.3, 2.3, 0.2), Vec3(0, 0, 1), 50.0});
  // "closeup": the foot of wall1 and the penumbra behind it.
  scene.cameras.push_back({"closeup", Vec3(3.9, 2.0, 1.1), Vec3(2.75, 1.7, 0.0), Vec3(0, 0, 1), 35.0});
  return scene;
}

}  // namespace radrecon
