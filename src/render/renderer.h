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

/// (u,v) of a point on the plane of a planar convex quad (the inverse of Surface::point);
/// nullopt if the point lies outside the quad.
std::optional<Vec2> quad_parameters(const Surface& surface, const Vec3& p);

struct RenderOptions {
  int width = 640, height = 480;
  int samples_per_axis = 3;  ///< stratified rays per pixel: samples_per_axis^2, >= 1
  Rgb background_w_m2 = Rgb::Zero();
};

/// The reconstruction of one surface side: radiosity in W/m^2 (3 channels) at points given in
/// the side's metric coordinates (s, t) = (u * length_u, v * length_v); null for a side the
/// solution does not have (drawn black).
using SideReconstruction = std::function<const Interpolant*(size_t surface, bool back_side)>;

/// The primary rays of a camera and what they hit: computed once, shaded for any solution and
/// method (the views of a figure share them).
struct CameraHits {
  RenderOptions options;
  std::vector<std::optional<SurfaceHit>> hits;  ///< per ray: pixel-major, samples_per_axis^2 each
};
CameraHits trace_camera(const Scene& scene, const Camera& camera, const RenderOptions& options);

/// Linear radiosity (W/m^2 per channel) of every pixel: the mean over its rays.
Image shade(const Scene& scene, const CameraHits& hits, const SideReconstruction& reconstruction);

/// trace_camera() then shade().
Image render(const Scene& scene, const Camera& camera, const SideReconstruction& reconstruction,
             const RenderOptions& options);

/// A primary ray through the image position (x, y) in pixels (x right, y down; pixel centres at
/// half-integers): origin and unit direction.
std::pair<Vec3, Vec3> camera_ray(const Camera& camera, int width, int height, double x, double y);

}  // namespace radrecon
