#include "reconstruct/clough_tocher.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "core/check.h"
#include "core/parallel.h"

namespace radrecon {

CloughTocher::CloughTocher(const ScatteredSamples& samples, OutsideHull outside, std::span<const double> gradients)
    : mesh_(samples.points, "clough-tocher"), channels_(samples.channels), outside_(outside) {
  RR_CHECK(samples.values.size() == samples.points.size() * static_cast<size_t>(channels_),
           "sample values do not match the points");
  if (gradients.empty()) {
    estimate_gradients(samples.values);
  } else {
    RR_CHECK(gradients.size() == 2 * samples.values.size(), "gradients do not match the samples");
    gradients_.assign(gradients.begin(), gradients.end());
  }
  build_nets(samples.values);
}

void CloughTocher::estimate_gradients(const std::vector<double>& values) {
  // Along an edge from p_i to p_j (vector E, length L) the element is the cubic with values
  // f_i, f_j and end slopes g_i.E, g_j.E (per unit of the edge parameter s in [0, 1]); with
  // d1 = g_i.E and d2 = -g_j.E its curvature integral is
  //   L^3 int_E |W''|^2 = 4 d1^2 - 4 d1 d2 + 4 d2^2 + 12 (f_i - f_j)(d1 - d2) (+ a constant).
  // Setting the derivative of the sum over all edges to zero, for each sample i:
  //   sum_j [4 E E^T g_i + 2 E E^T g_j] / L^3 = -sum_j 6 (f_i - f_j) E / L^3,
  // symmetric positive definite (each sample's edges span the plane). The points are scaled by
  // their extent h first (gradients by 1/h after), so that 1/L^3 neither overflows nor
  // underflows for any units.
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

  std::vector<double> diag(3 * n, 0.0);  // per sample: xx, xy, yy of sum 4 E E^T / L^3
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(8 * edges.size() + 4 * n);
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(2 * n), static_cast<Eigen::Index>(C));
  for (const auto& [i, j] : edges) {
    const Vec2 e = (p[j] - p[i]) / h;
    const double len_sq = e.squaredNorm(), w = 1 / (len_sq * std::sqrt(len_sq));
    const double xx = w * e.x() * e.x(), xy = w * e.x() * e.y(), yy = w * e.y() * e.y();
    for (const unsigned v : {i, j}) {
      diag[3 * v] += 4 * xx, diag[3 * v + 1] += 4 * xy, diag[3 * v + 2] += 4 * yy;
    }
    for (const auto& [r, c] : {std::pair(i, j), std::pair(j, i)}) {
      entries.emplace_back(2 * r, 2 * c, 2 * xx);
      entries.emplace_back(2 * r, 2 * c + 1, 2 * xy);
      entries.emplace_back(2 * r + 1, 2 * c, 2 * xy);
      entries.emplace_back(2 * r + 1, 2 * c + 1, 2 * yy);
    }
    for (size_t c = 0; c < C; ++c) {
      const double s = -6 * (values[i * C + c] - values[j * C + c]) * w;
      for (const unsigned v : {i, j}) {
        rhs(2 * v, static_cast<Eigen::Index>(c)) += s * e.x();
        rhs(2 * v + 1, static_cast<Eigen::Index>(c)) += s * e.y();
      }
    }
  }
  for (size_t v = 0; v < n; ++v) {
    const int r = static_cast<int>(2 * v);
    entries.emplace_back(r, r, diag[3 * v]);
    entries.emplace_back(r, r + 1, diag[3 * v + 1]);
    entries.emplace_back(r + 1, r, diag[3 * v + 1]);
    entries.emplace_back(r + 1, r + 1, diag[3 * v + 2]);
  }
  Eigen::SparseMatrix<double> a(static_cast<Eigen::Index>(2 * n), static_cast<Eigen::Index>(2 * n));
  a.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(a);
  if (solver.info() != Eigen::Success)
    throw ReconstructionError("clough-tocher: the gradient system could not be factorised (samples too close together?)");

  gradients_.assign(2 * n * C, 0.0);
  for (size_t c = 0; c < C; ++c) {  // one channel at a time: each channel's bits are its own
    const Eigen::VectorXd g = solver.solve(rhs.col(static_cast<Eigen::Index>(c)));
    if (!g.allFinite()) throw ReconstructionError("clough-tocher: the estimated gradients are not finite");
    for (size_t v = 0; v < n; ++v) {
      gradients_[(v * C + c) * 2] = g[static_cast<Eigen::Index>(2 * v)] / h;
      gradients_[(v * C + c) * 2 + 1] = g[static_cast<Eigen::Index>(2 * v + 1)] / h;
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
