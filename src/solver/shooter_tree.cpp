#include "solver/shooter_tree.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

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
  // Every field of a block is set when it is built: the storage's old blocks need no clearing.
  if (i1 - i0 == 1 && j1 - j0 == 1) {
    blocks_.resize(count(i0, j0, i1, j1));
    RR_CHECK_EQ(build(0, i0, j0, i1, j1, 1), blocks_.size(), "shooter tree: blocks miscounted");
    return;
  }
  // The whole patch's children, then their subtrees side by side, each from where the blocks
  // of the ones before it end, as a depth-first build would lay them out.
  std::array<std::array<int, 4>, 4> boxes;
  const int children = child_boxes(i0, j0, i1, j1, boxes);
  std::array<size_t, 4> first_descendant;
  size_t next = 1 + static_cast<size_t>(children);
  for (int c = 0; c < children; ++c) {
    first_descendant[static_cast<size_t>(c)] = next;
    const auto& q = boxes[static_cast<size_t>(c)];
    next += count(q[0], q[1], q[2], q[3]) - 1;
  }
  blocks_.resize(next);
  Block& root = blocks_[0];
  root.first_child = 1;
  root.child_count = children;
  set_outline(root, double(i0) / side_.nu, double(j0) / side_.nv, double(i1) / side_.nu, double(j1) / side_.nv);
  std::array<size_t, 4> ends{};
  parallel_for_coarse(0, children, [&](std::int64_t c) {
    const auto& q = boxes[static_cast<size_t>(c)];
    ends[static_cast<size_t>(c)] = build(1 + static_cast<size_t>(c), q[0], q[1], q[2], q[3], first_descendant[static_cast<size_t>(c)]);
  });
  RR_CHECK_EQ(ends[static_cast<size_t>(children - 1)], blocks_.size(), "shooter tree: blocks miscounted");
  aggregate(root);
}

int ShooterTree::child_boxes(int i0, int j0, int i1, int j1, std::array<std::array<int, 4>, 4>& boxes) const {
  // The middle, or the split inside (lo, hi) nearest to it.
  const auto split_at = [](int lo, int hi, const std::vector<int>* splits) {
    if (hi - lo <= 1) return hi;
    int at = (lo + hi) / 2;
    if (splits != nullptr) {
      int best = -1;
      for (auto it = std::upper_bound(splits->begin(), splits->end(), lo); it != splits->end() && *it < hi; ++it)
        if (best < 0 || std::abs(*it - at) < std::abs(best - at)) best = *it;
      if (best >= 0) at = best;
    }
    return at;
  };
  const int mi = split_at(i0, i1, splits_ != nullptr ? &splits_->u : nullptr);
  const int mj = split_at(j0, j1, splits_ != nullptr ? &splits_->v : nullptr);
  // A part of the box beyond a triangle's hypotenuse (no elements) is no child.
  int count = 0;
  for (const std::array<int, 4>& q : {std::array<int, 4>{i0, j0, mi, mj}, std::array<int, 4>{mi, j0, i1, mj},
                                      std::array<int, 4>{i0, mj, mi, j1}, std::array<int, 4>{mi, mj, i1, j1}})
    if (q[2] > q[0] && q[3] > q[1] && (!side_.domain.is_triangle() || q[0] + q[1] <= side_.nu - 1))
      boxes[static_cast<size_t>(count++)] = q;
  return count;
}

size_t ShooterTree::count(int i0, int j0, int i1, int j1) const {
  if (i1 - i0 == 1 && j1 - j0 == 1) {
    const auto [first, last] = side_.cell_elements(i0, j0);
    return 1 + (last - first > 1 ? last - first : 0);  // a cell of two elements: one child each
  }
  std::array<std::array<int, 4>, 4> boxes;
  const int children = child_boxes(i0, j0, i1, j1, boxes);
  size_t n = 1;
  for (int c = 0; c < children; ++c) {
    const auto& q = boxes[static_cast<size_t>(c)];
    n += count(q[0], q[1], q[2], q[3]);
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
  const int children = child_boxes(i0, j0, i1, j1, boxes);
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
  for (const Segment2& line : contacts.at(SideRef{side.scene_surface, side.back_side}).lines) {
    boundary(line.a.x(), line.b.x(), length_u, side.nu, out.u);
    boundary(line.a.y(), line.b.y(), length_v, side.nv, out.v);
  }
  for (std::vector<int>* v : {&out.u, &out.v}) {
    std::sort(v->begin(), v->end());
    v->erase(std::unique(v->begin(), v->end()), v->end());
  }
  return out;
}

bool kernel_log_gradient(const Block& b, const Vec3& p, const Vec3& n, const Vec3& shooter_normal, Vec3& g) {
  // k = (n_s . d)(-n . d) / (pi |d|^4) with d = x - y (n_s the shooter's normal, n the
  // receiver's): over y, grad ln k = -n_s / (n_s . d) + n / (-n . d) + 4 d / |d|^2.
  const Vec3 d = p - b.center;  // from the source point y = c to the receiver x = p
  const double r2 = d.squaredNorm(), cos_y = shooter_normal.dot(d), cos_x = -n.dot(d);  // times |d|
  if (!(cos_y > tol::kKernelCosine * std::sqrt(r2) && cos_x > tol::kKernelCosine * std::sqrt(r2))) return false;
  g = -shooter_normal / cos_y + n / cos_x + 4.0 * d / r2;
  return true;
}

namespace {

/// M = H + g g^T at p for the block's centroid: H the Hessian over the source point of ln k,
/// k = (n_s . d)(-n . d) / (pi |d|^4), d = p - y: -n_s n_s^T / (n_s . d)^2 - n n^T / (n . d)^2 +
/// 4 (2 d d^T / |d|^4 - I / |d|^2). Symmetric: its upper triangle, row by row (00 01 02 11 12 22).
std::array<double, 6> kernel_second_order(const Block& b, const Vec3& p, const Vec3& n, const Vec3& shooter_normal,
                                          const Vec3& g) {
  const Vec3 d = p - b.center;
  const double r2 = d.squaredNorm(), cos_y = shooter_normal.dot(d), cos_x = -n.dot(d);  // times |d|
  const double wy = 1.0 / (cos_y * cos_y), wx = 1.0 / (cos_x * cos_x), wd = 8.0 / (r2 * r2), wi = 4.0 / r2;
  const Vec3& s = shooter_normal;
  const auto entry = [&](int i, int j) {
    return -wy * s[i] * s[j] - wx * n[i] * n[j] + wd * d[i] * d[j] + g[i] * g[j] - (i == j ? wi : 0.0);
  };
  return {entry(0, 0), entry(0, 1), entry(0, 2), entry(1, 1), entry(1, 2), entry(2, 2)};
}

/// sum over i, j of M_ij S_ij for M as kernel_second_order() gives it (symmetric) and the moment S
/// (symmetric but for rounding: both of its off-diagonal entries are read).
double contract(const std::array<double, 6>& m, const Eigen::Matrix3d& s) {
  return m[0] * s(0, 0) + m[3] * s(1, 1) + m[5] * s(2, 2) +
         (m[1] * (s(0, 1) + s(1, 0)) + m[2] * (s(0, 2) + s(2, 0)) + m[4] * (s(1, 2) + s(2, 1)));
}

}  // namespace

double far_field_error(const Block& b, const Vec3& p, const Vec3& n, const Vec3& shooter_normal, const Vec3& g) {
  // The far field is sum_k A_k k(y_k) B_eff against the exact sum_k A_k k(y_k) B_k, with k's
  // expansion k(c) (1 + g . t + t^T M t / 2) integrated exactly (far_field_radiosity()): it errs
  // by k(c) sum_k A_k R(t_k) (B_eff - B_k), R the kernel's remainder relative to k(c). That is at
  // most the form factor times max |R| times the mean deviation of the radiosity from B_eff:
  // about half the spread (about the mean it is at most that; B_eff is the mean plus
  // corrections of first and second order). max |R| is read off the kernel itself at the
  // block's corners and edge midpoints: the leading remainder, a cubic form in t, takes at most
  // tol::kFarFieldRemainderSamplingBox times its largest value there anywhere on a box (other
  // blocks: at each edge's quarters, kFarFieldRemainderSamplingOther). Where the far field is
  // first order only (far_field_radiosity()), R is the remainder after the linear term.
  //
  // The cubic term dominates while the kernel's logarithm changes little over the block: its
  // gradient in the shooter's plane g_t, and the curvature 4 / |d|^2 of -4 ln |d|; beyond, the
  // block splits (the higher orders compete, and a closed room lost 2.3e-4 of its power instead
  // of 8e-6). The receiver's cosine is linear over the block: its curvature, large near the
  // receiver's plane, is no limit. The kernel must be positive at every point read: a block cut
  // by the receiver's plane has no expansion.
  const Vec3 g_t = g - g.dot(shooter_normal) * shooter_normal;
  const double radius = b.radius_m;
  if (!(0.5 * radius * radius * (4.0 / (p - b.center).squaredNorm() + g_t.squaredNorm()) <= tol::kFarFieldCurvatureLimit))
    return std::numeric_limits<double>::infinity();
  const auto kernel = [&](const Vec3& y) {
    const Vec3 d = p - y;
    const double r2 = d.squaredNorm();
    return shooter_normal.dot(d) * -n.dot(d) / (r2 * r2);
  };
  const double k_c = kernel(b.center);
  if (!(k_c > 0)) return std::numeric_limits<double>::infinity();
  const std::array<double, 6> m = kernel_second_order(b, p, n, shooter_normal, g);
  const bool second = std::abs(0.5 * contract(m, b.area_moment)) <= tol::kFarFieldCurvatureLimit;
  double worst = 0;
  const auto check = [&](const Vec3& y) {
    const Vec3 t = y - b.center;
    const double k = kernel(y);
    if (!(k > 0)) return false;
    double taylor = 1.0 + g.dot(t);
    if (second)
      taylor += 0.5 * (m[0] * t[0] * t[0] + m[3] * t[1] * t[1] + m[5] * t[2] * t[2] +
                       2.0 * (m[1] * t[0] * t[1] + m[2] * t[0] * t[2] + m[4] * t[1] * t[2]));
    worst = std::max(worst, std::abs(k / k_c - taylor));
    return true;
  };
  // A box's corners and edge midpoints; on other blocks those lie on three lines through the
  // centroid for a triangle (its medians), where a cubic form can vanish: each edge's quarters.
  const bool box = b.corner_count == 4;
  const int per_edge = box ? 2 : 4;
  for (int a = 0; a < b.corner_count; ++a) {
    const Vec3& y0 = b.corners[a];
    const Vec3& y1 = b.corners[(a + 1) % b.corner_count];
    for (int k = 0; k < per_edge; ++k)
      if (!check(y0 + (static_cast<double>(k) / per_edge) * (y1 - y0))) return std::numeric_limits<double>::infinity();
  }
  const double sampling = box ? tol::kFarFieldRemainderSamplingBox : tol::kFarFieldRemainderSamplingOther;
  return 0.5 * sampling * worst;
}


Rgb far_field_radiosity(const Block& b, const Vec3& p, const Vec3& n, const Vec3& shooter_normal) {
  Vec3 g;
  return far_field_radiosity(b, p, n, shooter_normal, kernel_log_gradient(b, p, n, shooter_normal, g) ? &g : nullptr);
}

Rgb far_field_radiosity(const Block& b, const Vec3& p, const Vec3& n, const Vec3& shooter_normal, const Vec3* gradient) {
  if (gradient == nullptr) return b.unshot_w_m2;
  const Vec3& g = *gradient;
  const std::array<double, 6> m = kernel_second_order(b, p, n, shooter_normal, g);
  const double shape = 1.0 + 0.5 * contract(m, b.area_moment);
  Rgb corrected = (g.transpose() * b.dipole).transpose().array();
  // Where the second-order term is not small (near grazing, or a block near the receiver that
  // shoots whole by the strict bound or the distance rule) the expansion is not to be trusted,
  // and 1 / shape could even change sign: first order only.
  if (std::abs(shape - 1.0) <= tol::kFarFieldCurvatureLimit) {
    for (int c = 0; c < 3; ++c) corrected[c] += 0.5 * contract(m, b.quadrupole[static_cast<size_t>(c)]);
    corrected /= shape;
  }
  corrected += b.unshot_w_m2;
  return corrected.max(b.lowest_w_m2).min(b.highest_w_m2);
}

GaussPoints gauss_points(const ParamCell& e) {
  GaussPoints out;
  if (e.is_triangle()) {
    const auto v = e.vertices();
    for (int k = 0; k < 3; ++k) out.uv[out.count++] = (4.0 * v[k] + v[(k + 1) % 3] + v[(k + 2) % 3]) / 6.0;
    return out;
  }
  const double g = 0.5 / std::sqrt(3.0);  // Gauss-Legendre nodes at the centre +- half-width / sqrt(3)
  const double um = 0.5 * (e.u0 + e.u1), vm = 0.5 * (e.v0 + e.v1);
  const double du = (e.u1 - e.u0) * g, dv = (e.v1 - e.v0) * g;
  for (const double sv : {-1.0, 1.0})
    for (const double su : {-1.0, 1.0}) out.uv[out.count++] = Vec2(um + su * du, vm + sv * dv);
  return out;
}

Receiver make_receiver(const Surface& surface, const MeshElement& e, const Vec3& normal) {
  Receiver r;
  r.center = e.center;
  r.normal = normal;
  r.size_m = std::max((e.corners[2] - e.corners[0]).norm(), (e.corners[3] - e.corners[1]).norm());
  const GaussPoints g = gauss_points(e);
  for (int k = 0; k < g.count; ++k) r.gauss[k] = surface.point(g.uv[k].x(), g.uv[k].y());
  r.gauss_count = g.count;
  return r;
}

double form_factor_bound(const Block& b, const Vec3& p, const Vec3& n, const Vec3& shooter_normal) {
  const double d = (p - b.center).norm() - b.radius_m;  // no point of the block is nearer to p
  if (!(d > 0)) return std::numeric_limits<double>::infinity();
  const double h = shooter_normal.dot(p - b.center);  // cos_y = h / r, the same plane for all y
  double lift = 0;  // n . (y - p) is linear in y: largest at a corner
  for (int k = 0; k < b.corner_count; ++k) lift = std::max(lift, n.dot(b.corners[k] - p));
  if (!(h > 0) || !(lift > 0)) return 0;
  return b.area_m2 * std::min(1.0, lift / d) * std::min(1.0, h / d) / (std::numbers::pi * d * d);
}

bool gathers_at_centre(const Block& b, const Receiver& r) {
  const double gap_m = (r.center - b.center).norm() - 0.5 * b.diagonal_m;
  return r.size_m <= tol::kMidpointReceiverRatio * gap_m;
}

namespace {

/// What shoots_whole() found at the receiving element's centre, for gather() to reuse: the
/// visible form factor (-1 if not computed) and the kernel's log-gradient (if computed: `g` when
/// `expands`, else the angle is grazing).
struct AtCentre {
  double f = -1;
  bool partly_seen = false;  ///< with f: whether the centre sees the block in part
  bool gradient_known = false, expands = false;
  Vec3 g;
};

/// Whether the block may shoot to the receiving element as one source: see gather(). Fills
/// `centre` with what it computed there to decide. `midpoint`: the element gathers at its
/// centre alone.
bool shoots_whole(const Block& b, const ConvexPolygon& poly, const Receiver& r, const Vec3& shooter_normal,
                  const ReceiverShadows& shadows, double budget_w_m2, bool midpoint, AtCentre& centre) {
  double& f = centre.f;
  if (b.first_child < 0 || b.uniform) return true;
  const Vec3 &p = r.center, &n = r.normal;
  if (budget_w_m2 <= 0) {
    const double far_m = tol::kFarFieldDiagonals * b.diagonal_m;
    return (p - b.center).squaredNorm() > far_m * far_m;
  }
  const double spread = (b.highest_w_m2 - b.lowest_w_m2).sum();
  // Any far field lies in [lowest, highest] times the visible form factor, as the children's sum
  // does: a strict bound with form_factor_bound() at the centre (the Gauss points, which only
  // the element's power uses, are within half its size of it).
  double form_factor = form_factor_bound(b, p, n, shooter_normal);
  if (form_factor * spread <= budget_w_m2) return true;
  if (!std::isfinite(form_factor)) return false;
  // The far field is exact to second order, whatever the radiosity over the block
  // (far_field_radiosity()): what is left is the spread times the kernel's third order,
  // provided the centre sees all of the block (else the kernel seen is cut).
  centre.gradient_known = true;
  centre.expands = kernel_log_gradient(b, p, n, shooter_normal, centre.g);
  const double error_per_spread = centre.expands ? far_field_error(b, p, n, shooter_normal, centre.g)
                                                 : std::numeric_limits<double>::infinity();
  // Off the midpoint the bound's form factor stays: without the visible one, the block splits.
  if (!midpoint && !(form_factor * spread * error_per_spread <= budget_w_m2)) return false;
  if (f < 0) f = visible_form_factor_past(p, n, poly, shooter_normal, shadows.at(0), &centre.partly_seen);
  const bool partly_seen = centre.partly_seen;
  // A block seen in part splits: it would shoot with the mean of all of it, an error within the
  // bound but of one sign for every element that sees the same part (the ground's blocks behind
  // a wall's horizon), which adds up over the shots: the paper's walls were 0.1% too dark.
  if (partly_seen) return false;
  if (midpoint) {
    // The element gathers at its centre alone: bound with the visible form factor there.
    form_factor = f;
    if (f * spread <= budget_w_m2) return true;
  }
  return form_factor * spread * error_per_spread <= budget_w_m2;
}

}  // namespace

std::span<const ShadowVolume> ReceiverShadows::at(int point) const {
  RR_CHECK(point >= 0 && point <= r_.gauss_count, "receiver point out of range");
  const size_t k = static_cast<size_t>(point);
  if (!made_[k]) {
    if (find_ != nullptr && !found_) {
      call_find_(find_);
      found_ = true;
    }
    shadow_volumes(point == 0 ? r_.center : r_.gauss[k - 1], r_.normal, occluders_, volumes_[k]);
    made_[k] = true;
  }
  return volumes_[k];
}

thread_local std::array<std::vector<ShadowVolume>, 5> ReceiverShadows::volumes_;

Gathered gather(const ShooterTree& tree, const Block& b, const Receiver& r, const Vec3& shooter_normal,
                const ReceiverShadows& shadows, double budget_w_m2, const SeenFromCentre* seen) {
  Gathered out;
  if ((b.highest_w_m2 == 0).all()) return out;
  AtCentre centre;
  if (seen != nullptr) centre.f = seen->form_factor, centre.partly_seen = seen->partly;
  // The budget is shared among the blocks in proportion to their area: those that shoot as one
  // tile the patch, so their errors add up to at most budget_w_m2.
  const double share = budget_w_m2 * b.area_m2 / tree.root().area_m2;
  const bool midpoint = gathers_at_centre(b, r);
  ConvexPolygon poly;  // the block's outline, for its form factors
  for (int k = 0; k < b.corner_count; ++k) poly.push(b.corners[k]);
  if (!shoots_whole(b, poly, r, shooter_normal, shadows, share, midpoint, centre)) {
    for (int c = 0; c < b.child_count; ++c)
      out += gather(tree, tree.block(b.first_child + c), r, shooter_normal, shadows, budget_w_m2);
    return out;
  }
  const auto at = [&](const Vec3& p, int point, double f, const AtCentre* known) -> Rgb {
    if (f < 0) f = visible_form_factor_past(p, r.normal, poly, shooter_normal, shadows.at(point));
    if (f == 0 || b.uniform) return f * b.unshot_w_m2;
    if (known != nullptr && known->gradient_known)
      return f * far_field_radiosity(b, p, r.normal, shooter_normal, known->expands ? &known->g : nullptr);
    return f * far_field_radiosity(b, p, r.normal, shooter_normal);
  };
  out.at_center = at(r.center, 0, centre.f, &centre);
  if (midpoint) {
    out.mean = out.at_center;
  } else {
    // The Gauss points' form factors together: those that see all of the block in one
    // vectorised integral.
    std::array<double, 4> f;
    const size_t count = static_cast<size_t>(r.gauss_count);
    double* kept = seen != nullptr ? seen->gauss : nullptr;  // the block's, from an earlier gather
    if (kept != nullptr && !std::isnan(kept[0])) {
      std::copy(kept, kept + count, f.begin());
    } else {
      std::array<std::span<const ShadowVolume>, 4> volumes;
      for (size_t k = 0; k < count; ++k) volumes[k] = shadows.at(static_cast<int>(k) + 1);
      visible_form_factors_past({r.gauss.data(), count}, r.normal, poly, shooter_normal, {volumes.data(), count},
                                {f.data(), count});
      if (kept != nullptr) std::copy(f.begin(), f.begin() + static_cast<std::ptrdiff_t>(count), kept);
    }
    for (size_t k = 0; k < count; ++k) out.mean += at(r.gauss[k], static_cast<int>(k) + 1, f[k], nullptr);
    out.mean /= r.gauss_count;
  }
  return out;
}

}  // namespace radrecon
