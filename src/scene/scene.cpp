#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "core/error.h"
#include "core/tolerances.h"

namespace radrecon {

Vec3 Surface::point(double u, double v) const {
  return (1 - u) * (1 - v) * corners[0] + u * (1 - v) * corners[1] + u * v * corners[2] +
         (1 - u) * v * corners[3];
}

Vec3 Surface::normal() const {
  // Newell's normal is exact for planar polygons and robust for nearly degenerate ones.
  Vec3 n = (corners[2] - corners[0]).cross(corners[3] - corners[1]);
  return n.normalized();
}

double Surface::area_m2() const {
  return 0.5 * (corners[2] - corners[0]).cross(corners[3] - corners[1]).norm();
}

double Surface::length_u_m() const {
  return 0.5 * ((corners[1] - corners[0]).norm() + (corners[2] - corners[3]).norm());
}

double Surface::length_v_m() const {
  return 0.5 * ((corners[3] - corners[0]).norm() + (corners[2] - corners[1]).norm());
}

std::optional<Vec2> Surface::parameters(const Vec3& p) const {
  const Surface& s = *this;
  // Solve p = (1-u)(1-v) c0 + u(1-v) c1 + u v c2 + (1-u) v c3 in the quad's plane, projected to
  // the two axes where the quad is largest: a quadratic in v (linear for a parallelogram).
  const Vec3 n = s.normal();
  int drop = 0;
  n.cwiseAbs().maxCoeff(&drop);
  const int a = (drop + 1) % 3, b = (drop + 2) % 3;
  auto xy = [&](const Vec3& q) { return Vec2(q[a], q[b]); };
  const Vec2 c0 = xy(s.corners[0]), c1 = xy(s.corners[1]), c2 = xy(s.corners[2]), c3 = xy(s.corners[3]);
  const Vec2 q = xy(p) - c0, e = c1 - c0, f = c3 - c0, g = c0 - c1 + c2 - c3;
  auto cross = [](const Vec2& x, const Vec2& y) { return x.x() * y.y() - x.y() * y.x(); };
  const double k2 = cross(g, f), k1 = cross(e, f) + cross(q, g), k0 = cross(q, e);
  double v;
  const double scale = std::abs(cross(e, f));
  if (std::abs(k2) <= tol::kParallelogramRelative * scale) {
    v = -k0 / k1;
  } else {
    const double disc = k1 * k1 - 4 * k0 * k2;
    if (disc < 0) return std::nullopt;
    const double w = std::sqrt(disc);
    v = (-k1 - w) / (2 * k2);
    if (v < 0 || v > 1) v = (-k1 + w) / (2 * k2);
  }
  const Vec2 denom = e + v * g;
  const double u = std::abs(denom.x()) > std::abs(denom.y()) ? (q.x() - v * f.x()) / denom.x() : (q.y() - v * f.y()) / denom.y();
  const double kEdge = tol::kQuadEdgeParameter;  // points on the border belong to the quad
  if (!(u >= -kEdge && u <= 1 + kEdge && v >= -kEdge && v <= 1 + kEdge)) return std::nullopt;
  return Vec2(std::clamp(u, 0.0, 1.0), std::clamp(v, 0.0, 1.0));
}

std::optional<size_t> Scene::find_surface(const std::string& name) const {
  for (size_t i = 0; i < surfaces.size(); ++i)
    if (surfaces[i].name == name) return i;
  return std::nullopt;
}

namespace {

bool finite(const Vec3& p) { return p.allFinite(); }

void validate_surface(const Surface& s, const std::string& where) {
  if (s.name.empty()) throw UserError(where + ".name", "must not be empty");
  for (int i = 0; i < 4; ++i)
    if (!finite(s.corners[i]) || s.corners[i].cwiseAbs().maxCoeff() > tol::kMaxCoordinate_m)
      throw UserError(where + ".corners[" + std::to_string(i) + "]",
                      "must be finite numbers of magnitude at most " + std::to_string(tol::kMaxCoordinate_m) + " m");
  double longest_sq = 0;
  for (int i = 0; i < 4; ++i)
    longest_sq = std::max(longest_sq, (s.corners[(i + 1) % 4] - s.corners[i]).squaredNorm());
  double longest = std::sqrt(longest_sq);
  if (longest == 0 || s.area_m2() <= tol::kDegenerateAreaRelative * longest_sq)
    throw UserError(where + ".corners", "degenerate quad (zero area)");
  Vec3 n = s.normal();
  Vec3 centroid = 0.25 * (s.corners[0] + s.corners[1] + s.corners[2] + s.corners[3]);
  for (int i = 0; i < 4; ++i) {
    double off_plane = std::abs((s.corners[i] - centroid).dot(n));
    if (off_plane > tol::kPlanarityRelative * longest)
      throw UserError(where + ".corners",
                      "quad is not planar (corner " + std::to_string(i) + " is " +
                          std::to_string(off_plane) + " m off the plane)");
  }
  for (int i = 0; i < 4; ++i) {
    Vec3 e0 = s.corners[(i + 1) % 4] - s.corners[i];
    Vec3 e1 = s.corners[(i + 2) % 4] - s.corners[(i + 1) % 4];
    if (e0.cross(e1).dot(n) <= tol::kDegenerateAreaRelative * longest_sq)
      throw UserError(where + ".corners",
                      "quad is not convex or its corners are not in order (at corner " +
                          std::to_string((i + 1) % 4) + ")");
  }
  for (int c = 0; c < 3; ++c) {
    double r = s.reflectance[c];
    if (!(r >= 0.0 && r < 1.0))
      throw UserError(where + ".reflectance", "must be in [0,1), got " + std::to_string(r));
    double e = s.emission_w_m2[c];
    if (!(e >= 0.0 && e <= tol::kMaxEmission_w_m2))
      throw UserError(where + ".emission", "must be in [0, 1e12] W/m^2, got " + std::to_string(e));
  }
  if (s.max_divisions && *s.max_divisions < 1)
    throw UserError(where + ".mesh.max_divisions", "must be at least 1");
}

void validate_camera(const Camera& c, const std::string& where) {
  if (c.name.empty()) throw UserError(where + ".name", "must not be empty");
  if (!finite(c.eye)) throw UserError(where + ".eye", "must be finite numbers");
  if (!finite(c.target)) throw UserError(where + ".target", "must be finite numbers");
  if (!finite(c.up)) throw UserError(where + ".up", "must be finite numbers");
  Vec3 dir = c.target - c.eye;
  if (dir.norm() == 0) throw UserError(where + ".target", "must differ from eye");
  if (c.up.norm() == 0 || dir.normalized().cross(c.up.normalized()).norm() < tol::kParallelSine)
    throw UserError(where + ".up", "must not be zero or parallel to the view direction");
  if (!(c.fov_deg > 0 && c.fov_deg < 180))
    throw UserError(where + ".fov_deg", "must be in (0, 180)");
}

}  // namespace

void validate_scene(const Scene& scene, const std::string& source) {
  if (scene.surfaces.empty()) throw UserError(source + ": surfaces", "the scene has no surface");
  std::set<std::string> names;
  for (size_t i = 0; i < scene.surfaces.size(); ++i) {
    std::string where = source + ": surfaces[" + std::to_string(i) + "]";
    validate_surface(scene.surfaces[i], where);
    if (!names.insert(scene.surfaces[i].name).second)
      throw UserError(where + ".name", "duplicate surface name '" + scene.surfaces[i].name + "'");
    if (scene.surfaces[i].name.find('/') != std::string::npos)
      throw UserError(where + ".name", "must not contain '/' (reserved for the sides of two-sided surfaces)");
  }
  std::set<std::string> camera_names;
  for (size_t i = 0; i < scene.cameras.size(); ++i) {
    std::string where = source + ": cameras[" + std::to_string(i) + "]";
    validate_camera(scene.cameras[i], where);
    if (!camera_names.insert(scene.cameras[i].name).second)
      throw UserError(where + ".name", "duplicate camera name '" + scene.cameras[i].name + "'");
  }
  // Some surface must emit a power (W) that is a normal double: an exitance so small that the
  // power underflows would leave nothing to distribute.
  bool emits = false;
  for (const Surface& s : scene.surfaces)
    emits = emits || (s.area_m2() * s.emission_w_m2 >= std::numeric_limits<double>::min()).any();
  if (!emits) throw UserError(source + ": surfaces", "no surface emits light (every emitted power is 0 or underflows)");
}

}  // namespace radrecon
