#include "solver/bvh.h"

#include <algorithm>
#include <cmath>

#include "core/check.h"
#include "core/tolerances.h"

namespace radrecon {

Shaft::Shaft(std::span<const Vec3> a, std::span<const Vec3> b, double margin_m)
    : reach_m_(std::max(margin_m, 0.0)) {
  RR_CHECK(!a.empty() && !b.empty() && a.size() + b.size() <= static_cast<size_t>(kMaxPoints),
           "shaft: 1 to 16 points in all, at least one on each side");
  // A triangle given as a quad repeats its last corner: keep each point once.
  const auto add_point = [&](const Vec3& p) {
    bool seen = false;
    for (int k = 0; k < point_count_ && !seen; ++k) seen = points_[k] == p;
    if (!seen) points_[point_count_++] = p;
  };
  for (const Vec3& p : a) add_point(p);
  a_count_ = point_count_;
  for (const Vec3& p : b) add_point(p);
  lo_ = hi_ = points_[0];
  for (int k = 1; k < point_count_; ++k) {
    lo_ = lo_.cwiseMin(points_[k]);
    hi_ = hi_.cwiseMax(points_[k]);
  }
  for (int axis = 0; axis < 3; ++axis) {
    add_plane(Vec3::Unit(axis));
    add_plane(-Vec3::Unit(axis));
  }
  const double extent = std::max((hi_ - lo_).maxCoeff(), 1e-300);
  if (a.size() == 1 && point_count_ >= 4 && point_count_ <= 5) {
    // A point and a convex polygon (in order): the pyramid's sides and the polygon's plane,
    // each turned away from the pyramid's centroid.
    Vec3 mid = Vec3::Zero();
    for (int k = 0; k < point_count_; ++k) mid += points_[k] / point_count_;
    const int m = point_count_ - 1;
    auto face = [&](const Vec3& x, const Vec3& y, const Vec3& z) {
      Vec3 n = (y - x).cross(z - x);
      const double norm = n.norm();
      if (!(norm > 1e-12 * extent * extent)) return;
      n /= norm;
      add_plane(n.dot(mid - x) > 0 ? Vec3(-n) : n);
    };
    for (int k = 0; k < m; ++k) face(points_[0], points_[1 + k], points_[1 + (k + 1) % m]);
    face(points_[1], points_[2], points_[3]);
    return;
  }
  // The hull's faces: the planes through three of the points with all the others on one side.
  // (Any direction would do, since add_plane() puts the offset at the farthest point; these are
  // the ones that cut the box's corners off.)
  const double on_side = 1e-9 * extent;
  for (int i = 0; i < point_count_; ++i)
    for (int j = i + 1; j < point_count_; ++j)
      for (int k = j + 1; k < point_count_; ++k) {
        Vec3 m = (points_[j] - points_[i]).cross(points_[k] - points_[i]);
        const double norm = m.norm();
        if (!(norm > 1e-12 * extent * extent)) continue;  // (nearly) collinear
        m /= norm;
        double lo = 0, hi = 0;
        for (int q = 0; q < point_count_; ++q) {
          const double d = m.dot(points_[q] - points_[i]);
          lo = std::min(lo, d);
          hi = std::max(hi, d);
        }
        if (hi <= on_side) add_plane(m);
        if (lo >= -on_side) add_plane(-m);
      }
}

void Shaft::add_plane(const Vec3& unit_normal) {
  for (int k = 0; k < plane_count_; ++k)
    if (normal_[k].dot(unit_normal) > 1 - 1e-12) return;  // that face already
  if (plane_count_ == kMaxPlanes) return;  // fewer planes: a weaker but still valid cull
  double offset = unit_normal.dot(points_[0]);
  for (int q = 1; q < point_count_; ++q) offset = std::max(offset, unit_normal.dot(points_[q]));
  normal_[plane_count_] = unit_normal;
  offset_[plane_count_] = offset + margin_m();
  ++plane_count_;
}

bool Shaft::may_meet_box(const Vec3& lo, const Vec3& hi) const {
  // The box's bounding-box test first (the first six planes), then its nearest corner to each face.
  if ((lo.array() > hi_.array() + margin_m()).any() || (hi.array() < lo_.array() - margin_m()).any())
    return false;
  for (int k = 6; k < plane_count_; ++k) {
    const Vec3& m = normal_[k];
    const double nearest = (m.x() > 0 ? m.x() * lo.x() : m.x() * hi.x()) +
                           (m.y() > 0 ? m.y() * lo.y() : m.y() * hi.y()) +
                           (m.z() > 0 ? m.z() * lo.z() : m.z() * hi.z());
    if (nearest > offset_[k]) return false;
  }
  return true;
}

bool Shaft::may_meet(const Occluder& o) const {
  if (!may_meet_box(o.bbox_min, o.bbox_max)) return false;
  for (int k = 6; k < plane_count_; ++k) {
    bool all_outside = true;
    for (int c = 0; c < o.corner_count && all_outside; ++c) all_outside = normal_[k].dot(o.corners[c]) > offset_[k];
    if (all_outside) return false;
  }
  // The occluder's own plane: when both ends (the first widened by its margin) lie on one closed
  // side of it, a segment between them meets the plane at an end or runs in it, and the
  // occluder shades nothing. Closed to tol::kPlaneDistance_m, the clipping's own tolerance: a
  // point that near the plane sees no shadow of it, and a polygon that reaches no farther
  // beyond it is not shaded by it (visibility.cpp). So the walls that meet a shooter at its
  // edges, or a light set into the ceiling, are no occluders.
  bool front = true, back = true;
  for (int q = 0; q < point_count_; ++q) {
    const double d = o.plane.eval(points_[q]);
    const double reach_m = q < a_count_ ? reach_m_ : 0.0;
    front = front && d - reach_m >= -tol::kPlaneDistance_m;
    back = back && d + reach_m <= tol::kPlaneDistance_m;
  }
  return !(front || back);
}

OccluderBvh::OccluderBvh(const std::vector<Occluder>& occluders) {
  std::vector<BoxItem> items;
  items.reserve(occluders.size());
  for (const Occluder& o : occluders) items.push_back({o.bbox_min, o.bbox_max, o.centroid});
  std::vector<int> order;
  build_box_hierarchy(items, kLeafSize, nodes_, order);
  order_.reserve(order.size());
  for (const int k : order) order_.push_back(&occluders[static_cast<size_t>(k)]);
}

void OccluderBvh::collect(const Shaft& shaft, size_t skip_a, size_t skip_b,
                          std::vector<const Occluder*>& out) const {
  if (nodes_.empty()) return;
  std::array<int, 64> stack;  // depth <= log2(occluders) + 1 for a median split
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const BoxNode& node = nodes_[static_cast<size_t>(stack[--top])];
    if (!shaft.may_meet_box(node.lo, node.hi)) continue;
    if (node.count > 0) {
      for (int k = node.first; k < node.first + node.count; ++k) {
        const Occluder* o = order_[static_cast<size_t>(k)];
        if (o->scene_surface == skip_a || o->scene_surface == skip_b) continue;
        if (shaft.may_meet(*o)) out.push_back(o);
      }
    } else {
      stack[top++] = node.first + 1;
      stack[top++] = node.first;
    }
  }
}

namespace {

/// Whether the segment from p to q crosses the occluder's polygon farther than `ignore_m` from q.
bool crosses(const Occluder& o, const Vec3& p, const Vec3& q, double ignore_m) {
  const double ep = o.plane.eval(p), eq = o.plane.eval(q);
  if (!((ep > tol::kPlaneDistance_m && eq < -tol::kPlaneDistance_m) ||
        (ep < -tol::kPlaneDistance_m && eq > tol::kPlaneDistance_m)))
    return false;
  const Vec3 x = p + (ep / (ep - eq)) * (q - p);
  if ((x - q).squaredNorm() < ignore_m * ignore_m) return false;
  // Inside when x lies on one side of every edge (either orientation of the corners), edges
  // included to tol::kPlaneDistance_m: a ray along the edge two triangles share passes through
  // neither by round-off, a crack the exact shadows do not have.
  bool left = true, right = true;
  for (int k = 0; k < o.corner_count; ++k) {
    const Vec3& a = o.corners[static_cast<size_t>(k)];
    const Vec3& b = o.corners[static_cast<size_t>((k + 1) % o.corner_count)];
    const double side = (b - a).cross(x - a).dot(o.plane.normal);  // |b - a| times x's distance
    const double slack = tol::kPlaneDistance_m * (b - a).norm();
    left = left && side >= -slack;
    right = right && side <= slack;
  }
  return left || right;
}

}  // namespace

bool OccluderBvh::blocks_segment(const Vec3& p, const Vec3& q, double ignore_m, size_t skip,
                                 std::span<const std::uint8_t> skip_surfaces) const {
  if (nodes_.empty()) return false;
  const Vec3 inverse = (q - p).cwiseInverse();  // infinite along an axis the segment runs parallel to
  const Vec3 slack = Vec3::Constant(tol::kShaftSlack_m);
  std::array<int, 64> stack;  // as collect()
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const BoxNode& node = nodes_[static_cast<size_t>(stack[--top])];
    if (ray_box_entry(node.lo - slack, node.hi + slack, p, inverse, 1) < 0) continue;
    if (node.count > 0) {
      for (int k = node.first; k < node.first + node.count; ++k) {
        const Occluder* o = order_[static_cast<size_t>(k)];
        if (o->scene_surface == skip || (!skip_surfaces.empty() && skip_surfaces[o->scene_surface] != 0)) continue;
        if (crosses(*o, p, q, ignore_m)) return true;
      }
    } else {
      stack[top++] = node.first + 1;
      stack[top++] = node.first;
    }
  }
  return false;
}

std::vector<const Occluder*> OccluderBvh::between(std::span<const Vec3> a, std::span<const Vec3> b,
                                                  size_t surface_a, size_t surface_b) const {
  std::vector<const Occluder*> out;
  collect(Shaft(a, b), surface_a, surface_b, out);
  return out;
}

}  // namespace radrecon
