// The parts of a side that surfaces standing on it enclose (solver/enclosed.h).

#include "solver/enclosed.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <span>

#include "core/tolerances.h"
#include "scene/side.h"

namespace radrecon {

namespace {

/// An axis-aligned box in (s, t): low and high corners.
struct StBox {
  Vec2 lo, hi;
  StBox(const Vec2& low, const Vec2& high) : lo(low), hi(high) {}
  explicit StBox(const std::vector<Vec2>& points) : lo(points[0]), hi(points[0]) {
    for (const Vec2& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  bool overlaps(const StBox& o) const { return (lo.array() < o.hi.array()).all() && (o.lo.array() < hi.array()).all(); }
};


}  // namespace

double overlap_area(const Polyline& region, const std::vector<Vec2>& convex) {
  // Sutherland-Hodgman: the region clipped by each edge's inner half-plane in turn. A non-convex
  // region may come out with edges doubling back along the clip lines, which add no area.
  std::vector<Vec2> out(region.begin(), region.end()), in;
  for (size_t i = 0, j = convex.size() - 1; i < convex.size() && !out.empty(); j = i++) {
    const Vec2 a = convex[j], edge = convex[i] - convex[j];
    const auto side = [&](const Vec2& p) { return cross(edge, p - a); };  // >= 0: inside
    in.swap(out);
    out.clear();
    for (size_t k = 0, l = in.size() - 1; k < in.size(); l = k++) {
      const Vec2 &p = in[l], &q = in[k];
      const double sp = side(p), sq = side(q);
      if (sq >= 0) {
        if (sp < 0) out.push_back(p + (q - p) * (sp / (sp - sq)));
        out.push_back(q);
      } else if (sp >= 0) {
        out.push_back(p + (q - p) * (sp / (sp - sq)));
      }
    }
  }
  return out.size() < 3 ? 0.0 : std::abs(0.5 * twice_signed_area(out));
}

EnclosedRegions::EnclosedRegions(const SideContactSet& set, const SurfaceFrame& frame) : frame_(frame) {
  const auto first = set.excluded.begin() + static_cast<std::ptrdiff_t>(set.covered);
  const auto last = set.excluded.end() - static_cast<std::ptrdiff_t>(set.faced);
  if (first < last) regions_.assign(first, last);
  for (const Polyline& r : regions_) {
    const StBox box(r);
    boxes_.push_back({box.lo, box.hi});
  }
}

double EnclosedRegions::exposed_fraction(const ParamCell& cell) const {
  if (regions_.empty()) return 1;
  std::vector<Vec2> polygon;  // the cell in (s, t), counter-clockwise (the frame keeps orientation)
  const auto uv = cell.vertices();
  for (int k = 0; k < cell.vertex_count(); ++k) polygon.push_back(frame_.st(uv[static_cast<size_t>(k)]));
  const StBox box(polygon);
  double covered = 0;
  for (size_t r = 0; r < regions_.size(); ++r)
    if (StBox{boxes_[r].lo, boxes_[r].hi}.overlaps(box)) covered += overlap_area(regions_[r], polygon);
  const double area = 0.5 * twice_signed_area(polygon);
  // An element that only touches a region's outline overlaps it by rounding (3e-17 m^2): it is
  // whole (it moved its gathering point, and its radiosity was 2.6% off its mirror image's; a
  // review).
  if (covered <= tol::kEnclosedOverlapRelative * area) return 1;
  const double exposed = 1 - covered / area;
  return exposed <= tol::kEnclosedOverlapRelative ? 0.0 : std::min(exposed, 1.0);  // wholly inside, to rounding: 0
}

bool EnclosedRegions::encloses(const Vec2& uv) const {
  const Vec2 st = frame_.st(uv);
  return std::any_of(regions_.begin(), regions_.end(), [&](const Polyline& r) { return in_region(r, st); });
}

std::vector<EnclosedElement> enclosed_elements(const Scene& scene, const Mesh& mesh, const ContactFinder& contacts) {
  std::vector<SideContactSet> by_side;
  for (const MeshSurface& side : mesh.surfaces) by_side.push_back(contacts.at(SideRef{side.scene_surface, side.back_side}));
  return enclosed_elements(scene, mesh, by_side);
}

std::vector<EnclosedElement> enclosed_elements(const Scene& scene, const Mesh& mesh,
                                               std::span<const SideContactSet> contacts_by_side) {
  std::vector<EnclosedElement> out;
  for (size_t s = 0; s < mesh.surfaces.size(); ++s) {
    const MeshSurface& side = mesh.surfaces[s];
    const EnclosedRegions regions(contacts_by_side[s], scene.surfaces[side.scene_surface].frame());
    if (regions.empty()) continue;
    for (size_t e = 0; e < side.elements.size(); ++e) {
      const MeshElement& element = side.elements[e];
      EnclosedElement found{s, e, regions.exposed_fraction(element), {}};
      if (found.exposed >= 1) continue;
      element.for_each_midpoint(kEnclosedSubdivision, [&](const Vec2& p) {
        if (!regions.encloses(p)) found.exposed_uv.push_back(p);
      });
      if (found.exposed_uv.size() == static_cast<size_t>(kEnclosedSubdivision * kEnclosedSubdivision)) found.exposed_uv.clear();
      out.push_back(std::move(found));
    }
  }
  return out;
}

void move_to_exposed_part(const Surface& surface, const std::vector<Vec2>& exposed_uv, Receiver& r) {
  // The point of a group nearest its mean: a point of the exposed part standing for the group.
  const auto nearest_to_mean = [](std::span<const Vec2> group) {
    Vec2 mean = Vec2::Zero();
    for (const Vec2& p : group) mean += p;
    mean /= static_cast<double>(group.size());
    return *std::min_element(group.begin(), group.end(), [&](const Vec2& a, const Vec2& b) {
      return (a - mean).squaredNorm() < (b - mean).squaredNorm();
    });
  };
  const Vec2 centre = nearest_to_mean(exposed_uv);
  r.center = surface.point(centre.x(), centre.y());
  // Four groups of equal count (equal area: the subdivision's cells are), halved along u and each
  // half along v, a point for each: equal weights, as the Gauss rule's.
  std::vector<Vec2> points = exposed_uv;
  const size_t n = points.size();
  if (n < r.gauss.size()) {
    for (size_t k = 0; k < n; ++k) r.gauss[k] = surface.point(points[k].x(), points[k].y());
    r.gauss_count = static_cast<int>(n);
    return;
  }
  const auto by = [](int axis) { return [axis](const Vec2& a, const Vec2& b) { return a[axis] < b[axis]; }; };
  std::sort(points.begin(), points.end(), by(0));
  const size_t half = n / 2;
  std::sort(points.begin(), points.begin() + static_cast<std::ptrdiff_t>(half), by(1));
  std::sort(points.begin() + static_cast<std::ptrdiff_t>(half), points.end(), by(1));
  const std::array<size_t, 5> cut = {0, half / 2, half, half + (n - half) / 2, n};
  for (size_t k = 0; k < 4; ++k) {
    const Vec2 p = nearest_to_mean(std::span<const Vec2>(points).subspan(cut[k], cut[k + 1] - cut[k]));
    r.gauss[k] = surface.point(p.x(), p.y());
  }
  r.gauss_count = 4;
}

}  // namespace radrecon
