#include "reconstruct/bicubic.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/check.h"

namespace radrecon {

void natural_spline_second_derivatives(const double* y, double* m, int n, double h, size_t stride) {
  m[0] = 0;
  m[(n - 1) * stride] = 0;
  if (n < 3) return;
  // Thomas algorithm on the (n-2) x (n-2) system with diagonal 4 and off-diagonals 1.
  std::vector<double> c(static_cast<size_t>(n)), d(static_cast<size_t>(n));
  const double scale = 6.0 / (h * h);
  for (int i = 1; i < n - 1; ++i) {
    const double rhs = scale * (y[(i - 1) * stride] - 2 * y[i * stride] + y[(i + 1) * stride]);
    const double denom = 4.0 - (i > 1 ? c[static_cast<size_t>(i - 1)] : 0.0);
    c[static_cast<size_t>(i)] = 1.0 / denom;
    d[static_cast<size_t>(i)] = (rhs - (i > 1 ? d[static_cast<size_t>(i - 1)] : 0.0)) / denom;
  }
  m[(n - 2) * stride] = d[static_cast<size_t>(n - 2)];
  for (int i = n - 3; i >= 1; --i) m[i * stride] = d[static_cast<size_t>(i)] - c[static_cast<size_t>(i)] * m[(i + 1) * stride];
}

Bicubic::Bicubic(GridNodes nodes) : nodes_(std::move(nodes)) {
  RR_CHECK(nodes_.nx >= 2 && nodes_.ny >= 2, "bicubic interpolation needs at least 2 x 2 nodes");
  RR_CHECK(nodes_.dx > 0 && nodes_.dy > 0, "grid spacing must be positive");
  const int nx = nodes_.nx, ny = nodes_.ny, C = nodes_.channels;
  RR_CHECK(nodes_.values.size() == static_cast<size_t>(nx) * ny * C, "nodal values do not match the grid");
  const size_t size = nodes_.values.size();
  fxx_.assign(size, 0.0);
  fyy_.assign(size, 0.0);
  fxxyy_.assign(size, 0.0);
  const size_t row = static_cast<size_t>(nx) * C;
  for (int c = 0; c < C; ++c) {
    for (int j = 0; j < ny; ++j)  // along x, every row
      natural_spline_second_derivatives(&nodes_.values[j * row + c], &fxx_[j * row + c], nx, nodes_.dx, C);
    for (int i = 0; i < nx; ++i) {  // along y, every column, of the values and of f_xx
      natural_spline_second_derivatives(&nodes_.values[static_cast<size_t>(i) * C + c], &fyy_[static_cast<size_t>(i) * C + c], ny,
                                        nodes_.dy, row);
      natural_spline_second_derivatives(&fxx_[static_cast<size_t>(i) * C + c], &fxxyy_[static_cast<size_t>(i) * C + c], ny,
                                        nodes_.dy, row);
    }
  }
}

void Bicubic::evaluate(std::span<const Vec2> points, std::span<double> out) const {
  const int C = nodes_.channels, nx = nodes_.nx, ny = nodes_.ny;
  RR_CHECK(out.size() == points.size() * static_cast<size_t>(C), "output size does not match the query points");
  const double hx = nodes_.dx, hy = nodes_.dy;
  for (size_t k = 0; k < points.size(); ++k) {
    const Vec2& q = points[k];
    if (!q.allFinite()) {
      for (int c = 0; c < C; ++c) out[k * C + c] = std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    const double gx = std::clamp((q.x() - nodes_.x0) / hx, 0.0, double(nx - 1));
    const double gy = std::clamp((q.y() - nodes_.y0) / hy, 0.0, double(ny - 1));
    const int i = std::min(static_cast<int>(gx), nx - 2), j = std::min(static_cast<int>(gy), ny - 2);
    // Cubic spline weights in "moment" form (Numerical Recipes eq. 3.3.3): along x
    // S = A f_i + B f_i+1 + Ca M_i + Cb M_i+1, and likewise along y.
    const double bx = gx - i, ax = 1 - bx, by = gy - j, ay = 1 - by;
    const double wx[4] = {ax, bx, (ax * ax * ax - ax) * hx * hx / 6, (bx * bx * bx - bx) * hx * hx / 6};
    const double wy[4] = {ay, by, (ay * ay * ay - ay) * hy * hy / 6, (by * by * by - by) * hy * hy / 6};
    const size_t n00 = (static_cast<size_t>(j) * nx + i) * C, n10 = n00 + C, n01 = n00 + static_cast<size_t>(nx) * C,
                 n11 = n01 + C;
    for (int c = 0; c < C; ++c) {
      // Values and x-moments at the two rows, then combined along y with the y-moments.
      auto along_x = [&](const std::vector<double>& f, const std::vector<double>& fxx, size_t a, size_t b) {
        return wx[0] * f[a + c] + wx[1] * f[b + c] + wx[2] * fxx[a + c] + wx[3] * fxx[b + c];
      };
      const double row0 = along_x(nodes_.values, fxx_, n00, n10), row1 = along_x(nodes_.values, fxx_, n01, n11);
      const double mom0 = along_x(fyy_, fxxyy_, n00, n10), mom1 = along_x(fyy_, fxxyy_, n01, n11);
      out[k * C + c] = wy[0] * row0 + wy[1] * row1 + wy[2] * mom0 + wy[3] * mom1;
    }
  }
}

}  // namespace radrecon
