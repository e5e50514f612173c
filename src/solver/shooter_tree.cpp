#include "solver/shooter_tree.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/check.h"
#include "core/parallel.h"
#include "core/tolerances.h"

namespace radrecon {

namespace {

/// The largest distance between two of the block's corners, metres.
double widest(const Block& b) {
  double d = 0;
  for (int a = 0; a < b.corner_count; ++a)
    for (int c = a + 1; c < b.corner_count; ++c) d = std::max(d, (b.corners[a] - b.corners[c]).norm());
  return d;
}

/// An element's second moment of area about its centre over its area, m^2: a parallelogram's
/// (a a^T + b b^T) / 12 for its mid-edge vectors a and b (a quad of the mesh is one up to its
/// surface's bilinear warp); a triangle's sum of v v^T / 12 over its corners v from the centroid.
Eigen::Matrix3d own_area_moment(const MeshElement& e) {
  if (e.corner_count() == 3) {
    const Vec3 c = (e.corners[0] + e.corners[1] + e.corners[2]) / 3.0;
    Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
    for (int k = 0; k < 3; ++k) m += (e.corners[k] - c) * (e.corners[k] - c).transpose();
    return m / 12.0;
  }
  const Vec3 a = 0.5 * ((e.corners[1] - e.corners[0]) + (e.corners[2] - e.corners[3]));
  const Vec3 b = 0.5 * ((e.corners[3] - e.corners[0]) + (e.corners[2] - e.corners[1]));
  return (a * a.transpose() + b * b.transpose()) / 12.0;
}

}  // namespace

/// The outline of the (u,v) box [u0,u1] x [v0,v1] inside the side's parameter domain.
void ShooterTree::set_outline(Block& b, double u0, double v0, double u1, double v1) const {
  std::array<Vec2, 5> uv;
  int n = 0;
  if (!side_.domain.is_triangle() || u1 + v1 <= 1) {
    uv = {Vec2(u0, v0), Vec2(u1, v0), Vec2(u1, v1), Vec2(u0, v1), Vec2()};
    n = 4;
  } else {
    // The box clipped by u + v <= 1 (one Sutherland-Hodgman pass); the box's lower-left corner
    // is inside, as the block holds elements.
    const std::array<Vec2, 4> box = {Vec2(u0, v0), Vec2(u1, v0), Vec2(u1, v1), Vec2(u0, v1)};
    for (int k = 0; k < 4; ++k) {
      const Vec2 &a = box[k], &c = box[(k + 1) % 4];
      const double da = 1 - a.sum(), dc = 1 - c.sum();
      if (da >= 0) uv[n++] = a;
      if ((da > 0 && dc < 0) || (da < 0 && dc > 0)) uv[n++] = a + da / (da - dc) * (c - a);
    }
  }
  set_corners(b, uv.data(), n);
}

void ShooterTree::set_corners(Block& b, const Vec2* uv, int n) const {
  b.corner_count = n;
  for (int k = 0; k < n; ++k) {
    const Vec2& q = uv[side_.back_side && k > 0 ? n - k : k];
    b.corners[k] = surface_.point(q.x(), q.y());
  }
  b.diagonal_m = widest(b);
}

namespace {

/// The block's area, centroid (from the area-weighted sum of centres), mean radiosity (from the
/// area-weighted sum), range and radius.
void set_means(Block& b, double area, const Vec3& weighted_center, const Rgb& weighted, const Rgb& lo, const Rgb& hi) {
  b.unshot_w_m2 = weighted / area;
  b.area_m2 = area;
  b.center = weighted_center / area;
  b.radius_m = 0;
  for (int k = 0; k < b.corner_count; ++k) b.radius_m = std::max(b.radius_m, (b.corners[k] - b.center).norm());
  b.lowest_w_m2 = lo;
  b.highest_w_m2 = hi;
  b.uniform = ((hi - lo) <= tol::kUniformRelative * hi.abs().max(std::numeric_limits<double>::min())).all();
}

}  // namespace

void ShooterTree::set_radiosity(Block& b, size_t first, size_t last) const {
  Rgb weighted = Rgb::Zero(), lo = unshot_[first], hi = lo;
  double area = 0;
  Vec3 center = Vec3::Zero();
  for (size_t k = first; k < last; ++k) {
    const double a = side_.elements[k].area_m2;
    weighted += a * unshot_[k];
    center += a * side_.elements[k].center;
    area += a;
    lo = lo.min(unshot_[k]);
    hi = hi.max(unshot_[k]);
  }
  set_means(b, area, center, weighted, lo, hi);
  b.dipole.setZero();
  for (size_t k = first; k < last; ++k)
    b.dipole += side_.elements[k].area_m2 * (side_.elements[k].center - b.center) *
                (unshot_[k] - b.unshot_w_m2).matrix().transpose();
  b.dipole /= area;
  b.area_moment.setZero();
  for (auto& q : b.quadrupole) q.setZero();
  for (size_t k = first; k < last; ++k) {
    const MeshElement& e = side_.elements[k];
    const Vec3 t = e.center - b.center;
    const Eigen::Matrix3d moment = e.area_m2 * (t * t.transpose() + own_area_moment(e));
    b.area_moment += moment;
    const Rgb deviation = unshot_[k] - b.unshot_w_m2;
    for (int c = 0; c < 3; ++c) b.quadrupole[static_cast<size_t>(c)] += deviation[c] * moment;
  }
  b.area_moment /= area;
  for (auto& q : b.quadrupole) q /= area;
}

void ShooterTree::aggregate(Block& b) const {
  // Each child's moments moved to the parent's centroid (w = its centroid's offset from it): the
  // cross terms vanish, as a child's deviations from its own means sum to zero.
  const std::span<const Block> children(blocks_.data() + b.first_child, static_cast<size_t>(b.child_count));
  Rgb weighted = Rgb::Zero(), lo = children[0].lowest_w_m2, hi = children[0].highest_w_m2;
  double area = 0;
  Vec3 center = Vec3::Zero();
  for (const Block& c : children) {
    weighted += c.area_m2 * c.unshot_w_m2;
    center += c.area_m2 * c.center;
    area += c.area_m2;
    lo = lo.min(c.lowest_w_m2);
    hi = hi.max(c.highest_w_m2);
  }
  set_means(b, area, center, weighted, lo, hi);
  b.dipole.setZero();
  b.area_moment.setZero();
  for (auto& q : b.quadrupole) q.setZero();
  for (const Block& c : children) {
    const Vec3 w = c.center - b.center;
    const Eigen::RowVector3d deviation = (c.unshot_w_m2 - b.unshot_w_m2).matrix().transpose();
    const Eigen::Matrix3d moment = c.area_m2 * (c.area_moment + w * w.transpose());
    b.dipole += c.area_m2 * (c.dipole + w * deviation);
    b.area_moment += moment;
    for (int ch = 0; ch < 3; ++ch) {
      const Vec3 d = c.dipole.col(ch);
      b.quadrupole[static_cast<size_t>(ch)] += c.area_m2 * (c.quadrupole[static_cast<size_t>(ch)] + d * w.transpose() + w * d.transpose()) +
                                               deviation[ch] * moment;
    }
  }
  b.dipole /= area;
  b.area_moment /= area;
  for (auto& q : b.quadrupole) q /= area;
}

ShooterTree::ShooterTree(const Surface& surface, const MeshSurface& side, const std::vector<Rgb>& unshot, int i0,
                         int j0, int i1, int j1, std::vector<Block> storage, const ShooterSplits* splits)
    : surface_(surface), side_(side), unshot_(unshot), splits_(splits), blocks_(std::move(storage)) {
  // Every field of a block is set when it is built: the storage's old blocks need no clearing,
  // and the storage grows only when it holds too few (resize() would construct every block it
  // adds, 0.6 KB each, on one thread, shot after shot).
  const auto hold = [&](size_t blocks) {
    if (blocks_.size() < blocks) blocks_.resize(blocks);
  };
  if (i1 - i0 == 1 && j1 - j0 == 1) {
    const size_t blocks = block_count(side_, splits_, i0, j0, i1, j1);
    hold(blocks);
    RR_CHECK_EQ(build(0, i0, j0, i1, j1, 1), blocks, "shooter tree: blocks miscounted");
    return;
  }
  // The whole patch's children, then their subtrees side by side, each from where the blocks
  // of the ones before it end, as a depth-first build would lay them out.
  std::array<std::array<int, 4>, 4> boxes;
  const int children = child_boxes(side_, splits_, i0, j0, i1, j1, boxes);
  std::array<size_t, 4> first_descendant;
  size_t next = 1 + static_cast<size_t>(children);
  for (int c = 0; c < children; ++c) {
    first_descendant[static_cast<size_t>(c)] = next;
    const auto& q = boxes[static_cast<size_t>(c)];
    next += block_count(side_, splits_, q[0], q[1], q[2], q[3]) - 1;
  }
  hold(next);
  Block& root = blocks_[0];
  root.first_child = 1;
  root.child_count = children;
  set_outline(root, double(i0) / side_.nu, double(j0) / side_.nv, double(i1) / side_.nu, double(j1) / side_.nv);
  std::array<size_t, 4> ends{};
  parallel_for_coarse(0, children, [&](std::int64_t c) {
    const auto& q = boxes[static_cast<size_t>(c)];
    ends[static_cast<size_t>(c)] = build(1 + static_cast<size_t>(c), q[0], q[1], q[2], q[3], first_descendant[static_cast<size_t>(c)]);
  });
  RR_CHECK_EQ(ends[static_cast<size_t>(children - 1)], next, "shooter tree: blocks miscounted");
  aggregate(root);
}

int ShooterTree::child_boxes(const MeshSurface& side, const ShooterSplits* splits, int i0, int j0, int i1, int j1,
                             std::array<std::array<int, 4>, 4>& boxes) {
  // The middle, or the split inside (lo, hi) nearest to it.
  const auto split_at = [](int lo, int hi, const std::vector<int>* at_cells) {
    if (hi - lo <= 1) return hi;
    int at = (lo + hi) / 2;
    if (at_cells != nullptr) {
      int best = -1;
      for (auto it = std::upper_bound(at_cells->begin(), at_cells->end(), lo); it != at_cells->end() && *it < hi; ++it)
        if (best < 0 || std::abs(*it - at) < std::abs(best - at)) best = *it;
      if (best >= 0) at = best;
    }
    return at;
  };
  const int mi = split_at(i0, i1, splits != nullptr ? &splits->u : nullptr);
  const int mj = split_at(j0, j1, splits != nullptr ? &splits->v : nullptr);
  // A part of the box beyond a triangle's hypotenuse (no elements) is no child.
  int count = 0;
  for (const std::array<int, 4>& q : {std::array<int, 4>{i0, j0, mi, mj}, std::array<int, 4>{mi, j0, i1, mj},
                                      std::array<int, 4>{i0, mj, mi, j1}, std::array<int, 4>{mi, mj, i1, j1}})
    if (q[2] > q[0] && q[3] > q[1] && (!side.domain.is_triangle() || q[0] + q[1] <= side.nu - 1))
      boxes[static_cast<size_t>(count++)] = q;
  return count;
}

size_t ShooterTree::block_count(const MeshSurface& side, const ShooterSplits* splits, int i0, int j0, int i1, int j1) {
  if (i1 - i0 == 1 && j1 - j0 == 1) {
    const auto [first, last] = side.cell_elements(i0, j0);
    return 1 + (last - first > 1 ? last - first : 0);  // a cell of two elements: one child each
  }
  std::array<std::array<int, 4>, 4> boxes;
  const int children = child_boxes(side, splits, i0, j0, i1, j1, boxes);
  size_t n = 1;
  for (int c = 0; c < children; ++c) {
    const auto& q = boxes[static_cast<size_t>(c)];
    n += block_count(side, splits, q[0], q[1], q[2], q[3]);
  }
  return n;
}

size_t ShooterTree::build(size_t index, int i0, int j0, int i1, int j1, size_t next) {
  const int nu = side_.nu, nv = side_.nv;
  Block& b = blocks_[index];
  set_outline(b, double(i0) / nu, double(j0) / nv, double(i1) / nu, double(j1) / nv);
  if (i1 - i0 == 1 && j1 - j0 == 1) {
    const auto [first, last] = side_.cell_elements(i0, j0);
    set_radiosity(b, first, last);
    b.first_child = -1;
    b.child_count = 0;
    if (last - first == 1) return next;
    // A cell of two elements (a triangle's lower and upper halves): one child block per element.
    b.first_child = static_cast<int>(next);
    b.child_count = static_cast<int>(last - first);
    for (size_t k = first; k < last; ++k) {
      Block& child = blocks_[next++];
      const MeshElement& e = side_.elements[k];
      child.corner_count = e.corner_count();
      std::copy_n(e.corners.begin(), child.corner_count, child.corners.begin());
      child.diagonal_m = widest(child);
      set_radiosity(child, k, k + 1);
      child.first_child = -1;
      child.child_count = 0;
    }
    return next;
  }
  std::array<std::array<int, 4>, 4> boxes;
  const int children = child_boxes(side_, splits_, i0, j0, i1, j1, boxes);
  b.first_child = static_cast<int>(next);
  b.child_count = children;
  size_t after = next + static_cast<size_t>(children);
  for (int c = 0; c < children; ++c) {
    const auto& q = boxes[static_cast<size_t>(c)];
    after = build(next + static_cast<size_t>(c), q[0], q[1], q[2], q[3], after);
  }
  aggregate(b);
  return after;
}

ShooterSplits shooter_splits(const Scene& scene, const MeshSurface& side, const ContactFinder& contacts) {
  return shooter_splits(scene, side, contacts.at(SideRef{side.scene_surface, side.back_side}));
}

ShooterSplits shooter_splits(const Scene& scene, const MeshSurface& side, const SideContactSet& contacts) {
  ShooterSplits out;
  if (side.domain.is_triangle()) return out;
  const Surface& surface = scene.surfaces[side.scene_surface];
  const double length_u = surface.length_u_m(), length_v = surface.length_v_m();
  // A contact line along which u (or v) is constant, on a cell boundary: that boundary.
  const auto boundary = [](double a, double b, double length, int n, std::vector<int>& into) {
    const double cells_a = a / length * n, cells_b = b / length * n;
    const double at = std::round(cells_a);
    if (std::abs(cells_a - cells_b) <= tol::kSplitAlignRelative && std::abs(cells_a - at) <= tol::kSplitAlignRelative &&
        at > 0 && at < n)
      into.push_back(static_cast<int>(at));
  };
  for (const Segment2& line : contacts.lines) {
    boundary(line.a.x(), line.b.x(), length_u, side.nu, out.u);
    boundary(line.a.y(), line.b.y(), length_v, side.nv, out.v);
  }
  for (std::vector<int>* v : {&out.u, &out.v}) {
    std::sort(v->begin(), v->end());
    v->erase(std::unique(v->begin(), v->end()), v->end());
  }
  return out;
}

}  // namespace radrecon
