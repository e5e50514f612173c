#include "solver/link_form_factor.h"

#include <algorithm>
#include <limits>

#include "solver/visibility.h"

namespace radrecon {

namespace {

LinkFormFactor sample_link(const LinkEnd& receiver, const LinkEnd& source, const std::vector<const Occluder*>& occluders,
                           int n) {
  const QuadNode& r = receiver.node;
  const QuadNode& s = source.node;
  ConvexPolygon polygon;
  for (int k = 0; k < s.vertex_count(); ++k) polygon.push(s.corners[k]);
  LinkFormFactor out;
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  r.for_each_midpoint(n, [&](const Vec2& uv) {
    const Vec3 p = receiver.surface->point(uv.x(), uv.y());
    const double f = visible_form_factor(p, receiver.normal, polygon, source.normal, occluders);
    out.f += f;
    lo = std::min(lo, f);
    hi = std::max(hi, f);
  });
  out.f /= n * n;
  out.f_spread = hi - lo;
  return out;
}

}  // namespace

LinkFormFactor measure_link(const LinkEnd& receiver, const LinkEnd& source, const OccluderBvh& bvh,
                            bool may_be_occluded) {
  const QuadNode& r = receiver.node;
  const QuadNode& s = source.node;
  // The occluders in the shaft between the two nodes (solver/bvh.h).
  std::vector<const Occluder*> occluders;
  if (may_be_occluded)
    bvh.collect(Shaft(std::span<const Vec3>(r.corners.data(), static_cast<size_t>(r.vertex_count())),
                      std::span<const Vec3>(s.corners.data(), static_cast<size_t>(s.vertex_count()))),
                receiver.scene_surface, source.scene_surface, occluders);
  LinkFormFactor link = sample_link(receiver, source, occluders, kLinkQuadrature);
  // A discontinuity makes the coarse rule's error of order 1 / kLinkQuadrature of the jump.
  if (link.f_spread > kDiscontinuousSpread * (link.f + link.f_spread))
    link = sample_link(receiver, source, occluders, kLinkQuadratureFine);
  return link;
}

}  // namespace radrecon
