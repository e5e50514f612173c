#pragma once
// Small scenes the solver tests share.

#include <string>
#include <utility>
#include <vector>

#include "scene/scene.h"

namespace radrecon::testing_support {

/// A grey quad.
inline Surface quad(const std::string& name, const Vec3& c0, const Vec3& c1, const Vec3& c2, const Vec3& c3,
                    double reflectance, double emission = 0) {
  Surface s;
  s.name = name;
  s.corners = {c0, c1, c2, c3};
  s.reflectance = Rgb::Constant(reflectance);
  s.emission_w_m2 = Rgb::Constant(emission);
  return s;
}

/// A polygon about the point c with half-axes u and v: the parallelogram c +- u +- v, or the
/// triangle (c - u - v, c + u - v, c + v) inside it (random occluders in the visibility tests).
inline Surface centred_polygon(const std::string& name, const Vec3& c, const Vec3& u, const Vec3& v, bool triangle) {
  Surface s;
  s.name = name;
  if (triangle) s.set_triangle(c - u - v, c + u - v, c + v);
  else s.corners = {c - u - v, c + u - v, c + u + v, c - u + v};
  return s;
}

/// The axis-aligned box [lo, hi] as six quads with outward normals (counter-clockwise seen from
/// outside), in the order -x, +x, -y, +y, -z, +z, named so, black; `inward` reverses every one.
/// A convex solid (solver/convex_solids.h) unless turned inward.
inline std::vector<Surface> box_faces(const Vec3& lo, const Vec3& hi, bool inward = false) {
  const auto at = [&](int x, int y, int z) { return Vec3(x ? hi.x() : lo.x(), y ? hi.y() : lo.y(), z ? hi.z() : lo.z()); };
  std::vector<Surface> faces = {
      quad("-x", at(0, 0, 0), at(0, 0, 1), at(0, 1, 1), at(0, 1, 0), 0.0),
      quad("+x", at(1, 0, 0), at(1, 1, 0), at(1, 1, 1), at(1, 0, 1), 0.0),
      quad("-y", at(0, 0, 0), at(1, 0, 0), at(1, 0, 1), at(0, 0, 1), 0.0),
      quad("+y", at(0, 1, 0), at(0, 1, 1), at(1, 1, 1), at(1, 1, 0), 0.0),
      quad("-z", at(0, 0, 0), at(0, 1, 0), at(1, 1, 0), at(1, 0, 0), 0.0),
      quad("+z", at(0, 0, 1), at(1, 0, 1), at(1, 1, 1), at(0, 1, 1), 0.0),
  };
  if (inward)
    for (Surface& f : faces) std::swap(f.corners[1], f.corners[3]);
  return faces;
}

/// A closed unit box, every face of reflectance rho facing inwards; the top emits E W/m^2.
inline Scene closed_box(double rho, double E) {
  Scene box;
  box.name = "box";
  box.surfaces.push_back(quad("bottom", {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, rho));
  box.surfaces.push_back(quad("top", {0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}, rho, E));
  box.surfaces.push_back(quad("x0", {0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}, rho));
  box.surfaces.push_back(quad("x1", {1, 0, 0}, {1, 0, 1}, {1, 1, 1}, {1, 1, 0}, rho));
  box.surfaces.push_back(quad("y0", {0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}, rho));
  box.surfaces.push_back(quad("y1", {0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}, rho));
  return box;
}

/// The scene with every quad cut into the triangles (c0, c1, c2) and (c0, c2, c3), named
/// "NAME.a" and "NAME.b": the same geometry, as a modeller exporting triangles would write it.
inline Scene as_triangles(const Scene& scene) {
  Scene out = scene;
  out.surfaces.clear();
  for (const Surface& s : scene.surfaces) {
    Surface a = s, b = s;
    a.name = s.name + ".a";
    b.name = s.name + ".b";
    a.set_triangle(s.corners[0], s.corners[1], s.corners[2]);
    b.set_triangle(s.corners[0], s.corners[2], s.corners[3]);
    out.surfaces.push_back(a);
    out.surfaces.push_back(b);
  }
  return out;
}

}  // namespace radrecon::testing_support
