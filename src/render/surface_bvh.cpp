#include "render/surface_bvh.h"

#include "core/tolerances.h"

namespace radrecon {

SurfaceBvh::SurfaceBvh(const Scene& scene) {
  const size_t n = scene.surfaces.size();
  if (n == 0) return;
  std::vector<BoxItem> items(n);
  Vec3 scene_lo = scene.surfaces[0].corners[0], scene_hi = scene_lo;
  for (size_t k = 0; k < n; ++k) {
    const Surface& s = scene.surfaces[k];
    // A ray hits the plane through corner 0 (the surface's normal), where Surface::parameters()
    // accepts a point whose projection along the normal's largest axis falls in the corners'
    // projection: inside the hull of the corners lifted onto that plane along that axis. A quad
    // off its plane (within the scene's planarity tolerance) puts those points beside its
    // corners: the box holds both.
    const Vec3 n = s.normal();
    int drop = 0;
    n.cwiseAbs().maxCoeff(&drop);
    Vec3 lo = s.corners[0], hi = s.corners[0];
    for (const Vec3& c : s.corners) {
      Vec3 lifted = c;
      lifted[drop] -= n.dot(c - s.corners[0]) / n[drop];
      lo = lo.cwiseMin(c).cwiseMin(lifted), hi = hi.cwiseMax(c).cwiseMax(lifted);
    }
    items[k] = {lo, hi, 0.5 * (lo + hi)};
    scene_lo = scene_lo.cwiseMin(lo), scene_hi = scene_hi.cwiseMax(hi);
  }
  const double slack_m = tol::kRayBoxSlackRelative * (1.0 + (scene_hi - scene_lo).norm() + scene_lo.norm() + scene_hi.norm());
  for (BoxItem& b : items) b.lo.array() -= slack_m, b.hi.array() += slack_m;
  build_box_hierarchy(items, kLeafSize, nodes_, order_);
}

}  // namespace radrecon
