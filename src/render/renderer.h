#pragma once
// A ray-casting renderer for radiosity solutions: for each pixel, several stratified rays from a
// pinhole camera find the visible surface side and its (u,v); the side's reconstruction gives
// the radiosity there (W/m^2), averaged over the pixel's rays. Radiosity is evaluated in one
// batch per surface side, not per ray. render() works tile by tile, so that memory holds the
// image and one tile's rays whatever the size and the rays per pixel; every pixel is the same,
// bit for bit, whatever the tiles and the number of threads.

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "core/image.h"
#include "reconstruct/interpolant.h"
#include "scene/scene.h"
#include "scene/side.h"

namespace radrecon {

/// Where a ray meets the scene: the surface, which side, and the surface parameters.
struct SurfaceHit {
  size_t surface;
  bool back_side;
  double u, v;  ///< in [0,1]
  double t;     ///< ray parameter, metres along a unit direction
};

/// The nearest surface hit by the ray o + t d (d of unit length), t > 0, if any. An emitting side
/// wins a tie: a light in the plane of a ceiling (hit at the same t, within
/// tol::kEmitterTieRelative (|o| + t)) is seen, not the ceiling. Then a side seen from its front
/// (a two-sided surface's either side) wins over a one-sided surface's back: of a sheet's two
/// faces back to back, the one facing the ray. Then the smaller surface: one lying on another
/// (a rug on a floor, a canvas on its frame on a wall) is seen on it, whatever the order of the
/// list. Other ties go to the nearer hit, then to the surface listed first.
std::optional<SurfaceHit> intersect_scene(const Scene& scene, const Vec3& o, const Vec3& d);
class SurfaceBvh;
/// The same through the scene's surface hierarchy (render/surface_bvh.h): the same hit.
std::optional<SurfaceHit> intersect_scene(const Scene& scene, const SurfaceBvh& bvh, const Vec3& o, const Vec3& d);

struct RenderOptions {
  int width = 640, height = 480;
  int samples_per_axis = 3;  ///< stratified rays per pixel: samples_per_axis^2, >= 1
  /// render(): tiles of tile_size x tile_size pixels (those at the right and bottom edges
  /// smaller); 0: the largest square tile of at most kRenderTileRays rays.
  int tile_size = 0;
  Rgb background_w_m2 = Rgb::Zero();
};

/// Rays traced and shaded at a time by render() with automatic tiles: a tile holds at most about
/// 120 bytes a ray (the hit's side and point 40 while traced, 20 kept; its radiosity 24; the
/// batch's values 24), 8 MB,
/// whatever the image size and rays per pixel (64 x 64 pixels at 16 rays, 16 x 16 at 256).
inline constexpr size_t kRenderTileRays = size_t{1} << 16;

/// The side of render()'s square tiles, pixels: options.tile_size, or the automatic one.
int tile_side(const RenderOptions& options);

/// Bytes render() holds for an image of these options: the linear image (24 a pixel), the mask
/// of reflecting pixels (1 a pixel) and one tile's rays; callers add what they write with.
size_t render_memory_bytes(const RenderOptions& options);

/// The pixels [x_begin, x_end) x [y_begin, y_end) of an image, x right, y down.
struct PixelRect {
  int x_begin = 0, y_begin = 0, x_end = 0, y_end = 0;
  size_t pixels() const { return static_cast<size_t>(x_end - x_begin) * static_cast<size_t>(y_end - y_begin); }
};

/// The reconstruction of one surface side: radiosity in W/m^2 (3 channels) at points given in
/// the side's metric coordinates (s, t) = (u * length_u, v * length_v); null for a side the
/// solution does not have (drawn black).
using SideReconstruction = std::function<const Interpolant*(SideRef side)>;

/// The primary rays of a camera (all its pixels, or a rectangle of them) and what they hit, side
/// by side: computed once, shaded for any solution and method (the views of a figure share
/// them), each side's points in one batch for its reconstruction.
struct CameraHits {
  RenderOptions options;
  PixelRect pixels;  ///< the pixels traced
  size_t rays = 0;   ///< pixels row by row, samples_per_axis^2 rays each
  /// The rays that met one side (the nearest hit), in increasing order, and where: the side's
  /// metric coordinates (s, t) (SurfaceFrame), what its reconstruction is evaluated at.
  struct SideRays {
    size_t slot;  ///< the side's SideRef::slot()
    std::vector<std::uint32_t> rays;
    std::vector<Vec2> st;
  };
  std::vector<SideRays> sides;  ///< the sides met, by increasing slot; rays in none of them met nothing
};
CameraHits trace_camera(const Scene& scene, const Camera& camera, const RenderOptions& options);
CameraHits trace_camera(const Scene& scene, const Camera& camera, const RenderOptions& options, const PixelRect& pixels);
/// Bands of rows traced one by one (trace_camera() of rectangles as wide as the image, each
/// beginning where the one before it ends) as one trace of the rows they cover: the same as
/// trace_camera() over those rows. The bands' hits are moved from.
CameraHits join_bands(std::vector<CameraHits>& bands);

/// A rendered picture: the linear radiosity, and which pixels see only reflecting surfaces (the
/// pixels a default white point is taken from: exposure.h).
struct Rendering {
  Image image;  ///< linear radiosity, W/m^2 per channel
  /// Per pixel, row by row: 1 when every ray of the pixel met a side that does not emit and has a
  /// reconstruction (not the background, a light, or a side drawn black), else 0.
  std::vector<std::uint8_t> reflecting;
  /// Rays that met a side at a point where its reconstruction has no value (NaN: outside=none,
  /// beyond a radius, cut off by barriers, in an excluded region), drawn black; and all rays
  /// traced.
  std::size_t rays_without_value = 0, rays = 0;
};

/// Linear radiosity (W/m^2 per channel) of every pixel of `hits` (all of the image): the mean
/// over its rays.
Image shade(const Scene& scene, const CameraHits& hits, const SideReconstruction& reconstruction);
/// The same for the pixels that `hits` covers, written into `out` (of the camera's size).
void shade(const Scene& scene, const CameraHits& hits, const SideReconstruction& reconstruction, Rendering& out);

/// Called after each tile with the fraction of the pixels done, in (0, 1].
using RenderProgress = std::function<void(double fraction_done)>;

/// trace_camera() then shade(), tile by tile (row by row of tiles).
Rendering render(const Scene& scene, const Camera& camera, const SideReconstruction& reconstruction,
                 const RenderOptions& options, const RenderProgress& progress = {});

/// A primary ray through the image position (x, y) in pixels (x right, y down; pixel centres at
/// half-integers): origin and unit direction.
std::pair<Vec3, Vec3> camera_ray(const Camera& camera, int width, int height, double x, double y);

}  // namespace radrecon
