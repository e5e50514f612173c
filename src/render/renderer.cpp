#include "render/renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <span>
#include <vector>

#include "core/check.h"
#include "core/parallel.h"
#include "core/tolerances.h"
#include "render/surface_bvh.h"

namespace radrecon {

namespace {

bool emits(const Surface& s, bool back_side) { return (side_emission(s, back_side) > 0).any(); }

/// Where the ray o + t d meets the plane of `s` (through its corner 0, unit normal n =
/// s.normal()): t, or none when the ray runs parallel to it; `back_side` when the ray comes from
/// behind.
std::optional<double> plane_hit(const Surface& s, const Vec3& n, const Vec3& o, const Vec3& d, bool& back_side) {
  const double denom = n.dot(d);
  if (denom == 0) return std::nullopt;
  back_side = denom > 0;
  return n.dot(s.corners[0] - o) / denom;
}

/// The nearest hit among `surfaces` (ascending indices), by intersect_scene()'s rules.
/// The surfaces' normal() by index, made once for many rays; an empty one: each made as needed.
using SurfaceNormals = std::span<const Vec3>;

Vec3 normal_of(const Scene& scene, SurfaceNormals normals, size_t k) {
  return normals.empty() ? scene.surfaces[k].normal() : normals[k];
}

std::vector<Vec3> surface_normals(const Scene& scene) {
  std::vector<Vec3> out;
  out.reserve(scene.surfaces.size());
  for (const Surface& s : scene.surfaces) out.push_back(s.normal());
  return out;
}

template <class Surfaces>
std::optional<SurfaceHit> nearest_hit(const Scene& scene, SurfaceNormals normals, const Surfaces& surfaces,
                                      const Vec3& o, const Vec3& d) {
  std::optional<SurfaceHit> best;
  // A tie's order (renderer.h): an emitting side, then a side seen from its front (a one-sided
  // surface's back is no side to be seen: of a sheet's two faces back to back, the first listed
  // was drawn black from one side), then the rest; among equals the smaller surface, which lies
  // on the other (a rug on a floor was drawn or not by the order of the list).
  const auto tie_rank = [&](const Surface& s, bool back_side) { return emits(s, back_side) ? 2 : (!back_side || s.two_sided) ? 1 : 0; };
  int best_rank = 0;
  double best_area_m2 = -1;  // the best's area once a tie needs it
  double t_best = std::numeric_limits<double>::infinity();
  const double o_norm = o.norm();
  for (const size_t k : surfaces) {
    const Surface& s = scene.surfaces[k];
    const Vec3 n = normal_of(scene, normals, k);
    bool back_side = false;
    const std::optional<double> hit = plane_hit(s, n, o, d, back_side);
    if (!hit || !(*hit > 0)) continue;
    const double t = *hit;
    // Within the tie distance (relative to the magnitude of the coordinates there, |o| + t, whose
    // round-off it covers) the higher tie_rank wins; otherwise, or between equals, the nearer.
    const bool tie = best && std::abs(t - t_best) <= tol::kEmitterTieRelative * (o_norm + t_best);
    bool wins = t < t_best;
    const int rank = tie_rank(s, back_side);
    double area_m2 = -1;
    if (tie && rank != best_rank) {
      wins = rank > best_rank;
    } else if (tie) {
      if (best_area_m2 < 0) best_area_m2 = scene.surfaces[best->surface].area_m2();
      area_m2 = s.area_m2();
      if (area_m2 != best_area_m2) wins = area_m2 < best_area_m2;
    }
    if (!wins) continue;
    const auto uv = s.parameters(o + t * d, n);
    if (!uv) continue;
    t_best = t;
    best = SurfaceHit{k, back_side, uv->x(), uv->y(), t};
    best_rank = rank;
    best_area_m2 = area_m2;
  }
  return best;
}

/// Surfaces from which a scene is searched through its hierarchy rather than one by one.
constexpr size_t kBvhLeastSurfaces = 16;

}  // namespace

namespace {

std::optional<SurfaceHit> intersect_all(const Scene& scene, SurfaceNormals normals, const Vec3& o, const Vec3& d) {
  // Every surface's index, in order (std::views::iota does not build with clang on libstdc++ 12,
  // the sanitizer build's pairing).
  struct All {
    size_t n;
    struct It {
      size_t k;
      size_t operator*() const { return k; }
      It& operator++() { return ++k, *this; }
      bool operator!=(const It& o) const { return k != o.k; }
    };
    It begin() const { return {0}; }
    It end() const { return {n}; }
  };
  return nearest_hit(scene, normals, All{scene.surfaces.size()}, o, d);
}

std::optional<SurfaceHit> intersect_through(const Scene& scene, SurfaceNormals normals, const SurfaceBvh& bvh,
                                            const Vec3& o, const Vec3& d) {
  // The surfaces whose boxes the ray meets before the nearest hit found so far plus four tie
  // distances: one beyond can neither be the nearest nor tie with it, so the one-by-one search
  // over these, in surface order, finds what it finds over all of them.
  thread_local std::vector<size_t> candidates;
  candidates.clear();
  const double o_norm = o.norm();
  double t_hit = std::numeric_limits<double>::infinity(), t_cut = t_hit;
  size_t seen = 0;  // candidates whose hit has lowered the cut
  bvh.collect(o, d.cwiseInverse(), [&] {
    for (; seen < candidates.size(); ++seen) {
      const Surface& s = scene.surfaces[candidates[seen]];
      const Vec3 n = normal_of(scene, normals, candidates[seen]);
      bool back_side = false;
      const std::optional<double> t = plane_hit(s, n, o, d, back_side);
      if (!t || !(*t > 0 && *t < t_hit) || !s.parameters(o + *t * d, n)) continue;
      t_hit = *t;
      t_cut = *t + 4 * tol::kEmitterTieRelative * (o_norm + *t);
    }
    return t_cut;
  }, candidates);
  std::sort(candidates.begin(), candidates.end());
  return nearest_hit(scene, normals, candidates, o, d);
}

}  // namespace

std::optional<SurfaceHit> intersect_scene(const Scene& scene, const Vec3& o, const Vec3& d) {
  return intersect_all(scene, {}, o, d);
}

std::optional<SurfaceHit> intersect_scene(const Scene& scene, const SurfaceBvh& bvh, const Vec3& o, const Vec3& d) {
  return intersect_through(scene, {}, bvh, o, d);
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

int tile_side(const RenderOptions& options) {
  RR_CHECK(options.tile_size >= 0 && options.samples_per_axis > 0, "render options out of range");
  if (options.tile_size > 0) return options.tile_size;
  const size_t rays_per_pixel = static_cast<size_t>(options.samples_per_axis) * options.samples_per_axis;
  const auto side = static_cast<int>(std::sqrt(static_cast<double>(kRenderTileRays / rays_per_pixel)));
  return std::max(side, 1);
}

size_t render_memory_bytes(const RenderOptions& options) {
  const size_t pixels = static_cast<size_t>(options.width) * static_cast<size_t>(options.height);
  const auto tile = static_cast<size_t>(tile_side(options));
  const size_t tile_rays = std::min(tile * tile, pixels) * options.samples_per_axis * options.samples_per_axis;
  return pixels * (sizeof(Rgb) + 1) + tile_rays * 120;
}

CameraHits trace_camera(const Scene& scene, const Camera& camera, const RenderOptions& options) {
  return trace_camera(scene, camera, options, PixelRect{0, 0, options.width, options.height});
}

namespace {

/// What tracing needs of the scene, made once per camera or render() rather than per tile: each
/// surface's unit normal and frame, and the scene's hierarchy if it has one (many surfaces).
struct TraceContext {
  explicit TraceContext(const Scene& scene) : normals(surface_normals(scene)) {
    for (const Surface& s : scene.surfaces) frames.push_back(s.frame());
    if (scene.surfaces.size() >= kBvhLeastSurfaces) bvh.emplace(scene);
  }
  std::vector<Vec3> normals;
  std::vector<SurfaceFrame> frames;
  std::optional<SurfaceBvh> bvh;
};

CameraHits trace_rect(const Scene& scene, const TraceContext& context, const Camera& camera,
                      const RenderOptions& options, const PixelRect& rect) {
  RR_CHECK(options.width > 0 && options.height > 0 && options.samples_per_axis > 0, "render options out of range");
  RR_CHECK(0 <= rect.x_begin && rect.x_begin < rect.x_end && rect.x_end <= options.width, "camera columns out of range");
  RR_CHECK(0 <= rect.y_begin && rect.y_begin < rect.y_end && rect.y_end <= options.height, "camera rows out of range");
  const int W = options.width, H = options.height, S = options.samples_per_axis;
  const size_t rect_w = static_cast<size_t>(rect.x_end - rect.x_begin);
  const size_t per_pixel = static_cast<size_t>(S) * S;
  const size_t rays = rect.pixels() * per_pixel;
  RR_CHECK(rays <= std::numeric_limits<std::uint32_t>::max(), "too many rays for one camera trace");
  CameraHits out;
  out.options = options;
  out.pixels = rect;
  out.rays = rays;
  // The hit of every ray (stratified, at the strata centres: deterministic): its side's slot
  // (kNone: none) and the point in the side's (s, t).
  constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> slot(rays);
  std::vector<Vec2> st(rays);
  const SurfaceBvh* bvh = context.bvh ? &*context.bvh : nullptr;
  parallel_for(0, static_cast<std::int64_t>(rays), [&](std::int64_t r) {
    const size_t k = static_cast<size_t>(r);
    const size_t pixel = k / per_pixel, sub = k % per_pixel;
    const double x = static_cast<double>(rect.x_begin + pixel % rect_w) + (static_cast<double>(sub % S) + 0.5) / S;
    const double y = static_cast<double>(rect.y_begin + pixel / rect_w) + (static_cast<double>(sub / S) + 0.5) / S;
    const auto [o, d] = camera_ray(camera, W, H, x, y);
    const std::optional<SurfaceHit> hit = bvh != nullptr ? intersect_through(scene, context.normals, *bvh, o, d)
                                                         : intersect_all(scene, context.normals, o, d);
    slot[k] = hit ? static_cast<std::uint32_t>(SideRef{hit->surface, hit->back_side}.slot()) : kNone;
    if (hit) st[k] = context.frames[hit->surface].st(Vec2(hit->u, hit->v));
  });
  // The sides met, by slot, each with its rays in order.
  std::vector<std::uint32_t> count(side_slots(scene), 0);
  for (const std::uint32_t s : slot)
    if (s != kNone) ++count[s];
  std::vector<std::uint32_t> place(count.size());  // the side's place in out.sides
  for (size_t s = 0; s < count.size(); ++s)
    if (count[s] > 0) {
      place[s] = static_cast<std::uint32_t>(out.sides.size());
      CameraHits::SideRays& side = out.sides.emplace_back(CameraHits::SideRays{s, {}, {}});
      side.rays.reserve(count[s]);
      side.st.reserve(count[s]);
    }
  for (size_t k = 0; k < rays; ++k)
    if (slot[k] != kNone) {
      CameraHits::SideRays& side = out.sides[place[slot[k]]];
      side.rays.push_back(static_cast<std::uint32_t>(k));
      side.st.push_back(st[k]);
    }
  return out;
}

}  // namespace

CameraHits trace_camera(const Scene& scene, const Camera& camera, const RenderOptions& options, const PixelRect& rect) {
  return trace_rect(scene, TraceContext(scene), camera, options, rect);
}

CameraHits join_bands(std::vector<CameraHits>& bands) {
  RR_CHECK(!bands.empty(), "no bands to join");
  CameraHits out;
  out.options = bands.front().options;
  out.pixels = {0, bands.front().pixels.y_begin, out.options.width, bands.front().pixels.y_begin};
  // Each side's rays over all bands, so that its arrays are made once at their size.
  std::vector<std::pair<size_t, size_t>> count;  // (slot, rays), by slot
  for (const CameraHits& band : bands)
    for (const CameraHits::SideRays& side : band.sides) {
      auto at = std::lower_bound(count.begin(), count.end(), std::pair{side.slot, size_t{0}});
      if (at == count.end() || at->first != side.slot) at = count.insert(at, {side.slot, 0});
      at->second += side.rays.size();
    }
  for (const auto& [slot, rays] : count) {
    CameraHits::SideRays& side = out.sides.emplace_back(CameraHits::SideRays{slot, {}, {}});
    side.rays.reserve(rays);
    side.st.reserve(rays);
  }
  for (CameraHits& band : bands) {
    RR_CHECK(band.pixels.x_begin == 0 && band.pixels.x_end == out.options.width && band.pixels.y_begin == out.pixels.y_end,
             "bands must be as wide as the image and follow one another");
    out.pixels.y_end = band.pixels.y_end;
    // Ray k of a band is ray out.rays + k of the rows so far (pixels row by row, their rays in
    // turn); each side's rays stay in increasing order, the sides by slot.
    RR_CHECK(out.rays + band.rays <= std::numeric_limits<std::uint32_t>::max(), "too many rays for one camera trace");
    const auto first = static_cast<std::uint32_t>(out.rays);
    for (CameraHits::SideRays& side : band.sides) {
      const auto at = std::lower_bound(out.sides.begin(), out.sides.end(), side.slot,
                                       [](const CameraHits::SideRays& s, size_t slot) { return s.slot < slot; });
      for (const std::uint32_t k : side.rays) at->rays.push_back(first + k);
      at->st.insert(at->st.end(), side.st.begin(), side.st.end());
    }
    out.rays += band.rays;
    band = CameraHits{};
  }
  return out;
}

Rendering render(const Scene& scene, const Camera& camera, const SideReconstruction& reconstruction,
                 const RenderOptions& options, const RenderProgress& progress) {
  const int tile = tile_side(options);
  Rendering out{Image(options.width, options.height),
                std::vector<std::uint8_t>(static_cast<size_t>(options.width) * options.height, 0)};
  const double pixels = static_cast<double>(options.width) * options.height;
  size_t done = 0;
  const TraceContext context(scene);  // once for all tiles
  for (int y = 0; y < options.height; y += tile)
    for (int x = 0; x < options.width; x += tile) {
      const PixelRect rect{x, y, std::min(options.width, x + tile), std::min(options.height, y + tile)};
      shade(scene, trace_rect(scene, context, camera, options, rect), reconstruction, out);
      done += rect.pixels();
      if (progress) progress(static_cast<double>(done) / pixels);
    }
  return out;
}

Image shade(const Scene& scene, const CameraHits& traced, const SideReconstruction& reconstruction) {
  const RenderOptions& options = traced.options;
  RR_CHECK(traced.pixels.pixels() == static_cast<size_t>(options.width) * options.height,
           "shade() of a part of the image needs a Rendering to write into");
  Rendering out{Image(options.width, options.height),
                std::vector<std::uint8_t>(static_cast<size_t>(options.width) * options.height, 0)};
  shade(scene, traced, reconstruction, out);
  return std::move(out.image);
}

void shade(const Scene& scene, const CameraHits& traced, const SideReconstruction& reconstruction, Rendering& out) {
  const RenderOptions& options = traced.options;
  const int W = options.width, S = options.samples_per_axis;
  Image& img = out.image;
  RR_CHECK(img.width() == W && img.height() == options.height, "image size does not match the camera's");
  RR_CHECK_EQ(out.reflecting.size(), static_cast<size_t>(W) * options.height, "mask size does not match the camera's");
  const size_t rays = traced.rays;
  // Radiosity per ray (the background where a ray met nothing, black on a side without a
  // reconstruction); and whether the ray met a reflecting side.
  std::vector<double> radiosity(rays * 3);
  std::vector<std::uint8_t> reflecting(rays, 0), without_value(rays, 0);
  parallel_for(0, static_cast<std::int64_t>(rays), [&](std::int64_t k) {
    for (int c = 0; c < 3; ++c) radiosity[static_cast<size_t>(k) * 3 + c] = options.background_w_m2[c];
  });
  std::vector<double> values;
  for (const CameraHits::SideRays& hits : traced.sides) {
    RR_CHECK(hits.slot < side_slots(scene), "camera traced for another scene");
    const SideRef side = SideRef::from_slot(hits.slot);
    const Interpolant* f = reconstruction(side);
    const bool reflects = f != nullptr && !(side_emission(scene.surfaces[side.surface], side.back_side) > 0).any();
    if (f != nullptr) {
      RR_CHECK_EQ(f->channels(), 3, "renderer needs 3-channel reconstructions");
      values.resize(hits.rays.size() * 3);
      f->evaluate(hits.st, values);
    }
    parallel_for(0, static_cast<std::int64_t>(hits.rays.size()), [&](std::int64_t j) {
      const size_t k = hits.rays[static_cast<size_t>(j)];
      for (int c = 0; c < 3; ++c) {
        const double v = f != nullptr ? values[static_cast<size_t>(j) * 3 + c] : 0.0;  // no reconstruction: black
        radiosity[k * 3 + c] = std::isfinite(v) ? v : 0.0;
        if (!std::isfinite(v)) without_value[k] = 1;
      }
      // A ray drawn black for want of a value shows nothing lit: it does not count towards the
      // white point (it lowered it: 0.80 for 0.96 with 74% of rays without value).
      reflecting[k] = reflects && !without_value[k];
    });
  }
  out.rays += rays;
  out.rays_without_value += static_cast<std::size_t>(std::count(without_value.begin(), without_value.end(), 1));
  // Box filter over each pixel's rays.
  const PixelRect& rect = traced.pixels;
  const int rect_w = rect.x_end - rect.x_begin;
  const size_t per_pixel = static_cast<size_t>(S) * S;
  parallel_for(0, static_cast<std::int64_t>(rect.pixels()), [&](std::int64_t p) {
    const int x = rect.x_begin + static_cast<int>(p % rect_w), y = rect.y_begin + static_cast<int>(p / rect_w);
    const size_t first = static_cast<size_t>(p) * per_pixel;  // the pixel's first ray
    Rgb sum = Rgb::Zero();
    bool all_reflecting = true;
    for (size_t k = first; k < first + per_pixel; ++k) {
      for (int c = 0; c < 3; ++c) sum[c] += radiosity[k * 3 + c];
      all_reflecting = all_reflecting && reflecting[k];
    }
    img.at(x, y) = sum / (S * S);
    out.reflecting[static_cast<size_t>(y) * W + x] = all_reflecting;
  });
}

}  // namespace radrecon
