#include "reconstruct/clough_tocher.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>


#include "core/check.h"
#include "core/parallel.h"
#include "core/parse.h"
#include "core/tolerances.h"

namespace radrecon {

CloughTocher::CloughTocher(const ScatteredSamples& samples, OutsideHull outside, std::span<const double> gradients)
    : mesh_(samples.points, "clough-tocher"), channels_(samples.channels), outside_(outside) {
  RR_CHECK(samples.values.size() == samples.points.size() * static_cast<size_t>(channels_),
           "sample values do not match the points");
  for (const double v : samples.values)
    if (!std::isfinite(v)) throw ReconstructionError("clough-tocher needs finite sample values");
  if (gradients.empty()) {
    estimate_gradients(samples.values);
  } else {
    RR_CHECK(gradients.size() == 2 * samples.values.size(), "gradients do not match the samples");
    gradients_.assign(gradients.begin(), gradients.end());
  }
  build_nets(samples.values);
}

namespace {

/// The normal equations of Nielson's functional (estimate_gradients()) as 2 x 2 blocks: per
/// sample, its diagonal block and, per Delaunay neighbour, the off-diagonal block; all are
/// symmetric, stored as (xx, xy, yy).
struct BlockSystem {
  std::vector<std::array<double, 3>> diagonal;        ///< by sample
  std::vector<size_t> start;                          ///< by sample: its first neighbour entry
  std::vector<unsigned> neighbour;                    ///< by entry
  std::vector<std::array<double, 3>> off;             ///< by entry
  std::vector<std::array<double, 3>> inverse;         ///< by sample: the diagonal block's inverse

  /// y = A x. On one thread: a product costs a few milliseconds for 10^5 samples, less than
  /// waking a team for each of the ~20 iterations on a busy machine.
  void multiply(const std::vector<double>& x, std::vector<double>& y) const {
    for (size_t v = 0; v < diagonal.size(); ++v) {
      const auto& d = diagonal[v];
      double yx = d[0] * x[2 * v] + d[1] * x[2 * v + 1], yy = d[1] * x[2 * v] + d[2] * x[2 * v + 1];
      for (size_t e = start[v]; e < start[v + 1]; ++e) {
        const auto& b = off[e];
        const unsigned j = neighbour[e];
        yx += b[0] * x[2 * j] + b[1] * x[2 * j + 1];
        yy += b[1] * x[2 * j] + b[2] * x[2 * j + 1];
      }
      y[2 * v] = yx, y[2 * v + 1] = yy;
    }
  }
  /// z = (block diagonal)^-1 r.
  void precondition(const std::vector<double>& r, std::vector<double>& z) const {
    for (size_t v = 0; v < inverse.size(); ++v) {
      const auto& m = inverse[v];
      z[2 * v] = m[0] * r[2 * v] + m[1] * r[2 * v + 1];
      z[2 * v + 1] = m[1] * r[2 * v] + m[2] * r[2 * v + 1];
    }
  }
};

double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0;
  for (size_t k = 0; k < a.size(); ++k) s += a[k] * b[k];
  return s;
}

/// Preconditioned conjugate gradients for A x = b from x = 0, until the preconditioned residual
/// is below kNielsonResidualRelative of b's (or after kMaxIterations: the rounding floor).
/// Sequential sums: the result does not depend on the thread count.
std::vector<double> solve(const BlockSystem& a, const std::vector<double>& b) {
  constexpr int kMaxIterations = 500;
  const size_t n = b.size();
  std::vector<double> x(n, 0.0), r = b, z(n), p(n), q(n);
  a.precondition(r, z);
  double rz = dot(r, z);
  const double stop = rz * tol::kNielsonResidualRelative * tol::kNielsonResidualRelative;
  p = z;
  for (int it = 0; it < kMaxIterations && rz > stop; ++it) {
    a.multiply(p, q);
    const double alpha = rz / dot(p, q);
    for (size_t k = 0; k < n; ++k) x[k] += alpha * p[k], r[k] -= alpha * q[k];
    a.precondition(r, z);
    const double rz_next = dot(r, z);
    const double beta = rz_next / rz;
    rz = rz_next;
    for (size_t k = 0; k < n; ++k) p[k] = z[k] + beta * p[k];
  }
  return x;
}

}  // namespace

void CloughTocher::estimate_gradients(const std::vector<double>& values) {
  // Along an edge from p_i to p_j (vector E, length L) the element is the cubic with values
  // f_i, f_j and end slopes g_i.E, g_j.E (per unit of the edge parameter s in [0, 1]); with
  // d1 = g_i.E and d2 = -g_j.E its curvature integral is
  //   L^3 int_E |W''|^2 = 4 d1^2 - 4 d1 d2 + 4 d2^2 + 12 (f_i - f_j)(d1 - d2) (+ a constant).
  // Setting the derivative of the sum over all edges to zero, for each sample i:
  //   sum_j [4 E E^T g_i + 2 E E^T g_j] / L^3 = -sum_j 6 (f_i - f_j) E / L^3.
  // Each edge adds [4 2; 2 4] (x) E E^T / L^3, whose eigenvalues 2 and 6 bound the matrix between
  // 1/2 and 3/2 times its block diagonal (4 E E^T / L^3 summed per sample, positive definite as
  // each sample's edges span the plane): conjugate gradients preconditioned by that block
  // diagonal converge by a factor (sqrt 3 - 1) / (sqrt 3 + 1) = 0.27 or better per iteration,
  // some 30 iterations to the rounding floor. The points are scaled by their extent h first
  // (gradients by 1/h after), so that 1/L^3 neither overflows nor underflows for any units; and
  // each channel's values by the power of two m at or above their largest magnitude (gradients
  // by m after; exact, and the equations are linear in the values), so that the solver's
  // squared residuals neither underflow (values of 1e-160 gave zero or NaN gradients) nor
  // overflow: the gradients scale with the values to rounding, bit for bit by a power of two.
  const std::vector<Vec2>& p = mesh_.points();
  const size_t n = p.size(), C = static_cast<size_t>(channels_);
  Vec2 lo = p[0], hi = p[0];
  for (const Vec2& q : p) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
  const double h = (hi - lo).maxCoeff();

  // The edges, each once: from the face of smaller index (or the only one, on the hull).
  std::vector<std::pair<unsigned, unsigned>> edges;
  edges.reserve(3 * mesh_.faces() / 2 + 3);
  for (size_t f = 0; f < mesh_.faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const std::int64_t nb = mesh_.neighbour(f, k);
      if (nb < 0 || static_cast<size_t>(nb) > f) edges.emplace_back(mesh_.face(f)[(k + 1) % 3], mesh_.face(f)[(k + 2) % 3]);
    }

  BlockSystem a;
  a.diagonal.assign(n, {0, 0, 0});
  a.start.assign(n + 1, 0);
  for (const auto& [i, j] : edges) ++a.start[i + 1], ++a.start[j + 1];
  for (size_t v = 0; v < n; ++v) a.start[v + 1] += a.start[v];
  a.neighbour.resize(2 * edges.size());
  a.off.resize(2 * edges.size());
  std::vector<size_t> fill(a.start.begin(), a.start.end() - 1);
  std::vector<std::vector<double>> rhs(C, std::vector<double>(2 * n, 0.0));
  std::vector<double> unit(C, 1.0);  // m per channel: a power of two
  for (size_t c = 0; c < C; ++c) {
    double largest = 0;
    for (size_t v = 0; v < n; ++v) largest = std::max(largest, std::abs(values[v * C + c]));
    if (largest > 0) unit[c] = std::ldexp(1.0, std::ilogb(largest) + 1);
  }
  for (const auto& [i, j] : edges) {
    const Vec2 e = (p[j] - p[i]) / h;
    const double len_sq = e.squaredNorm(), w = 1 / (len_sq * std::sqrt(len_sq));
    const std::array<double, 3> b = {w * e.x() * e.x(), w * e.x() * e.y(), w * e.y() * e.y()};
    for (const auto& [r, c] : {std::pair(i, j), std::pair(j, i)}) {
      for (int k = 0; k < 3; ++k) a.diagonal[r][k] += 4 * b[k];
      a.neighbour[fill[r]] = c;
      a.off[fill[r]++] = {2 * b[0], 2 * b[1], 2 * b[2]};
    }
    for (size_t c = 0; c < C; ++c) {
      const double s = -6 * (values[i * C + c] / unit[c] - values[j * C + c] / unit[c]) * w;
      for (const unsigned v : {i, j}) rhs[c][2 * v] += s * e.x(), rhs[c][2 * v + 1] += s * e.y();
    }
  }
  a.inverse.resize(n);
  for (size_t v = 0; v < n; ++v) {
    const auto& d = a.diagonal[v];
    const double det = d[0] * d[2] - d[1] * d[1];
    RR_CHECK(std::isfinite(det), "clough-tocher: a sample's gradient equations overflow");  // scaled by h: finite
    if (!(det > 0))  // its edges do not span the plane, to rounding
      throw ReconstructionError("clough-tocher: the edges of the triangulation at the sample at (" + format_number(p[v].x()) +
                                ", " + format_number(p[v].y()) + ") lie on one line to rounding, so its gradient cannot be "
                                "estimated (samples collinear up to rounding?); linear or natural-neighbour take them");
    a.inverse[v] = {d[2] / det, -d[1] / det, d[0] / det};
  }

  gradients_.assign(2 * n * C, 0.0);
  for (size_t c = 0; c < C; ++c) {  // one channel at a time: each channel's bits are its own
    const std::vector<double> g = solve(a, rhs[c]);
    for (size_t v = 0; v < n; ++v) {
      // Finite for any finite values and points the triangulation takes (the values' unit and
      // the points' extent are taken out): a failure here is a bug, not the input's.
      RR_CHECK(std::isfinite(g[2 * v]) && std::isfinite(g[2 * v + 1]), "clough-tocher: the estimated gradients are not finite");
      gradients_[(v * C + c) * 2] = g[2 * v] / h * unit[c];
      gradients_[(v * C + c) * 2 + 1] = g[2 * v + 1] / h * unit[c];
    }
  }
}

void CloughTocher::build_nets(const std::vector<double>& values) {
  const std::vector<Vec2>& p = mesh_.points();
  const size_t C = static_cast<size_t>(channels_), nf = mesh_.faces();
  net_.assign(nf * C * kPerFace, 0.0);
  parallel_for(0, static_cast<std::int64_t>(nf), [&](std::int64_t fi) {
    const size_t f = static_cast<size_t>(fi);
    const std::array<unsigned, 3>& v = mesh_.face(f);
    // The cross direction of each edge (opposite corner k), in the coordinates (b_i, b_j,
    // b_centroid) of its sub-triangle (they sum to 0): towards the neighbour's centroid C', whose
    // coordinates in this face are c, so that C' - C = (c_i - c_k) p_i + (c_j - c_k) p_j +
    // (3 c_k - 1) C; on the hull, from the edge's midpoint to the centroid.
    double dir[3][3];
    for (int k = 0; k < 3; ++k) {
      const std::int64_t nb = mesh_.neighbour(f, k);
      const int i = (k + 1) % 3, j = (k + 2) % 3;
      if (nb < 0) {
        dir[k][0] = -0.5, dir[k][1] = -0.5, dir[k][2] = 1;
        continue;
      }
      const std::array<unsigned, 3>& w = mesh_.face(static_cast<size_t>(nb));
      const Vec2 centroid = (p[w[0]] + p[w[1]] + p[w[2]]) / 3;
      const std::array<double, 3> c = mesh_.barycentric(f, centroid);
      dir[k][0] = c[i] - c[k], dir[k][1] = c[j] - c[k], dir[k][2] = 3 * c[k] - 1;  // the last < -1: c_k < 0
    }
    for (size_t ch = 0; ch < C; ++ch) {
      double value[3], edge[3][3], inner[3], mid[3], second[3];
      for (int i = 0; i < 3; ++i) value[i] = values[v[i] * C + ch];
      // edge[i][j]: the control point on edge i-j next to corner i (the tangent plane at p_i).
      for (int i = 0; i < 3; ++i) {
        const double gx = gradients_[(v[i] * C + ch) * 2], gy = gradients_[(v[i] * C + ch) * 2 + 1];
        for (int j = 0; j < 3; ++j) {
          if (j == i) continue;
          const Vec2 d = p[v[j]] - p[v[i]];
          edge[i][j] = value[i] + (gx * d.x() + gy * d.y()) / 3;
        }
      }
      // inner[i]: on the split edge p_i - centroid next to p_i, in the tangent plane at p_i (C1
      // across the split edge there: the centroid has coordinates (1/3, 1/3, 1/3)).
      for (int i = 0; i < 3; ++i) inner[i] = (value[i] + edge[i][(i + 1) % 3] + edge[i][(i + 2) % 3]) / 3;
      // mid[k]: the point 111 of sub-triangle k, set so that the cross derivative along the edge
      // (a quadratic with Bezier coefficients D0, D1, D2) is linear: D1 = (D0 + D2) / 2.
      for (int k = 0; k < 3; ++k) {
        const int i = (k + 1) % 3, j = (k + 2) % 3;
        const double ai = dir[k][0], aj = dir[k][1], ac = dir[k][2];
        const double d0 = ai * value[i] + aj * edge[i][j] + ac * inner[i];
        const double d2 = ai * edge[j][i] + aj * value[j] + ac * inner[j];
        mid[k] = (0.5 * (d0 + d2) - ai * edge[i][j] - aj * edge[j][i]) / ac;
      }
      // second[i]: on the split edge next to the centroid; then the centroid (C1 across the
      // split edges in the second and third rows).
      for (int i = 0; i < 3; ++i) second[i] = (inner[i] + mid[(i + 1) % 3] + mid[(i + 2) % 3]) / 3;
      const double centre = (second[0] + second[1] + second[2]) / 3;
      double* out = &net_[(f * C + ch) * kPerFace];
      for (int k = 0; k < 3; ++k) {
        const int i = (k + 1) % 3, j = (k + 2) % 3;
        const double sub[kPerSubTriangle] = {value[i], edge[i][j], edge[j][i], value[j], inner[i],
                                             mid[k],   inner[j],   second[i],  second[j], centre};
        std::copy(sub, sub + kPerSubTriangle, out + k * kPerSubTriangle);
      }
    }
  });
}

void CloughTocher::evaluate(std::span<const Vec2> points, std::span<double> out) const {
  const size_t C = static_cast<size_t>(channels_);
  mesh_.evaluate(points, out, channels_, outside_, [&](const DelaunayMesh::Location& loc, double* o) {
    // The sub-triangle opposite the corner of smallest coordinate, and q's coordinates there.
    const std::array<double, 3>& b = loc.b;
    const int k = b[1] < b[0] ? (b[2] < b[1] ? 2 : 1) : (b[2] < b[0] ? 2 : 0);
    const double u = b[(k + 1) % 3] - b[k], v = b[(k + 2) % 3] - b[k], w = 3 * b[k];
    const double uu = u * u, vv = v * v, ww = w * w;
    const double t[kPerSubTriangle] = {uu * u,     3 * uu * v,     3 * u * vv, vv * v,     3 * uu * w,
                                       6 * u * v * w, 3 * vv * w, 3 * u * ww, 3 * v * ww, ww * w};
    const double* net = &net_[(static_cast<size_t>(loc.face) * C) * kPerFace + static_cast<size_t>(k) * kPerSubTriangle];
    for (size_t c = 0; c < C; ++c, net += kPerFace) {
      double s = 0;
      for (int m = 0; m < kPerSubTriangle; ++m) s += t[m] * net[m];
      o[c] = s;
    }
  });
}

}  // namespace radrecon
