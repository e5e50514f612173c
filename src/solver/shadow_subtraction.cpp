#include "solver/shadow_subtraction.h"

#include <cstdint>

#include "solver/form_factor.h"

namespace radrecon {

namespace {

/// Each of subtract()'s five clips adds at most one vertex: a polygon with more vertices than this
/// is cut in two first (subtract_large()).
constexpr int kMaxSubtractVertices = ConvexPolygon::kCapacity - 6;

/// Whether q lies wholly outside one of the half-spaces (to clip()'s tolerance): then it misses
/// their intersection.
bool misses(const ConvexPolygon& q, const std::array<HalfSpace, 5>& volume) {
  for (const HalfSpace& h : volume) {
    const double on_plane = h.on_plane >= 0 ? h.on_plane : tol::kPlaneDistance_m * h.normal.norm();
    bool outside = true;
    for (int i = 0; i < q.n && outside; ++i) outside = h.eval(q.v[i]) <= on_plane;
    if (outside) return true;
  }
  return false;
}

/// Appends the convex pieces of q (at most kMaxSubtractVertices vertices) outside the
/// intersection of the half-spaces to `out`: the part outside each half-space peeled off in turn;
/// what is left inside all five is hidden. For a q that misses() does not pass over.
void peel(const ConvexPolygon& q, const std::array<HalfSpace, 5>& volume, std::vector<ConvexPolygon>& out) {
  std::array<ConvexPolygon, 2> rest;
  ConvexPolygon outside;
  const ConvexPolygon* left = &q;
  for (size_t k = 0; k < volume.size(); ++k) {
    ConvexPolygon& inside = rest[k % 2];
    split(*left, volume[k], inside, outside);
    if (!outside.empty()) out.push_back(outside);
    if (inside.empty()) break;
    left = &inside;
  }
}

/// Appends the convex pieces of q (at most kMaxSubtractVertices vertices) minus the
/// intersection of the half-spaces to `out`.
void subtract(const ConvexPolygon& q, const std::array<HalfSpace, 5>& volume,
              std::vector<ConvexPolygon>& out) {
  // A fragment wholly outside one of the half-spaces (to clip()'s tolerance) misses the shadow:
  // keep it whole rather than cut it along the planes before that one (fewer, larger fragments;
  // the same visible polygon).
  if (misses(q, volume)) {
    out.push_back(q);
    return;
  }
  peel(q, volume, out);
}

/// A convex polygon cut in two convex halves along a diagonal (form factors and areas add up
/// over the halves).
void halve(const ConvexPolygon& q, ConvexPolygon& a, ConvexPolygon& b) {
  const int m = q.n / 2;
  for (int i = 0; i <= m; ++i) a.push(q.v[i]);
  for (int i = m; i < q.n; ++i) b.push(q.v[i]);
  b.push(q.v[0]);
}

/// subtract() for a polygon of any size: one with too many vertices is cut into two convex halves
/// along a diagonal first (form factors add up over the pieces), so the fragments of any number of
/// overlapping shadows fit in a ConvexPolygon and the result stays exact. Rare: kept out of line.
[[gnu::noinline]] void subtract_large(const ConvexPolygon& q, const std::array<HalfSpace, 5>& volume,
                                      std::vector<ConvexPolygon>& out) {
  if (q.n <= kMaxSubtractVertices) {
    subtract(q, volume, out);
    return;
  }
  ConvexPolygon a, b;
  halve(q, a, b);
  subtract_large(a, volume, out);
  subtract_large(b, volume, out);
}

}  // namespace

/// Whether the shadow volume can hide any point of `polygon`: some vertex of it lies inside each
/// of the volume's half-spaces (else the polygon lies wholly outside one of them).
bool meets(const ShadowVolume& volume, const ConvexPolygon& polygon) {
  if (volume.sides == 0) return false;  // the point lies in the occluder's plane
  for (int h = 0; h <= volume.sides; ++h) {
    bool any_inside = false;
    for (int i = 0; i < polygon.n && !any_inside; ++i) any_inside = volume.planes[h].eval(polygon.v[i]) > 0;
    if (!any_inside) return false;
  }
  return true;
}

/// The convex fragments of `front` (a polygon in front of the point) that the point sees past
/// `shadows` (the volumes that meet it; sorted here) into `fragments`. Nearest occluders first:
/// their shadows are the largest seen from the point, so the fragments shrink (or vanish, ending
/// the loop) early and later shadows cut fewer of them. With `plane` (the polygon's plane seen from
/// the point: for many shadows, a light seen past hundreds of a model's small triangles) each
/// shadow's trace on the plane lies within its occluder's projection, so a fragment whose
/// projection's box misses that one's misses the shadow, and is kept whole without subtract()'s
/// plane tests; the fragments' boxes are then left in `boxes`. With a few shadows there are few
/// fragments, and the boxes would cost more than they save.
void subtract_shadows(std::vector<Shadow>& shadows, const ConvexPolygon& front, const PlaneBasis* plane,
                      std::vector<ConvexPolygon>& fragments, std::vector<Box2>& boxes) {
  std::stable_sort(shadows.begin(), shadows.end(),
                   [](const Shadow& x, const Shadow& y) { return x.distance_m2 < y.distance_m2; });
  thread_local std::vector<ConvexPolygon> pieces;
  const auto subtract_one = [&](const ConvexPolygon& q, const Shadow& shadow) {
    pieces.clear();
    if (q.n <= kMaxSubtractVertices) subtract(q, shadow.volume->planes, pieces);
    else subtract_large(q, shadow.volume->planes, pieces);
  };
  fragments.clear();
  boxes.clear();
  if (plane == nullptr) {
    // Shadow by shadow over the fragments left. A fragment the shadow misses stays where it is;
    // one it cuts is replaced by its first piece, and its other pieces go to the end, past the
    // fragments still to cut.
    fragments.push_back(front);
    for (const Shadow& shadow : shadows) {
      const size_t count = fragments.size();
      size_t kept = 0;  // fragments [0, kept) survive; the rest of [0, f) are gone
      for (size_t f = 0; f < count; ++f) {
        subtract_one(fragments[f], shadow);
        if (pieces.empty()) continue;
        fragments[kept++] = pieces[0];
        for (size_t i = 1; i < pieces.size(); ++i) fragments.push_back(pieces[i]);
      }
      // Close the gap between the survivors and the pieces appended after them.
      fragments.erase(fragments.begin() + static_cast<std::ptrdiff_t>(kept),
                      fragments.begin() + static_cast<std::ptrdiff_t>(count));
      if (fragments.empty()) return;
    }
    return;
  }
  // With boxes: fragment by fragment, depth first, each with the shadows after the one that made
  // it whose traces its box meets (listed again for each new piece: a piece is smaller than the
  // fragment it came from, and meets fewer traces). Each fragment meets the shadows in the same
  // order as above: the same visible polygon, in fragments listed in another order (and a
  // fragment of many vertices that a shadow misses is kept whole rather than halved).
  thread_local std::vector<Box2> traces;
  traces.clear();
  for (const Shadow& shadow : shadows) traces.push_back(plane->trace(*shadow.volume->occluder));
  struct Work {
    ConvexPolygon fragment;
    Box2 box;
    size_t first, last;  ///< its shadows: candidates[first, last), indices into `shadows`
  };
  thread_local std::vector<std::uint32_t> candidates;
  thread_local std::vector<Work> stack;
  candidates.clear();
  stack.clear();
  const auto push = [&](const ConvexPolygon& fragment, const Box2& box, size_t from, size_t to) {
    const size_t first = candidates.size();
    for (size_t i = from; i < to; ++i)
      if (box.meets(traces[candidates[i]])) candidates.push_back(candidates[i]);
    stack.push_back({fragment, box, first, candidates.size()});
  };
  for (size_t k = 0; k < shadows.size(); ++k) candidates.push_back(static_cast<std::uint32_t>(k));
  push(front, plane->box(front), 0, shadows.size());
  while (!stack.empty()) {
    const Work work = stack.back();
    stack.pop_back();
    // What later-pushed (so already finished) work listed after this one's candidates is spent.
    candidates.resize(work.last);
    size_t i = work.first;
    while (i < work.last && misses(work.fragment, shadows[candidates[i]].volume->planes)) ++i;
    if (i == work.last) {  // past every shadow
      fragments.push_back(work.fragment);
      boxes.push_back(work.box);
      continue;
    }
    // (misses() has just passed it over: peel it without asking again.)
    pieces.clear();
    if (work.fragment.n <= kMaxSubtractVertices) peel(work.fragment, shadows[candidates[i]].volume->planes, pieces);
    else subtract_large(work.fragment, shadows[candidates[i]].volume->planes, pieces);
    for (const ConvexPolygon& piece : pieces) push(piece, plane->box(piece), i + 1, work.last);
  }
}

namespace {

/// Sums over the pieces of polygons inside a cone: their Lambert form factors and areas.
struct InCone {
  double form_factor = 0, area_m2 = 0;
  bool any = false;  ///< some piece was not empty
};

/// Adds q's part inside every half-space of `cone` to `sums`, its form factor as seen from p
/// (unit normal n). A part that would outgrow a ConvexPolygon (each clip adds at most one vertex)
/// is cut in two along a diagonal first: form factors and areas add up over the pieces.
void add_in_cone(ConvexPolygon q, std::span<const HalfSpace> cone, const Vec3& p, const Vec3& n, InCone& sums) {
  for (size_t i = 0; i < cone.size(); ++i) {
    if (q.n >= ConvexPolygon::kCapacity) {
      ConvexPolygon a, b;
      halve(q, a, b);
      add_in_cone(a, cone.subspan(i), p, n, sums);
      add_in_cone(b, cone.subspan(i), p, n, sums);
      return;
    }
    q = clip(q, cone[i]);
    if (q.empty()) return;
  }
  sums.any = true;
  sums.form_factor += lambert_form_factor(p, n, q);
  sums.area_m2 += area_m2(q);
}

}  // namespace

bool VisibleFragments::find(const Vec3& p, const Vec3& n, const ConvexPolygon& polygon, const Vec3& polygon_normal,
                            std::span<const ShadowVolume> volumes) {
  p_ = p, n_ = n, polygon_normal_ = polygon_normal;
  fragments_.clear();
  boxes_.clear();
  behind_ = polygon.empty() || polygon_normal.dot(p - polygon.v[0]) <= tol::kPlaneDistance_m;
  if (!behind_) front_ = clip_to_horizon(p, n, polygon);
  behind_ = behind_ || front_.empty();
  if (behind_) return true;  // every part gives 0
  thread_local std::vector<Shadow> shadows;
  shadows.clear();
  for (const ShadowVolume& v : volumes)
    if (meets(v, front_)) shadows.push_back({(v.occluder->centroid - p).squaredNorm(), &v});
  if (shadows.size() < tol::kKeptFragmentsShadows) return false;
  plane_ = PlaneBasis(p, polygon_normal, polygon_normal.dot(polygon.v[0]));
  subtract_shadows(shadows, front_, &plane_, fragments_, boxes_);
  return true;
}

double VisibleFragments::form_factor(const ConvexPolygon& part, bool* partly_seen) const {
  bool partly_unused = false;
  bool& partly = partly_seen != nullptr ? *partly_seen : partly_unused;
  partly = false;
  if (behind_ || part.empty() || polygon_normal_.dot(p_ - part.v[0]) <= tol::kPlaneDistance_m) return 0.0;
  const ConvexPolygon front = clip_to_horizon(p_, n_, part);
  if (front.empty()) return 0.0;
  // The part's cone from p: the half-spaces through p and each edge of the part (not of its
  // front: the fragments lie in front of p already, and a short edge that the horizon cut off a
  // corner would tilt its plane), the part's middle inside.
  Vec3 middle = Vec3::Zero();
  for (int i = 0; i < part.n; ++i) middle += part.v[i] / part.n;
  std::array<HalfSpace, ConvexPolygon::kCapacity> cone;
  for (int i = 0; i < part.n; ++i) {
    Vec3 m = (part.v[i] - p_).cross(part.v[(i + 1) % part.n] - p_);
    if (m.dot(middle - p_) < 0) m = -m;
    cone[static_cast<size_t>(i)] = HalfSpace{m, m.dot(p_)}.with_tolerance();
  }
  const std::span<const HalfSpace> sides(cone.data(), static_cast<size_t>(part.n));
  const Box2 box = plane_.box(front);
  InCone seen;
  for (size_t f = 0; f < fragments_.size(); ++f)
    if (boxes_[f].meets(box)) add_in_cone(fragments_[f], sides, p_, n_, seen);
  if (!seen.any) return 0.0;  // all of it hidden
  for (int i = 0; i < part.n && !partly; ++i) partly = n_.dot(part.v[i] - p_) < 0;
  // Else compare what the fragments show of the part with its front, both in the polygon's plane,
  // up to the slack of clip()'s snapping along the part's outline (tol::kHiddenAreaRelative).
  if (!partly) {
    InCone whole;
    add_in_cone(front_, sides, p_, n_, whole);
    double outline_m = 0;
    for (int i = 0; i < front.n; ++i) outline_m += (front.v[(i + 1) % front.n] - front.v[i]).norm();
    const double slack_m2 = tol::kHiddenAreaRelative * whole.area_m2 + tol::kPlaneDistance_m * outline_m;
    partly = seen.area_m2 < whole.area_m2 - slack_m2;
  }
  return seen.form_factor;
}

}  // namespace radrecon
