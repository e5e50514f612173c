#include "solver/far_field.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/check.h"
#include "core/simd.h"
#include "core/tolerances.h"

namespace radrecon {

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
KernelSecondOrder kernel_second_order(const Block& b, const Vec3& p, const Vec3& n, const Vec3& shooter_normal,
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
double contract(const KernelSecondOrder& m, const Eigen::Matrix3d& s) {
  return m[0] * s(0, 0) + m[3] * s(1, 1) + m[5] * s(2, 2) +
         (m[1] * (s(0, 1) + s(1, 0)) + m[2] * (s(0, 2) + s(2, 0)) + m[4] * (s(1, 2) + s(2, 1)));
}

}  // namespace

double far_field_error(const Block& b, const Vec3& p, const Vec3& n, const Vec3& shooter_normal, const Vec3& g,
                       std::optional<KernelSecondOrder>* second_order) {
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
  const KernelSecondOrder m = kernel_second_order(b, p, n, shooter_normal, g);
  if (second_order != nullptr) *second_order = m;
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
#if RADRECON_SIMD
  // A box's eight points in SIMD packets, each lane in check()'s operations and order (Eigen sums
  // a 3-vector's dot product and squared norm as (x + y) + z in these builds), so with the values
  // the loop below gives in the same build: the paper's reference and the Cornell box's
  // solutions are identical either way (docs/benchmarks.md).
  if (box) {
    using simd::PackD;
    constexpr int kPoints = 8;
    alignas(64) double yx[kPoints], yy[kPoints], yz[kPoints];
    for (int a = 0; a < 4; ++a) {
      const Vec3& y0 = b.corners[a];
      const Vec3 mid = y0 + 0.5 * (b.corners[(a + 1) % 4] - y0);
      yx[2 * a] = y0.x(), yy[2 * a] = y0.y(), yz[2 * a] = y0.z();
      yx[2 * a + 1] = mid.x(), yy[2 * a + 1] = mid.y(), yz[2 * a + 1] = mid.z();
    }
    const auto set = [](double v) { return PackD::set(v); };
    PackD most = PackD::zero();
    for (int j = 0; j < kPoints; j += PackD::kLanes) {
      const PackD qx = PackD::load(yx + j), qy = PackD::load(yy + j), qz = PackD::load(yz + j);  // the points y
      const PackD d0 = set(p.x()) - qx, d1 = set(p.y()) - qy, d2 = set(p.z()) - qz;
      const PackD r2 = (d0 * d0 + d1 * d1) + d2 * d2;
      const PackD sd = (set(shooter_normal.x()) * d0 + set(shooter_normal.y()) * d1) + set(shooter_normal.z()) * d2;
      const PackD nd = (set(n.x()) * d0 + set(n.y()) * d1) + set(n.z()) * d2;
      const PackD k = (sd * -nd) / (r2 * r2);
      if (!k.all_positive()) return std::numeric_limits<double>::infinity();
      const PackD t0 = qx - set(b.center.x()), t1 = qy - set(b.center.y()), t2 = qz - set(b.center.z());
      PackD taylor = set(1.0) + ((set(g.x()) * t0 + set(g.y()) * t1) + set(g.z()) * t2);
      if (second) {
        const PackD squares = (set(m[0]) * t0 * t0 + set(m[3]) * t1 * t1) + set(m[5]) * t2 * t2;
        const PackD products = (set(m[1]) * t0 * t1 + set(m[2]) * t0 * t2) + set(m[4]) * t1 * t2;
        taylor = taylor + set(0.5) * (squares + set(2.0) * products);
      }
      // As std::max(worst, term): a NaN term leaves the maximum as it was (max() returns its
      // second operand where either is NaN).
      most = max(abs(k / set(k_c) - taylor), most);
    }
    return 0.5 * tol::kFarFieldRemainderSamplingBox * most.max_lane();
  }
#endif
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

Rgb far_field_radiosity(const Block& b, const Vec3& p, const Vec3& n, const Vec3& shooter_normal, const Vec3* gradient,
                        const KernelSecondOrder* second_order) {
  if (gradient == nullptr) return b.unshot_w_m2;
  const Vec3& g = *gradient;
  const KernelSecondOrder m = second_order != nullptr ? *second_order : kernel_second_order(b, p, n, shooter_normal, g);
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

void far_field_radiosities(const Block& b, std::span<const Vec3> points, const Vec3& n, const Vec3& shooter_normal,
                           std::span<Rgb> out) {
  RR_CHECK_EQ(points.size(), out.size(), "a far field per point");
#if RADRECON_SIMD
  // kernel_log_gradient(), kernel_second_order() and far_field_radiosity() lane by lane, in
  // their operations and order (Eigen's 3-vector dot and a row vector times a 3 x 3 matrix sum
  // (x + y) + z), so with their values bit for bit.
  using simd::PackD;
  constexpr size_t L = PackD::kLanes;
  const auto set = [](double v) { return PackD::set(v); };
  const Vec3& s = shooter_normal;
  for (size_t first = 0; first < points.size(); first += L) {
    const size_t count = std::min(L, points.size() - first);
    alignas(64) double lane[3][L];
    for (size_t k = 0; k < L; ++k)  // lanes past the end repeat the first point
      for (int a = 0; a < 3; ++a) lane[a][k] = points[first + (k < count ? k : 0)][a] - b.center[a];
    const PackD d[3] = {PackD::load(lane[0]), PackD::load(lane[1]), PackD::load(lane[2])};
    const PackD r2 = (d[0] * d[0] + d[1] * d[1]) + d[2] * d[2];
    const PackD cos_y = (set(s.x()) * d[0] + set(s.y()) * d[1]) + set(s.z()) * d[2];
    const PackD cos_x = -((set(n.x()) * d[0] + set(n.y()) * d[1]) + set(n.z()) * d[2]);
    const PackD least = set(tol::kKernelCosine) * sqrt(r2);
    alignas(64) double expands[L];
    PackD::select(cos_y > least, PackD::select(cos_x > least, set(1.0), PackD::zero()), PackD::zero()).store(expands);
    PackD g[3];
    for (int i = 0; i < 3; ++i) g[i] = (set(-s[i]) / cos_y + set(n[i]) / cos_x) + (set(4.0) * d[i]) / r2;
    // M = H + g g^T, its upper triangle row by row (00 01 02 11 12 22).
    const PackD wy = set(1.0) / (cos_y * cos_y), wx = set(1.0) / (cos_x * cos_x), wd = set(8.0) / (r2 * r2),
                wi = set(4.0) / r2;
    const auto entry = [&](int i, int j) {
      const PackD e = (((-wy) * set(s[i]) * set(s[j]) - wx * set(n[i]) * set(n[j])) + wd * d[i] * d[j]) + g[i] * g[j];
      return i == j ? e - wi : e - PackD::zero();
    };
    const PackD m[6] = {entry(0, 0), entry(0, 1), entry(0, 2), entry(1, 1), entry(1, 2), entry(2, 2)};
    const auto contract = [&](const Eigen::Matrix3d& t) {
      return ((m[0] * set(t(0, 0)) + m[3] * set(t(1, 1))) + m[5] * set(t(2, 2))) +
             ((m[1] * set(t(0, 1) + t(1, 0)) + m[2] * set(t(0, 2) + t(2, 0))) + m[4] * set(t(1, 2) + t(2, 1)));
    };
    const PackD shape = set(1.0) + set(0.5) * contract(b.area_moment);
    const PackD::Mask second = abs(shape - set(1.0)) <= set(tol::kFarFieldCurvatureLimit);
    alignas(64) double channel[3][L];
    for (int c = 0; c < 3; ++c) {
      PackD corrected = (g[0] * set(b.dipole(0, c)) + g[1] * set(b.dipole(1, c))) + g[2] * set(b.dipole(2, c));
      corrected = PackD::select(second, (corrected + set(0.5) * contract(b.quadrupole[static_cast<size_t>(c)])) / shape,
                                corrected);
      corrected = min(max(corrected + set(b.unshot_w_m2[c]), set(b.lowest_w_m2[c])), set(b.highest_w_m2[c]));
      corrected.store(channel[c]);
    }
    for (size_t k = 0; k < count; ++k)
      out[first + k] = expands[k] != 0 ? Rgb(channel[0][k], channel[1][k], channel[2][k]) : b.unshot_w_m2;
  }
#else
  for (size_t k = 0; k < points.size(); ++k) out[k] = far_field_radiosity(b, points[k], n, shooter_normal);
#endif
}

}  // namespace radrecon
