#include "reconstruct/hermite.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/check.h"
#include "core/parallel.h"

namespace radrecon {

void estimate_derivatives(const double* y, double* d, int n, double h, size_t stride) {
  RR_CHECK(n >= 2, "derivative estimates need at least 2 samples");
  auto at = [&](int k) { return y[static_cast<size_t>(k) * stride]; };
  if (n == 2) {
    d[0] = d[stride] = (at(1) - at(0)) / h;
    return;
  }
  d[0] = (-3 * at(0) + 4 * at(1) - at(2)) / (2 * h);
  for (int k = 1; k < n - 1; ++k) d[static_cast<size_t>(k) * stride] = (at(k + 1) - at(k - 1)) / (2 * h);
  d[static_cast<size_t>(n - 1) * stride] = (3 * at(n - 1) - 4 * at(n - 2) + at(n - 3)) / (2 * h);
}

Hermite::Hermite(GridNodes nodes) : nodes_(std::move(nodes)) {
  const int nx = nodes_.nx, ny = nodes_.ny, C = nodes_.channels;
  if (nx < 2 || ny < 2)
    throw ReconstructionError("hermite needs a grid of at least 2 x 2 samples, got " + std::to_string(nx) + " x " +
                              std::to_string(ny));
  if (!(nodes_.dx > 0 && nodes_.dy > 0) || !std::isfinite(nodes_.dx) || !std::isfinite(nodes_.dy) ||
      !std::isfinite(nodes_.x0) || !std::isfinite(nodes_.y0))
    throw ReconstructionError("hermite needs a grid with a finite origin and a positive, finite spacing");
  RR_CHECK(C >= 1, "no channels");
  RR_CHECK_EQ(nodes_.values.size(), static_cast<size_t>(nx) * ny * C, "nodal values do not match the grid");
  for (double v : nodes_.values)
    if (!std::isfinite(v)) throw ReconstructionError("hermite needs finite sample values");
  const size_t size = nodes_.values.size(), row = static_cast<size_t>(nx) * C;
  fx_.assign(size, 0.0);
  fy_.assign(size, 0.0);
  fxy_.assign(size, 0.0);
  for (int c = 0; c < C; ++c) {
    for (int j = 0; j < ny; ++j)  // f_x along every row
      estimate_derivatives(&nodes_.values[j * row + c], &fx_[j * row + c], nx, nodes_.dx, C);
    for (int i = 0; i < nx; ++i) {  // f_y and f_xy = d/dy f_x along every column
      const size_t col = static_cast<size_t>(i) * C + c;
      estimate_derivatives(&nodes_.values[col], &fy_[col], ny, nodes_.dy, row);
      estimate_derivatives(&fx_[col], &fxy_[col], ny, nodes_.dy, row);
    }
  }
}

namespace {

/// The cubic Hermite basis at t in [0, 1]: weights of p(0), p(1), h p'(0), h p'(1).
struct HermiteWeights {
  double v0, v1, d0, d1;
  explicit HermiteWeights(double t) {
    const double t2 = t * t, t3 = t2 * t;
    v0 = 2 * t3 - 3 * t2 + 1;
    v1 = 3 * t2 - 2 * t3;
    d0 = t3 - 2 * t2 + t;
    d1 = t3 - t2;
  }
};

}  // namespace

void Hermite::evaluate(std::span<const Vec2> points, std::span<double> out) const {
  const int C = nodes_.channels, nx = nodes_.nx, ny = nodes_.ny;
  RR_CHECK(out.size() == points.size() * static_cast<size_t>(C), "output size does not match the query points");
  const double hx = nodes_.dx, hy = nodes_.dy;
  parallel_for(0, static_cast<std::int64_t>(points.size()), [&](std::int64_t k) {
    const Vec2& q = points[static_cast<size_t>(k)];
    double* o = &out[static_cast<size_t>(k) * C];
    if (!q.allFinite()) {
      for (int c = 0; c < C; ++c) o[c] = std::numeric_limits<double>::quiet_NaN();
      return;
    }
    const double gx = std::clamp((q.x() - nodes_.x0) / hx, 0.0, double(nx - 1));
    const double gy = std::clamp((q.y() - nodes_.y0) / hy, 0.0, double(ny - 1));
    const int i = std::min(static_cast<int>(gx), nx - 2), j = std::min(static_cast<int>(gy), ny - 2);
    const HermiteWeights wx(gx - i), wy(gy - j);
    // Corner weights: value, h_x f_x, h_y f_y, h_x h_y f_xy, for corners 00, 10, 01, 11.
    const double ax[2] = {wx.v0, wx.v1}, bx[2] = {wx.d0 * hx, wx.d1 * hx};
    const double ay[2] = {wy.v0, wy.v1}, by[2] = {wy.d0 * hy, wy.d1 * hy};
    for (int c = 0; c < C; ++c) {
      double sum = 0;
      for (int b = 0; b < 2; ++b)
        for (int a = 0; a < 2; ++a) {
          const size_t n = index(i + a, j + b, c);
          sum += ax[a] * ay[b] * nodes_.values[n] + bx[a] * ay[b] * fx_[n] + ax[a] * by[b] * fy_[n] +
                 bx[a] * by[b] * fxy_[n];
        }
      o[c] = sum;
    }
  });
}

}  // namespace radrecon
