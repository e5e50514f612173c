#include "render/renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/check.h"
#include "core/parallel.h"

namespace radrecon {

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
    const auto uv = s.parameters(o + t * d);
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
  return trace_camera(scene, camera, options, 0, options.height);
}

CameraHits trace_camera(const Scene& scene, const Camera& camera, const RenderOptions& options, int row_begin,
                        int row_end) {
  RR_CHECK(options.width > 0 && options.height > 0 && options.samples_per_axis > 0, "render options out of range");
  RR_CHECK(0 <= row_begin && row_begin < row_end && row_end <= options.height, "camera rows out of range");
  const int W = options.width, H = options.height, S = options.samples_per_axis;
  const size_t rays = static_cast<size_t>(W) * (row_end - row_begin) * S * S;
  CameraHits out;
  out.options = options;
  out.row_begin = row_begin;
  out.row_end = row_end;
  out.hits.resize(rays);
  auto& hits = out.hits;
  const size_t first_pixel = static_cast<size_t>(row_begin) * W;
  // The hit of every ray (stratified, at the strata centres: deterministic).
  parallel_for(0, static_cast<std::int64_t>(rays), [&](std::int64_t r) {
    const size_t k = static_cast<size_t>(r);
    const size_t pixel = first_pixel + k / (S * S), sub = k % (S * S);
    const double x = static_cast<double>(pixel % W) + (static_cast<double>(sub % S) + 0.5) / S;
    const double y = static_cast<double>(pixel / W) + (static_cast<double>(sub / S) + 0.5) / S;
    const auto [o, d] = camera_ray(camera, W, H, x, y);
    hits[k] = intersect_scene(scene, o, d);
  });
  return out;
}

Image render(const Scene& scene, const Camera& camera, const SideReconstruction& reconstruction,
             const RenderOptions& options, const RenderProgress& progress) {
  // Bands of rows, so that memory holds the image and one band's rays, whatever the size.
  const size_t rays_per_row = static_cast<size_t>(options.width) * options.samples_per_axis * options.samples_per_axis;
  const int band_rows = static_cast<int>(std::clamp<size_t>(kRenderBandRays / rays_per_row, 1, options.height));
  Image img(options.width, options.height);
  for (int row = 0; row < options.height; row += band_rows) {
    const int end = std::min(options.height, row + band_rows);
    shade(scene, trace_camera(scene, camera, options, row, end), reconstruction, img);
    if (progress) progress(static_cast<double>(end) / options.height);
  }
  return img;
}

Image shade(const Scene& scene, const CameraHits& traced, const SideReconstruction& reconstruction) {
  RR_CHECK(traced.row_begin == 0 && traced.row_end == traced.options.height, "shade() of a band needs an image");
  Image img(traced.options.width, traced.options.height);
  shade(scene, traced, reconstruction, img);
  return img;
}

void shade(const Scene& scene, const CameraHits& traced, const SideReconstruction& reconstruction, Image& img) {
  const RenderOptions& options = traced.options;
  const int W = options.width, S = options.samples_per_axis;
  RR_CHECK(img.width() == W && img.height() == options.height, "image size does not match the camera's");
  const size_t rays = traced.hits.size();
  const auto& hits = traced.hits;
  // Radiosity per ray, one batch per surface side.
  std::vector<double> radiosity(rays * 3, 0.0);
  for (size_t k = 0; k < rays; ++k)
    if (!hits[k])
      for (int c = 0; c < 3; ++c) radiosity[k * 3 + c] = options.background_w_m2[c];
  // The rays of each side in one pass, not one scan per side.
  std::vector<std::vector<size_t>> rays_of(side_slots(scene));
  for (size_t k = 0; k < rays; ++k)
    if (hits[k]) rays_of[SideRef{hits[k]->surface, hits[k]->back_side}.slot()].push_back(k);
  for (size_t slot = 0; slot < rays_of.size(); ++slot) {
    const std::vector<size_t>& which = rays_of[slot];
    if (which.empty()) continue;
    const SideRef side = SideRef::from_slot(slot);
    const Interpolant* f = reconstruction(side);
    if (!f) continue;  // black
    RR_CHECK_EQ(f->channels(), 3, "renderer needs 3-channel reconstructions");
    const Surface& s = scene.surfaces[side.surface];
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
  for (int y = traced.row_begin; y < traced.row_end; ++y)
    for (int x = 0; x < W; ++x) {
      Rgb sum = Rgb::Zero();
      const size_t first = (static_cast<size_t>(y - traced.row_begin) * W + x) * S * S;
      for (int k = 0; k < S * S; ++k)
        for (int c = 0; c < 3; ++c) sum[c] += radiosity[(first + static_cast<size_t>(k)) * 3 + c];
      img.at(x, y) = sum / (S * S);
    }
}

}  // namespace radrecon
