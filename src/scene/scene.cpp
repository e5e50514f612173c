#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>
#include <unordered_map>

#include "core/error.h"
#include "core/parse.h"
#include "core/tolerances.h"

namespace radrecon {

void Surface::set_triangle(const Vec3& c0, const Vec3& c1, const Vec3& c2) {
  corners = {c0, c1, c2, c2};
  corner_count = 3;
}

Vec3 Surface::point(double u, double v) const {
  if (is_triangle()) return corners[0] + u * (corners[1] - corners[0]) + v * (corners[2] - corners[0]);
  return (1 - u) * (1 - v) * corners[0] + u * (1 - v) * corners[1] + u * v * corners[2] +
         (1 - u) * v * corners[3];
}

Vec3 Surface::normal() const {
  // The diagonals' cross product is Newell's normal of a planar quad, robust for nearly
  // degenerate ones; for a triangle (corners[3] == corners[2]) it is (c1 - c0) x (c2 - c0).
  Vec3 n = (corners[2] - corners[0]).cross(corners[3] - corners[1]);
  return n.normalized();
}

double Surface::area_m2() const {
  return 0.5 * (corners[2] - corners[0]).cross(corners[3] - corners[1]).norm();
}

double Surface::length_u_m() const {
  if (is_triangle()) return (corners[1] - corners[0]).norm();
  return 0.5 * ((corners[1] - corners[0]).norm() + (corners[2] - corners[3]).norm());
}

double Surface::length_v_m() const {
  if (is_triangle()) return 2 * area_m2() / (corners[1] - corners[0]).norm();
  return 0.5 * ((corners[3] - corners[0]).norm() + (corners[2] - corners[1]).norm());
}

double Surface::frame_bend_m() const {
  if (is_triangle()) return 0;
  const Vec3 a = corners[1] - corners[0], b = corners[3] - corners[0], twist = corners[0] - corners[1] + corners[2] - corners[3];
  if (twist == Vec3::Zero()) return 0;
  // At each corner the plane's length dX becomes d(s, t) = diag(Lu, Lv) J^+ dX, J = [dP/du, dP/dv]:
  // stretched by at most 1 / sigma_min(M), M = [dP/du / Lu, dP/dv / Lv].
  const double lu = length_u_m(), lv = length_v_m();
  double stretch = 0;
  for (const auto& [u, v] : {std::pair{0.0, 0.0}, std::pair{1.0, 0.0}, std::pair{1.0, 1.0}, std::pair{0.0, 1.0}}) {
    const Vec3 m1 = (a + v * twist) / lu, m2 = (b + u * twist) / lv;
    const double g11 = m1.dot(m1), g12 = m1.dot(m2), g22 = m2.dot(m2);
    const double half_trace = 0.5 * (g11 + g22), det = g11 * g22 - g12 * g12;
    const double smallest = half_trace - std::sqrt(std::max(half_trace * half_trace - det, 0.0));
    stretch = std::max(stretch, smallest > 0 ? 1 / std::sqrt(smallest) : std::numeric_limits<double>::infinity());
  }
  return std::min(0.5 * twist.norm() * stretch, std::max(lu, lv));  // a sliver of a corner: at most the side
}

double Surface::shear_m() const {
  if (!is_triangle()) return 0;
  const Vec3 e = corners[1] - corners[0];
  return (corners[2] - corners[0]).dot(e) / e.norm();
}

bool Surface::in_domain(double u, double v) const {
  const double kEdge = tol::kQuadEdgeParameter;
  if (!(u >= -kEdge && v >= -kEdge)) return false;
  return is_triangle() ? u + v <= 1 + kEdge : u <= 1 + kEdge && v <= 1 + kEdge;
}

std::optional<Vec2> Surface::parameters(const Vec3& p) const { return parameters(p, normal()); }

std::optional<Vec2> Surface::parameters(const Vec3& p, const Vec3& n) const {
  const Surface& s = *this;
  // Solve p = point(u, v) in the surface's plane, projected to the two axes where the surface is
  // largest: linear for a triangle, a quadratic in v for a quad (linear for a parallelogram).
  int drop = 0;
  n.cwiseAbs().maxCoeff(&drop);
  const int a = (drop + 1) % 3, b = (drop + 2) % 3;
  auto xy = [&](const Vec3& q) { return Vec2(q[a], q[b]); };
  const Vec2 c0 = xy(s.corners[0]), c1 = xy(s.corners[1]), c2 = xy(s.corners[2]), c3 = xy(s.corners[3]);
  const Vec2 q = xy(p) - c0, e = c1 - c0;
  if (is_triangle()) {
    const Vec2 f = c2 - c0;
    const double det = cross(e, f);
    double u = cross(q, f) / det, v = cross(e, q) / det;
    if (!in_domain(u, v)) return std::nullopt;
    u = std::max(u, 0.0);
    v = std::max(v, 0.0);
    if (u + v > 1) {
      const double sum = u + v;
      u /= sum;
      v /= sum;
    }
    return Vec2(u, v);
  }
  const Vec2 f = c3 - c0, g = c0 - c1 + c2 - c3;
  const double k2 = cross(g, f), k1 = cross(e, f) + cross(q, g), k0 = cross(q, e);
  double v;
  const double scale = std::abs(cross(e, f));
  if (std::abs(k2) <= tol::kParallelogramRelative * scale) {
    v = -k0 / k1;
  } else {
    const double disc = k1 * k1 - 4 * k0 * k2;
    if (disc < 0) return std::nullopt;
    // The roots (-k1 -+ w) / (2 k2) without cancelling: one as q / k2, the other as k0 / q, q =
    // -(k1 + sign(k1) w) / 2. (-k1 + w) / (2 k2) cancelled to a few digits where the quad is
    // barely no parallelogram (k2 just above the threshold): (u, v) came out in steps of 3e-5, and
    // points 2e-5 of the quad outside it were taken in (a review).
    const double w = std::sqrt(disc);
    const double q = -0.5 * (k1 + std::copysign(w, k1));
    if (q == 0) {
      v = 0;  // k1 = 0 and a double root: k0 = 0 too
    } else {
      const double minus = k1 >= 0 ? q / k2 : k0 / q, plus = k1 >= 0 ? k0 / q : q / k2;  // (-k1 -+ w) / (2 k2)
      v = minus;  // the other root where this one lies beyond the border's tolerance (in_domain())
      if (v < -tol::kQuadEdgeParameter || v > 1 + tol::kQuadEdgeParameter) v = plus;
    }
  }
  const Vec2 denom = e + v * g;
  const double u = std::abs(denom.x()) > std::abs(denom.y()) ? (q.x() - v * f.x()) / denom.x() : (q.y() - v * f.y()) / denom.y();
  if (!in_domain(u, v)) return std::nullopt;  // points on the border belong to the quad
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
  const int n_corners = s.corner_count;
  if (n_corners != 3 && n_corners != 4) throw UserError(where + ".corners", "must have 3 or 4 corners");
  if (n_corners == 3 && s.corners[3] != s.corners[2]) throw UserError(where + ".corners", "triangle's corners[3] must repeat corners[2] (Surface::set_triangle)");
  for (int i = 0; i < n_corners; ++i)
    if (!finite(s.corners[i]) || s.corners[i].cwiseAbs().maxCoeff() > tol::kMaxCoordinate_m)
      throw UserError(where + ".corners[" + std::to_string(i) + "]",
                      "must be finite numbers of magnitude at most " + format_number(tol::kMaxCoordinate_m) + " m");
  double longest_sq = 0;
  for (int i = 0; i < n_corners; ++i)
    longest_sq = std::max(longest_sq, (s.corners[(i + 1) % n_corners] - s.corners[i]).squaredNorm());
  double longest = std::sqrt(longest_sq);
  const std::string kind = n_corners == 3 ? "triangle" : "quad";
  if (longest == 0 || s.area_m2() <= tol::kDegenerateAreaRelative * longest_sq) {
    // A bow tie's two halves cancel: zero area, though its corners are distinct and three of them
    // span a triangle.
    bool distinct = true;
    double spanned_m2 = 0;
    for (int i = 0; n_corners == 4 && i < n_corners; ++i) {
      for (int j = i + 1; j < n_corners; ++j)
        distinct = distinct && (s.corners[j] - s.corners[i]).squaredNorm() > tol::kDegenerateAreaRelative * longest_sq;
      spanned_m2 = std::max(spanned_m2, 0.5 * (s.corners[(i + 1) % 4] - s.corners[i]).cross(s.corners[(i + 2) % 4] - s.corners[i]).norm());
    }
    if (n_corners == 4 && distinct && spanned_m2 > tol::kDegenerateAreaRelative * longest_sq)
      throw UserError(where + ".corners", "quad crosses itself (a bow tie): its corners are not in order around it");
    throw UserError(where + ".corners", "degenerate " + kind + " (zero area: its corners are collinear or coincide)");
  }
  Vec3 n = s.normal();
  Vec3 centroid = 0.25 * (s.corners[0] + s.corners[1] + s.corners[2] + s.corners[3]);
  for (int i = 0; i < n_corners; ++i) {
    double off_plane = std::abs((s.corners[i] - centroid).dot(n));
    if (off_plane > tol::kPlanarityRelative * longest)
      throw UserError(where + ".corners",
                      "quad is not planar (corner " + std::to_string(i) + " is " +
                          format_number(off_plane) + " m off the plane)");
  }
  for (int i = 0; i < n_corners; ++i) {
    Vec3 e0 = s.corners[(i + 1) % n_corners] - s.corners[i];
    Vec3 e1 = s.corners[(i + 2) % n_corners] - s.corners[(i + 1) % n_corners];
    if (e0.cross(e1).dot(n) <= tol::kDegenerateAreaRelative * longest_sq)
      throw UserError(where + ".corners",
                      kind + " is not convex or its corners are not in order (at corner " +
                          std::to_string((i + 1) % n_corners) + ")");
  }
  if (const std::string problem = reflectance_problem(s.reflectance); !problem.empty()) throw UserError(where + ".reflectance", problem);
  if (const std::string problem = emission_problem(s.emission_w_m2); !problem.empty()) throw UserError(where + ".emission", problem);
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

std::string reflectance_problem(const Rgb& reflectance) {
  for (int c = 0; c < 3; ++c)
    if (!(reflectance[c] >= 0.0 && reflectance[c] < 1.0)) return "must be in [0,1), got " + format_number(reflectance[c]);
  return {};
}

std::string emission_problem(const Rgb& emission_w_m2) {
  for (int c = 0; c < 3; ++c)
    if (!(emission_w_m2[c] >= 0.0 && emission_w_m2[c] <= tol::kMaxEmission_w_m2))
      return "must be in [0, " + format_number(tol::kMaxEmission_w_m2) + "] W/m^2, got " + format_number(emission_w_m2[c]);
  return {};
}

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
  Vec3 lo = scene.surfaces[0].corners[0], hi = lo;
  for (const Surface& s : scene.surfaces)
    for (int i = 0; i < s.corner_count; ++i) {
      lo = lo.cwiseMin(s.corners[i]);
      hi = hi.cwiseMax(s.corners[i]);
    }
  if (const double extent = (hi - lo).norm(); extent < tol::kMinSceneExtent_m)
    throw UserError(source + ": surfaces", "the scene is " + format_number(extent) + " m across, less than the " +
                                               format_number(tol::kMinSceneExtent_m) +
                                               " m its visibility tolerances need (metres are the unit: scale the model up)");
}

namespace {

/// The largest distance of a quad's corners from the plane through their centroid with the
/// diagonals' normal, metres.
double off_plane_m(const Surface& s) {
  const Vec3 n = s.normal();
  const Vec3 centroid = 0.25 * (s.corners[0] + s.corners[1] + s.corners[2] + s.corners[3]);
  double off = 0;
  for (const Vec3& c : s.corners) off = std::max(off, std::abs((c - centroid).dot(n)));
  return off;
}

std::string metres(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g m", x);
  return buf;
}

}  // namespace

std::vector<std::string> regularise_surfaces(Scene& scene, const std::string& source) {
  std::vector<std::string> warnings;
  std::vector<Surface> out;
  out.reserve(scene.surfaces.size());
  std::unordered_map<std::string, size_t> index_by_name;  // the file's names (the first of each), made at the first split
  for (size_t index = 0; index < scene.surfaces.size(); ++index) {
    Surface& s = scene.surfaces[index];
    const std::string where = source + ": surfaces[" + std::to_string(index) + "] '" + s.name + "'";
    if (s.is_triangle() || !s.corners[0].allFinite() || !s.corners[1].allFinite() || !s.corners[2].allFinite() ||
        !s.corners[3].allFinite()) {
      out.push_back(s);
      continue;
    }
    double longest = 0;
    for (int i = 0; i < 4; ++i) longest = std::max(longest, (s.corners[(i + 1) % 4] - s.corners[i]).norm());
    // A repeated corner: the triangle of the other three.
    int repeated = -1;
    for (int i = 0; i < 4 && repeated < 0; ++i)
      if ((s.corners[(i + 1) % 4] - s.corners[i]).norm() <= tol::kRepeatedCornerRelative * longest) repeated = i;
    if (repeated >= 0 && longest > 0) {
      std::array<Vec3, 3> keep;
      for (int k = 0; k < 3; ++k) keep[k] = s.corners[(repeated + 1 + k) % 4];
      s.set_triangle(keep[0], keep[1], keep[2]);
      warnings.push_back(where + ": a quad with a repeated corner (" + std::to_string(repeated) +
                         "), read as a triangle");
      out.push_back(s);
      continue;
    }
    const Vec3 n = s.normal();
    if (!n.allFinite() || longest == 0) {
      out.push_back(s);  // degenerate: validate_scene() refuses it with the reason
      continue;
    }
    int reflex = -1, reflex_count = 0;
    for (int i = 0; i < 4; ++i) {
      const Vec3 e0 = s.corners[(i + 1) % 4] - s.corners[i], e1 = s.corners[(i + 2) % 4] - s.corners[(i + 1) % 4];
      if (e0.cross(e1).dot(n) <= 0) {
        reflex = (i + 1) % 4;
        ++reflex_count;
      }
    }
    const double off = off_plane_m(s);
    const bool warped = off > tol::kPlanarityRelative * longest;
    if (!warped && reflex_count == 0) {
      out.push_back(s);
      continue;
    }
    if (reflex_count > 1) {
      out.push_back(s);  // corners out of order (a bow tie): validate_scene() refuses it
      continue;
    }
    // Split along the diagonal through the reflex corner, else along the shorter diagonal.
    int d = 0;  // the diagonal from corner d to corner d + 2
    if (reflex >= 0)
      d = reflex % 2;
    else if ((s.corners[3] - s.corners[1]).norm() < (s.corners[2] - s.corners[0]).norm())
      d = 1;
    const auto c = [&](int k) { return s.corners[(d + k) % 4]; };
    Surface a = s, b = s;
    a.name = s.name + ".a";
    b.name = s.name + ".b";
    // A half named as another surface of the file: said of that one, by its own index (the
    // duplicate-name check after the split counts the halves).
    if (index_by_name.empty())
      for (size_t k = 0; k < scene.surfaces.size(); ++k) index_by_name.emplace(scene.surfaces[k].name, k);
    for (const std::string* half : {&a.name, &b.name})
      if (const auto other = index_by_name.find(*half); other != index_by_name.end())
        throw UserError(source + ": surfaces[" + std::to_string(other->second) + "].name",
                        "'" + *half + "' is the name of a half of surfaces[" + std::to_string(index) + "] '" + s.name +
                            "', " + (warped ? "a quad off its plane" : "a quad that is not convex") +
                            " split into two triangles: rename one of them");
    a.set_triangle(c(0), c(1), c(2));
    b.set_triangle(c(0), c(2), c(3));
    warnings.push_back(where + (warped ? ": a quad " + metres(off) + " off its plane" : std::string(": a quad that is not convex")) +
                       ", split into the triangles '" + a.name + "' and '" + b.name + "' along the diagonal of corners " +
                       std::to_string(d) + "-" + std::to_string(d + 2));
    out.push_back(a);
    out.push_back(b);
  }
  scene.surfaces = std::move(out);
  return warnings;
}

}  // namespace radrecon
