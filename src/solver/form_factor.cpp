#include "solver/form_factor.h"

#include <cmath>
#include <numbers>

#include "core/math.h"

namespace radrecon {

namespace {

#if defined(__AVX2__) && defined(__FMA__)
/// Lambert's term of four edges (lanes) from r0 to r1 (offsets of an edge's ends from the
/// receiving point), angle(r0, r1) n . unit(r0 x r1); 0 where r0 x r1 = 0 (the point on the
/// edge's line, or a lane holding no edge).
__m256d edge_terms(__m256d x0, __m256d y0, __m256d z0, __m256d x1, __m256d y1, __m256d z1, __m256d nx, __m256d ny,
                   __m256d nz) {
  const __m256d zero = _mm256_setzero_pd();
  const __m256d cx = _mm256_fmsub_pd(y0, z1, _mm256_mul_pd(z0, y1));
  const __m256d cy = _mm256_fmsub_pd(z0, x1, _mm256_mul_pd(x0, z1));
  const __m256d cz = _mm256_fmsub_pd(x0, y1, _mm256_mul_pd(y0, x1));
  const __m256d c_norm = _mm256_sqrt_pd(_mm256_fmadd_pd(cx, cx, _mm256_fmadd_pd(cy, cy, _mm256_mul_pd(cz, cz))));
  const __m256d dot = _mm256_fmadd_pd(x0, x1, _mm256_fmadd_pd(y0, y1, _mm256_mul_pd(z0, z1)));
  const __m256d n_dot_c = _mm256_fmadd_pd(nx, cx, _mm256_fmadd_pd(ny, cy, _mm256_mul_pd(nz, cz)));
  const __m256d some = _mm256_cmp_pd(c_norm, zero, _CMP_GT_OQ);
  const __m256d ratio = _mm256_div_pd(n_dot_c, _mm256_blendv_pd(_mm256_set1_pd(1.0), c_norm, some));
  return _mm256_and_pd(some, _mm256_mul_pd(atan2_nonneg4(c_norm, dot), ratio));
}
#endif

}  // namespace

double lambert_form_factor(const Vec3& p, const Vec3& n, const ConvexPolygon& polygon) {
  if (polygon.empty()) return 0.0;
#if defined(__AVX2__) && defined(__FMA__)
  // Four edges at a time: the edge from vertex k - 1 to vertex k in lane k mod 4 (r0 = the
  // former's offset from p, r1 = the latter's); lanes past the last edge hold zero vectors,
  // whose cross product is zero: they add nothing, as an edge through p does.
  const int count = polygon.n;
  const __m256d nx = _mm256_set1_pd(n.x()), ny = _mm256_set1_pd(n.y()), nz = _mm256_set1_pd(n.z());
  if (count <= 4) {
    // A triangle or a quad (most calls): its vertices' offsets put in lanes straight from the
    // registers (a vector load of values just stored one by one would wait on their stores), the
    // previous vertex's by rotating the lanes; the same lanes as below.
    const auto offsets = [&](int axis) {
      const auto at = [&](int k) { return k < count ? polygon.v[k][axis] - p[axis] : 0.0; };
      return _mm256_setr_pd(at(0), at(1), at(2), at(3));
    };
    const __m256d bx = offsets(0), by = offsets(1), bz = offsets(2);
    // Lane k takes vertex k - 1: lanes (3, 0, 1, 2) of a quad, (2, 0, 1, 3) of a triangle (whose
    // lane 3 is zero in b and in previous(b) alike: no edge).
    const auto previous = [&](__m256d b) {
      return count == 4 ? _mm256_permute4x64_pd(b, 0x93) : _mm256_permute4x64_pd(b, 0xd2);
    };
    const __m256d total = edge_terms(previous(bx), previous(by), previous(bz), bx, by, bz, nx, ny, nz);
    return std::abs(sum_lanes(total)) / (2.0 * std::numbers::pi);
  }
  alignas(32) double r[6][ConvexPolygon::kCapacity + 4];  // x0 y0 z0 x1 y1 z1 by edge
  Vec3 a = polygon.v[count - 1] - p;
  for (int k = 0; k < count; ++k) {
    const Vec3 b = polygon.v[k] - p;
    r[0][k] = a.x(), r[1][k] = a.y(), r[2][k] = a.z(), r[3][k] = b.x(), r[4][k] = b.y(), r[5][k] = b.z();
    a = b;
  }
  for (int k = count; k % 4 != 0; ++k)
    for (auto& row : r) row[k] = 0;
  __m256d total = _mm256_setzero_pd();
  for (int k = 0; k < count; k += 4)
    total = _mm256_add_pd(total, edge_terms(_mm256_load_pd(&r[0][k]), _mm256_load_pd(&r[1][k]), _mm256_load_pd(&r[2][k]),
                                            _mm256_load_pd(&r[3][k]), _mm256_load_pd(&r[4][k]), _mm256_load_pd(&r[5][k]),
                                            nx, ny, nz));
  return std::abs(sum_lanes(total)) / (2.0 * std::numbers::pi);
#else
  double sum = 0.0;
  Vec3 r0 = polygon.v[polygon.n - 1] - p;
  for (int i = 0; i < polygon.n; ++i) {
    Vec3 r1 = polygon.v[i] - p;
    Vec3 c = r0.cross(r1);
    double c_norm = c.norm();
    // c_norm == 0: p on the line of this edge; the edge subtends no angle and adds nothing.
    if (c_norm > 0) sum += atan2_nonneg(c_norm, r0.dot(r1)) * n.dot(c) / c_norm;
    r0 = r1;
  }
  return std::abs(sum) / (2.0 * std::numbers::pi);
#endif
}

void lambert_form_factors4(const std::array<Vec3, 4>& points, const Vec3& n, const ConvexPolygon& polygon,
                           std::array<double, 4>& out) {
  if (polygon.empty()) {
    out.fill(0.0);
    return;
  }
#if defined(__AVX2__) && defined(__FMA__)
  const __m256d px = _mm256_setr_pd(points[0].x(), points[1].x(), points[2].x(), points[3].x());
  const __m256d py = _mm256_setr_pd(points[0].y(), points[1].y(), points[2].y(), points[3].y());
  const __m256d pz = _mm256_setr_pd(points[0].z(), points[1].z(), points[2].z(), points[3].z());
  const __m256d nx = _mm256_set1_pd(n.x()), ny = _mm256_set1_pd(n.y()), nz = _mm256_set1_pd(n.z());
  const auto offset = [&](const Vec3& v, __m256d& x, __m256d& y, __m256d& z) {
    x = _mm256_sub_pd(_mm256_set1_pd(v.x()), px);
    y = _mm256_sub_pd(_mm256_set1_pd(v.y()), py);
    z = _mm256_sub_pd(_mm256_set1_pd(v.z()), pz);
  };
  __m256d x0, y0, z0, x1, y1, z1;
  offset(polygon.v[polygon.n - 1], x0, y0, z0);
  __m256d total = _mm256_setzero_pd();
  for (int k = 0; k < polygon.n; ++k) {
    offset(polygon.v[k], x1, y1, z1);
    total = _mm256_add_pd(total, edge_terms(x0, y0, z0, x1, y1, z1, nx, ny, nz));
    x0 = x1, y0 = y1, z0 = z1;
  }
  const __m256d magnitude = _mm256_andnot_pd(_mm256_set1_pd(-0.0), total);
  _mm256_storeu_pd(out.data(), _mm256_div_pd(magnitude, _mm256_set1_pd(2.0 * std::numbers::pi)));
#else
  for (size_t k = 0; k < 4; ++k) out[k] = lambert_form_factor(points[k], n, polygon);
#endif
}

ConvexPolygon clip_to_horizon(const Vec3& p, const Vec3& n, const ConvexPolygon& polygon) {
  return clip(polygon, HalfSpace{n, n.dot(p)});
}

}  // namespace radrecon
