#pragma once
// A closed room whose light is part of its ceiling, for the energy tests of both solvers.

#include "solver/solution.h"
#include "support/scenes.h"

namespace radrecon::testing_support {

/// The room's total surface area and its light's, m^2.
inline constexpr double kClosedRoomArea_m2 = 2 * 3 * 2.5 + 2 * 3 * 2 + 2 * 2.5 * 2;
inline constexpr double kClosedRoomLight_m2 = 0.5;

/// A closed room 3 x 2.5 x 2 m, every surface of reflectance rho facing inwards; the ceiling is
/// tiled by a light of 1 x 0.5 m (exitance E, reflectance rho too) and four quads around it.
inline Scene closed_room(double rho, double E) {
  Scene room;
  room.name = "room";
  const double X = 3, Y = 2.5, Z = 2;
  auto add = [&](const std::string& name, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, double e = 0) {
    room.surfaces.push_back(quad(name, a, b, c, d, rho, e));
  };
  add("floor", {0, 0, 0}, {X, 0, 0}, {X, Y, 0}, {0, Y, 0});
  add("x0", {0, 0, 0}, {0, Y, 0}, {0, Y, Z}, {0, 0, Z});
  add("x1", {X, 0, 0}, {X, 0, Z}, {X, Y, Z}, {X, Y, 0});
  add("y0", {0, 0, 0}, {0, 0, Z}, {X, 0, Z}, {X, 0, 0});
  add("y1", {0, Y, 0}, {X, Y, 0}, {X, Y, Z}, {0, Y, Z});
  // Ceiling tiles facing down (corners clockwise seen from above): the light x in [1, 2],
  // y in [1, 1.5], and the four quads around it.
  auto tile = [&](const std::string& name, double x0, double y0, double x1, double y1, double e = 0) {
    add(name, {x0, y0, Z}, {x0, y1, Z}, {x1, y1, Z}, {x1, y0, Z}, e);
  };
  tile("ceiling_south", 0, 0, X, 1);
  tile("ceiling_north", 0, 1.5, X, Y);
  tile("ceiling_west", 0, 1, 1, 1.5);
  tile("ceiling_east", 2, 1, X, 1.5);
  tile("light", 1, 1, 2, 1.5, E);
  return room;
}

/// The same room with its ceiling one quad and the light lying on it, face down, as a modeller
/// places a lamp: the ceiling's part under the light is hidden (solver/covered.h), and the room's
/// visible area and closed forms are the tiled room's.
inline Scene closed_room_with_lamp(double rho, double E) {
  Scene room = closed_room(rho, E);
  std::erase_if(room.surfaces, [](const Surface& s) { return s.name.starts_with("ceiling_"); });
  room.surfaces.push_back(quad("ceiling", {0, 0, 2}, {0, 2.5, 2}, {3, 2.5, 2}, {3, 0, 2}, rho));
  return room;
}

/// The room with a block 0.78 x 0.66 x 0.9 m standing on its floor, open at its foot as the
/// Cornell box's blocks are (its five faces facing out, reflectance rho): the floor under it is
/// enclosed (solver/enclosed.h), and its edges lie off the floor's dyadic lines, so quadtree nodes
/// straddle them. Absorbed = emitted still holds; the block's faces add to the visible area.
inline Scene closed_room_with_standing_block(double rho, double E) {
  Scene room = closed_room(rho, E);
  for (Surface& f : box_faces({0.83, 0.71, 0}, {1.61, 1.37, 0.9})) {
    if (f.name == "-z") continue;  // no bottom: the faces stand on the floor
    f.name = "block" + f.name;
    f.reflectance = Rgb::Constant(rho);
    room.surfaces.push_back(f);
  }
  return room;
}

/// sum A B over every element of the solution, channel 0, W: the radiosity power the closed forms
/// predict (Phi / (1 - rho) in a closed room or box).
inline double radiosity_power_w(const Solution& sol) {
  double power = 0;
  for (const SurfaceSolution& s : sol.surfaces)
    for (const SolutionElement& e : s.elements) power += e.area_m2 * e.radiosity_w_m2[0];
  return power;
}

}  // namespace radrecon::testing_support
