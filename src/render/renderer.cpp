#include "render/renderer.h"

#include <cmath>
#include <limits>
#include <numbers>

#include "core/check.h"
#include "core/parallel.h"

namespace radrecon {

std::optional<Vec2> quad_parameters(const Surface& s, const Vec3& p) {
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
  if (std::abs(k2) <= 1e-12 * scale) {
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
  constexpr double kEdge = 1e-12;  // points on the border belong to the quad
  if (!(u >= -kEdge && u <= 1 + kEdge && v >= -kEdge && v <= 1 + kEdge)) return std::nullopt;
  return Vec2(std::clamp(u, 0.0, 1.0), std::clamp(v, 0.0, 1.0));
}

std::optional<SurfaceHit> intersect_scene(const Scene& scene, const Vec3& o, const Vec3& d) {
  std::optional<SurfaceHit> best;
  double t_best = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < scene.surfaces.size(); ++k) {
    const Surface& s = scene.surfaces[k];
    const Vec3 n = s.normal();
    const double denom = n.dot(d);
    if (denom == 0) continue;
    const double t = n.dot(s.corners[0] - o) / denom;
    if (!(t > 0 && t < t_best)) continue;
    const auto uv = quad_parameters(s, o + t * d);
    if (!uv) continue;
    t_best = t;
    best = SurfaceHit{k, denom > 0, uv->x(), uv->y(), t};
  }
  return best;
}

std::pair<Vec3, Vec3> camera_ray(const Camera& c, int width, int height, double x, double y) {
  const Vec3 forward = (c.target - c.eye).normalized();
  const Vec3 right = forward.cross(c.up).normalized();
  const Vec3 up = right.cross(forward);
  const double half_h = std::tan(0.5 * c.fov_deg * std::numbers::pi / 180.0);
  const double half_w = half_h * width / height;
  const double sx = (2 * x / width - 1) * half_w, sy = (1 - 2 * y / height) * half_h;
  return {c.eye, (forward + sx * right + sy * up).normalized()};
}

CameraHits trace_camera(const Scene& scene, const Camera& camera, const RenderOptions& options) {
  RR_CHECK(options.width > 0 && options.height > 0 && options.samples_per_axis > 0, "render options out of range");
  const int W = options.width, H = options.height, S = options.samples_per_axis;
  const size_t rays = static_cast<size_t>(W) * H * S * S;
  CameraHits out;
  out.options = options;
  out.hits.resize(rays);
  auto& hits = out.hits;
  // The hit of every ray (stratified, at the strata centres: deterministic).
  parallel_for(0, static_cast<std::int64_t>(rays), [&](std::int64_t r) {
    const size_t k = static_cast<size_t>(r);
    const size_t pixel = k / (S * S), sub = k % (S * S);
    const double x = static_cast<double>(pixel % W) + (static_cast<double>(sub % S) + 0.5) / S;
    const double y = static_cast<double>(pixel / W) + (static_cast<double>(sub / S) + 0.5) / S;
    const auto [o, d] = camera_ray(camera, W, H, x, y);
    hits[k] = intersect_scene(scene, o, d);
  });
  return out;
}

Image render(const Scene& scene, const Camera& camera, const SideReconstruction& reconstruction,
             const RenderOptions& options) {
  return shade(scene, trace_camera(scene, camera, options), reconstruction);
}

Image shade(const Scene& scene, const CameraHits& traced, const SideReconstruction& reconstruction) {
  const RenderOptions& options = traced.options;
  const int W = options.width, H = options.height, S = options.samples_per_axis;
  const size_t rays = traced.hits.size();
  const auto& hits = traced.hits;
  // Radiosity per ray, one batch per surface side.
  std::vector<double> radiosity(rays * 3, 0.0);
  for (size_t k = 0; k < rays; ++k)
    if (!hits[k])
      for (int c = 0; c < 3; ++c) radiosity[k * 3 + c] = options.background_w_m2[c];
  // The rays of each side in one pass (side k = 2 * surface + back), not one scan per side.
  std::vector<std::vector<size_t>> rays_of(2 * scene.surfaces.size());
  for (size_t k = 0; k < rays; ++k)
    if (hits[k]) rays_of[2 * hits[k]->surface + (hits[k]->back_side ? 1 : 0)].push_back(k);
  for (size_t side = 0; side < rays_of.size(); ++side) {
    const std::vector<size_t>& which = rays_of[side];
    if (which.empty()) continue;
    const size_t surface = side / 2;
    const Interpolant* f = reconstruction(surface, side % 2 == 1);
    if (!f) continue;  // black
    RR_CHECK(f->channels() == 3, "renderer needs 3-channel reconstructions");
    const Surface& s = scene.surfaces[surface];
    std::vector<Vec2> at;
    at.reserve(which.size());
    for (size_t k : which) at.emplace_back(hits[k]->u * s.length_u_m(), hits[k]->v * s.length_v_m());
    std::vector<double> values(which.size() * 3);
    f->evaluate(at, values);
    for (size_t j = 0; j < which.size(); ++j)
      for (int c = 0; c < 3; ++c) {
        const double v = values[j * 3 + c];
        radiosity[which[j] * 3 + c] = std::isfinite(v) ? v : 0.0;
      }
  }
  // Box filter over each pixel's rays.
  Image img(W, H);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      Rgb sum = Rgb::Zero();
      const size_t first = (static_cast<size_t>(y) * W + x) * S * S;
      for (int k = 0; k < S * S; ++k)
        for (int c = 0; c < 3; ++c) sum[c] += radiosity[(first + static_cast<size_t>(k)) * 3 + c];
      img.at(x, y) = sum / (S * S);
    }
  return img;
}

}  // namespace radrecon
