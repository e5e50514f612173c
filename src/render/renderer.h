#pragma once
// A ray-casting renderer for radiosity solutions: for each pixel, several stratified rays from a
// pinhole camera find the visible surface side and its (u,v); the side's reconstruction gives
// the radiosity there (W/m^2), averaged over the pixel's rays. Radiosity is evaluated in one
// batch per surface side, not per ray.

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

/// The nearest surface hit by the ray o + t d (d of unit length), t > 0, if any.
std::optional<SurfaceHit> intersect_scene(const Scene& scene, const Vec3& o, const Vec3& d);

struct RenderOptions {
  int width = 640, height = 480;
  int samples_per_axis = 3;  ///< stratified rays per pixel: samples_per_axis^2, >= 1
  Rgb background_w_m2 = Rgb::Zero();
};

/// The reconstruction of one surface side: radiosity in W/m^2 (3 channels) at points given in
/// the side's metric coordinates (s, t) = (u * length_u, v * length_v); null for a side the
/// solution does not have (drawn black).
using SideReconstruction = std::function<const Interpolant*(SideRef side)>;

/// The primary rays of a camera (all its rows, or a band of rows) and what they hit: computed
/// once, shaded for any solution and method (the views of a figure share them).
struct CameraHits {
  RenderOptions options;
  int row_begin = 0, row_end = 0;               ///< the image rows [row_begin, row_end) traced
  std::vector<std::optional<SurfaceHit>> hits;  ///< per ray: pixel-major, samples_per_axis^2 each
};
CameraHits trace_camera(const Scene& scene, const Camera& camera, const RenderOptions& options);
CameraHits trace_camera(const Scene& scene, const Camera& camera, const RenderOptions& options, int row_begin,
                        int row_end);

/// Linear radiosity (W/m^2 per channel) of every pixel of `hits` (all rows): the mean over its
/// rays.
Image shade(const Scene& scene, const CameraHits& hits, const SideReconstruction& reconstruction);
/// The same for the rows that `hits` covers, written into `image` (of the camera's size).
void shade(const Scene& scene, const CameraHits& hits, const SideReconstruction& reconstruction, Image& image);

/// Rays traced and shaded at a time by render(): memory stays at the image plus about 120 bytes
/// a ray of one band (the hit 48, its radiosity 24, the batch's point, value and index 48; ~125
/// MB), whatever the image size and rays per pixel.
inline constexpr size_t kRenderBandRays = size_t{1} << 20;

/// Called after each band with the fraction of rows done, in (0, 1].
using RenderProgress = std::function<void(double fraction_done)>;

/// trace_camera() then shade(), band by band of rows.
Image render(const Scene& scene, const Camera& camera, const SideReconstruction& reconstruction,
             const RenderOptions& options, const RenderProgress& progress = {});

/// A primary ray through the image position (x, y) in pixels (x right, y down; pixel centres at
/// half-integers): origin and unit direction.
std::pair<Vec3, Vec3> camera_ray(const Camera& camera, int width, int height, double x, double y);

}  // namespace radrecon
