#include "scene/contacts.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <tuple>
#include <utility>

#include "core/tolerances.h"

namespace radrecon {

namespace {

/// The segment where the convex polygon `corners` meets the plane {x : dot(n, x) = d}, given the
/// signed distances of its corners (snapped to 0 within `touch_m`); false if it does not.
bool plane_section(const std::array<Vec3, 4>& corners, const std::array<double, 4>& dist, Vec3& a, Vec3& b) {
  std::vector<Vec3> points;
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    if (dist[i] == 0) points.push_back(corners[i]);
    if ((dist[i] < 0 && dist[j] > 0) || (dist[i] > 0 && dist[j] < 0)) {
      const double t = dist[i] / (dist[i] - dist[j]);
      points.push_back(corners[i] + t * (corners[j] - corners[i]));
    }
  }
  if (points.size() < 2) return false;
  // A convex polygon meets a plane in a segment: its two most distant points.
  double best = -1;
  for (size_t i = 0; i < points.size(); ++i)
    for (size_t j = i + 1; j < points.size(); ++j)
      if ((points[i] - points[j]).squaredNorm() > best) {
        best = (points[i] - points[j]).squaredNorm();
        a = points[i];
        b = points[j];
      }
  return best > 0;
}

/// Clips the segment [a, b] (in the quad's plane) to the convex quad; false if nothing is left.
bool clip_to_quad(const Surface& quad, Vec3& a, Vec3& b) {
  const Vec3 n = quad.normal();
  double t0 = 0, t1 = 1;
  const Vec3 d = b - a;
  for (int i = 0; i < 4; ++i) {
    const Vec3& c = quad.corners[static_cast<size_t>(i)];
    const Vec3 inward = n.cross(quad.corners[static_cast<size_t>((i + 1) % 4)] - c);  // corners are CCW
    const double fa = inward.dot(a - c), fd = inward.dot(d);
    if (fd == 0) {
      if (fa < 0) return false;
      continue;
    }
    const double t = -fa / fd;
    if (fd > 0) t0 = std::max(t0, t);
    else t1 = std::min(t1, t);
  }
  if (!(t0 < t1)) return false;
  // An end the quad does not cut stays as it is: a0 + 1 * (b - a0) rounds (the paper's wall foot
  // ended at y = 0.6000000000000001 for 0.6, and its corner let a sight line through).
  const Vec3 a0 = a;
  if (t0 > 0) a = a0 + t0 * d;
  if (t1 < 1) b = a0 + t1 * d;
  return true;
}

/// The convex polygon `poly`, projected onto the quad's plane, clipped to the convex quad
/// (Sutherland-Hodgman, one inward half-plane per edge).
std::vector<Vec3> clip_polygon_to_quad(const Surface& quad, std::vector<Vec3> poly) {
  const Vec3 n = quad.normal();
  const double offset = n.dot(quad.corners[0]);
  for (Vec3& p : poly) p -= (n.dot(p) - offset) * n;
  for (int i = 0; i < 4 && !poly.empty(); ++i) {
    const Vec3& c = quad.corners[static_cast<size_t>(i)];
    const Vec3 inward = n.cross(quad.corners[static_cast<size_t>((i + 1) % 4)] - c);
    std::vector<Vec3> kept;
    for (size_t k = 0; k < poly.size(); ++k) {
      const Vec3& p = poly[k];
      const Vec3& q = poly[(k + 1) % poly.size()];
      const double fp = inward.dot(p - c), fq = inward.dot(q - c);
      if (fp >= 0) kept.push_back(p);
      if ((fp > 0 && fq < 0) || (fp < 0 && fq > 0)) kept.push_back(p + (fp / (fp - fq)) * (q - p));
    }
    poly = std::move(kept);
  }
  return poly;
}


bool lexicographically_less(const Vec2& a, const Vec2& b) { return std::tie(a.x(), a.y()) < std::tie(b.x(), b.y()); }

/// The closed polygon `p` as a region: points within `join_m` of their predecessor and vertices
/// within `join_m` of the line through their neighbours dropped, counter-clockwise, starting at
/// its lexicographically smallest vertex; nullopt if fewer than 3 vertices remain or it is no
/// wider than `join_m` (its area at most join_m times its bounding box's diagonal).
std::optional<Polyline> as_region(Polyline p, double join_m) {
  for (bool changed = true; changed && p.size() >= 3;) {
    changed = false;
    for (size_t i = 0; i < p.size() && p.size() >= 3; ++i) {
      const Vec2& prev = p[(i + p.size() - 1) % p.size()];
      const Vec2& next = p[(i + 1) % p.size()];
      const double base = (next - prev).norm();
      // A repeated point, the tip of a spike, or a vertex on the line through its neighbours.
      const bool drop = (p[i] - prev).norm() <= join_m || base <= join_m ||
                        std::abs(cross(next - prev, p[i] - prev)) <= join_m * base;
      if (drop) {
        p.erase(p.begin() + static_cast<std::ptrdiff_t>(i));
        changed = true;
        break;
      }
    }
  }
  if (p.size() < 3) return std::nullopt;
  Vec2 lo = p[0], hi = p[0];
  for (const Vec2& q : p) {
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  const double area2 = twice_signed_area(p);
  if (std::abs(area2) <= 2 * join_m * (hi - lo).norm()) return std::nullopt;
  if (area2 < 0) std::reverse(p.begin(), p.end());
  std::rotate(p.begin(), std::min_element(p.begin(), p.end(), lexicographically_less), p.end());
  return p;
}

/// Whether two regions (as_region()) are the same polygon: as many vertices, each within
/// `join_m` of one of the other's.
bool same_region(const Polyline& a, const Polyline& b, double join_m) {
  if (a.size() != b.size()) return false;
  for (const Vec2& p : a)
    if (std::none_of(b.begin(), b.end(), [&](const Vec2& q) { return (p - q).norm() <= join_m; })) return false;
  return true;
}

/// Which halves of the side, left and right of a contact line's direction a -> b in (s, t), the
/// surfaces standing on the line face: a one-sided surface the half it faces, a two-sided one
/// both, a surface lying flat on the side neither.
struct SeenFrom {
  bool left = false, right = false, both = false;
  /// Whether the half to the left (or right) is seen. Two one-sided surfaces back to back on one
  /// line (two boxes side by side, touching) hide each other: neither half is seen through them.
  bool sees(bool left_half) const { return both || (left_half ? left && !right : right && !left); }
  SeenFrom reversed() const { return {right, left, both}; }
  void add(const SeenFrom& o) { left = left || o.left, right = right || o.right, both = both || o.both; }
};


/// Everything contacts.h computes for one side, in its (s, t) metres.
struct SideContacts {
  std::vector<Segment2> lines;    ///< contact_lines()
  std::vector<SeenFrom> seen;     ///< per line, from which half the surfaces standing on it see the side
  std::vector<Polyline> covered;  ///< regions under the surfaces lying on the side, surface order
};

SideContacts side_contacts(const Scene& scene, SideRef side, std::span<const size_t> candidates) {
  const Surface& s = scene.surfaces[side.surface];
  const Vec3 n = side_normal(s, side.back_side);
  const double offset = n.dot(s.corners[0]);
  const SurfaceFrame frame = s.frame();
  const double border = tol::kOnBorderParameter;
  const double join_m = tol::kContactJoinRelative * std::max(frame.length_u_m, frame.length_v_m);
  const auto on_border = [&](double x, double y) {
    return (std::abs(x) <= border && std::abs(y) <= border) || (std::abs(x - 1) <= border && std::abs(y - 1) <= border);
  };
  SideContacts out;
  // A segment from parameters ua to ub, unless along the surface's border, zero-length or a repeat
  // (whose halves seen are added to the first's).
  const auto add_line = [&](const Vec2& ua, const Vec2& ub, SeenFrom seen) {
    if (on_border(ua.x(), ub.x()) || on_border(ua.y(), ub.y())) return;  // along an edge u or v = 0 or 1
    if (s.is_triangle() && std::abs(ua.sum() - 1) <= border && std::abs(ub.sum() - 1) <= border) return;  // hypotenuse
    Vec2 pa = frame.st(ua), pb = frame.st(ub);
    if (pa == pb) return;
    if (lexicographically_less(pb, pa)) std::swap(pa, pb), seen = seen.reversed();
    for (size_t k = 0; k < out.lines.size(); ++k) {
      const Segment2& l = out.lines[k];
      const bool same = (l.a - pa).norm() <= join_m && (l.b - pb).norm() <= join_m;
      if (same || ((l.a - pb).norm() <= join_m && (l.b - pa).norm() <= join_m)) {
        out.seen[k].add(same ? seen : seen.reversed());
        return;
      }
    }
    out.lines.push_back({pa, pb});
    out.seen.push_back(seen);
  };
  // (s, t) turns counter-clockwise about the surface's front normal (scene.h): left of a
  // direction d in the side's plane is along front x d.
  const Vec3 st_up = s.normal();
  const bool sheet = sheet_face(scene, side.surface, candidates);
  for (const size_t k : candidates) {
    if (k == side.surface) continue;
    const Surface& t = scene.surfaces[k];
    if (lies_on(t, s)) {
      if (!covers(scene, k, side.surface, sheet, candidates)) continue;  // the sheet's other face: no cover, no outline
      std::optional<Polyline> region = overlap_region(t, s);  // the outline clipped to the side
      if (!region) continue;  // no overlap, or only along an edge
      for (size_t i = 0; i < region->size(); ++i) {
        const Vec2& a = (*region)[i];
        const Vec2& b = (*region)[(i + 1) % region->size()];
        add_line(frame.uv(a), frame.uv(b), SeenFrom{});
      }
      out.covered.push_back(std::move(*region));
      continue;
    }
    const double touch_m = contact_tolerance_m(t);
    std::array<double, 4> dist;
    bool in_front = false, all_on = true;
    for (int i = 0; i < 4; ++i) {
      double d = n.dot(t.corners[static_cast<size_t>(i)]) - offset;
      if (std::abs(d) <= touch_m) d = 0;
      dist[static_cast<size_t>(i)] = d;
      in_front = in_front || d > 0;
      all_on = all_on && d == 0;
    }
    if (all_on || !in_front) continue;  // lying flat on the side but not smaller, or only behind it
    Vec3 a, b;
    if (!plane_section(t.corners, dist, a, b) || !clip_to_quad(s, a, b)) continue;
    const std::optional<Vec2> ua = s.parameters(a), ub = s.parameters(b);
    if (!ua || !ub) continue;
    const double facing_left = t.normal().dot(st_up.cross(b - a));
    add_line(*ua, *ub, SeenFrom{facing_left > 0, facing_left < 0, t.two_sided});
  }
  return out;
}

/// The bounded faces of the graph of `lines` joined at their end points (within `join_m`), after
/// removing dangling lines, as regions (as_region()): into `hidden`, or into `faced` if a
/// surface standing on one of their lines faces them (`seen`, per line: the inside of a closed
/// room, not the foot of a block).
void enclosed_regions(const std::vector<Segment2>& lines, const std::vector<SeenFrom>& seen, double join_m,
                      std::vector<Polyline>& hidden, std::vector<Polyline>& faced_out) {
  std::vector<Vec2> nodes;
  const auto node_of = [&](const Vec2& p) {
    for (size_t i = 0; i < nodes.size(); ++i)
      if ((nodes[i] - p).norm() <= join_m) return i;
    nodes.push_back(p);
    return nodes.size() - 1;
  };
  std::set<std::pair<size_t, size_t>> edges;
  std::map<std::pair<size_t, size_t>, SeenFrom> edge_seen;  ///< halves seen, of the direction low -> high node
  for (size_t k = 0; k < lines.size(); ++k) {
    const size_t i = node_of(lines[k].a), j = node_of(lines[k].b);
    if (i == j) continue;
    edges.insert(std::minmax(i, j));
    edge_seen[std::minmax(i, j)].add(i < j ? seen[k] : seen[k].reversed());
  }
  // Dangling lines bound no area: remove every edge at a node of degree 1, until none is left.
  for (bool pruned = true; pruned;) {
    pruned = false;
    std::vector<int> degree(nodes.size(), 0);
    for (const auto& [i, j] : edges) ++degree[i], ++degree[j];
    for (auto e = edges.begin(); e != edges.end();)
      if (degree[e->first] == 1 || degree[e->second] == 1) {
        e = edges.erase(e);
        pruned = true;
      } else {
        ++e;
      }
  }
  // Each node's neighbours counter-clockwise by direction. Walking a face keeps it on the left:
  // from the edge a -> b, on along b's next neighbour clockwise from a. Bounded faces are walked
  // counter-clockwise (positive area), the unbounded one of each connected part clockwise.
  std::vector<std::vector<size_t>> around(nodes.size());
  for (const auto& [i, j] : edges) {
    around[i].push_back(j);
    around[j].push_back(i);
  }
  for (size_t i = 0; i < nodes.size(); ++i)
    std::sort(around[i].begin(), around[i].end(), [&](size_t a, size_t b) {
      const Vec2 da = nodes[a] - nodes[i], db = nodes[b] - nodes[i];
      return std::atan2(da.y(), da.x()) < std::atan2(db.y(), db.x());
    });
  std::vector<std::vector<bool>> walked(nodes.size());
  for (size_t i = 0; i < nodes.size(); ++i) walked[i].assign(around[i].size(), false);
  for (size_t start = 0; start < nodes.size(); ++start)
    for (size_t k0 = 0; k0 < around[start].size(); ++k0) {
      if (walked[start][k0]) continue;
      Polyline face;
      bool faced = false;  // a surface standing on its outline faces it
      size_t node = start, k = k0;
      while (!walked[node][k]) {
        walked[node][k] = true;
        face.push_back(nodes[node]);
        const size_t next = around[node][k];
        // The face lies left of node -> next.
        const SeenFrom& e = edge_seen[std::minmax(node, next)];
        faced = faced || e.sees(node < next);
        const std::vector<size_t>& nb = around[next];
        const size_t back = static_cast<size_t>(std::find(nb.begin(), nb.end(), node) - nb.begin());
        k = (back + nb.size() - 1) % nb.size();
        node = next;
      }
      if (twice_signed_area(face) <= 0) continue;  // the unbounded face
      if (std::optional<Polyline> region = as_region(std::move(face), join_m)) (faced ? faced_out : hidden).push_back(std::move(*region));
    }
}

}  // namespace

// overlap_region() (covering.h) needs this file's clipping and regions.
std::optional<Polyline> overlap_region(const Surface& t, const Surface& s) {
  const SurfaceFrame frame = s.frame();
  const double join_m = tol::kContactJoinRelative * std::max(frame.length_u_m, frame.length_v_m);
  Polyline st;
  for (const Vec3& p : clip_polygon_to_quad(s, std::vector<Vec3>(t.corners.begin(), t.corners.end())))
    if (const std::optional<Vec2> q = s.parameters(p)) st.push_back(frame.st(*q));
  return as_region(std::move(st), join_m);
}

namespace {

/// A surface's bounding box, widened by twice its contact tolerance (tol::kContactRelative of its
/// size), twice the planarity tolerance of its size (the plane side_contacts() cuts with,
/// through corner 0, may leave the corners' box by that much) and tol::kPlaneDistance_m: a
/// surface that touches a side meets the side within these, so their widened boxes meet.
std::array<Vec3, 2> contact_box(const Surface& t) {
  Vec3 lo = t.corners[0], hi = t.corners[0];
  double size_m = 0;  // the largest distance between two corners
  for (const Vec3& c : t.corners) {
    lo = lo.cwiseMin(c), hi = hi.cwiseMax(c);
    for (const Vec3& d : t.corners) size_m = std::max(size_m, (c - d).norm());
  }
  const double margin_m = 2 * contact_tolerance_m(t) +
                          2 * tol::kPlanarityRelative * size_m + tol::kPlaneDistance_m;
  return {lo.array() - margin_m, hi.array() + margin_m};
}

}  // namespace

ContactFinder::ContactFinder(const Scene& scene) : scene_(scene) {
  boxes_.reserve(scene.surfaces.size());
  for (const Surface& t : scene.surfaces) boxes_.push_back(contact_box(t));
}

SideContactSet ContactFinder::at(SideRef side) const {
  const std::array<Vec3, 2>& box = boxes_[side.surface];
  std::vector<size_t> near;  // the surfaces whose box meets the side's, in surface order
  for (size_t k = 0; k < boxes_.size(); ++k)
    if ((boxes_[k][0].array() <= box[1].array()).all() && (box[0].array() <= boxes_[k][1].array()).all())
      near.push_back(k);
  SideContacts contacts = side_contacts(scene_, side, near);
  const Surface& s = scene_.surfaces[side.surface];
  const double join_m = tol::kContactJoinRelative * std::max(s.length_u_m(), s.length_v_m());
  SideContactSet out;
  const auto add = [&](Polyline region) {
    for (const Polyline& r : out.excluded)
      if (same_region(r, region, join_m)) return;
    out.excluded.push_back(std::move(region));
  };
  std::vector<Polyline> hidden, faced;
  enclosed_regions(contacts.lines, contacts.seen, join_m, hidden, faced);
  for (Polyline& r : contacts.covered) add(std::move(r));
  out.covered = out.excluded.size();
  for (Polyline& r : hidden) add(std::move(r));
  const size_t before = out.excluded.size();
  for (Polyline& r : faced) add(std::move(r));
  out.faced = out.excluded.size() - before;
  out.lines = std::move(contacts.lines);
  return out;
}

std::vector<Segment2> contact_lines(const Scene& scene, SideRef side) { return ContactFinder(scene).at(side).lines; }

std::vector<Polyline> excluded_regions(const Scene& scene, SideRef side) {
  SideContactSet set = ContactFinder(scene).at(side);
  set.excluded.resize(set.excluded.size() - set.faced);
  return set.excluded;
}

bool in_region(const Polyline& region, const Vec2& st) {
  bool in = false;
  for (size_t i = 0, j = region.size() - 1; i < region.size(); j = i++) {
    const Vec2 &a = region[i], &b = region[j];
    if ((a.y() > st.y()) != (b.y() > st.y()) && st.x() < a.x() + (st.y() - a.y()) / (b.y() - a.y()) * (b.x() - a.x()))
      in = !in;
  }
  return in;
}

}  // namespace radrecon
