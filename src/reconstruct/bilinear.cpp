#include "reconstruct/bilinear.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/check.h"

namespace radrecon {

Bilinear::Bilinear(GridNodes nodes) : nodes_(std::move(nodes)) {
  RR_CHECK(nodes_.nx >= 2 && nodes_.ny >= 2, "bilinear interpolation needs at least 2 x 2 nodes");
  RR_CHECK(nodes_.dx > 0 && nodes_.dy > 0, "grid spacing must be positive");
  RR_CHECK(nodes_.values.size() == static_cast<size_t>(nodes_.nx) * nodes_.ny * nodes_.channels,
           "nodal values do not match the grid");
}

void Bilinear::evaluate(std::span<const Vec2> points, std::span<double> out) const {
  const int C = nodes_.channels;
  RR_CHECK(out.size() == points.size() * C, "output size does not match the query points");
  for (size_t k = 0; k < points.size(); ++k) {
    const Vec2& q = points[k];
    if (!q.allFinite()) {
      for (int c = 0; c < C; ++c) out[k * C + c] = std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    const double gx = std::clamp((q.x() - nodes_.x0) / nodes_.dx, 0.0, double(nodes_.nx - 1));
    const double gy = std::clamp((q.y() - nodes_.y0) / nodes_.dy, 0.0, double(nodes_.ny - 1));
    const int i = std::min(static_cast<int>(gx), nodes_.nx - 2);
    const int j = std::min(static_cast<int>(gy), nodes_.ny - 2);
    const double u = gx - i, v = gy - j;
    const double* b00 = &nodes_.values[(static_cast<size_t>(j) * nodes_.nx + i) * C];
    const double* b10 = b00 + C;
    const double* b01 = b00 + static_cast<size_t>(nodes_.nx) * C;
    const double* b11 = b01 + C;
    for (int c = 0; c < C; ++c)
      out[k * C + c] = (1 - u) * (1 - v) * b00[c] + u * (1 - v) * b10[c] + u * v * b11[c] + (1 - u) * v * b01[c];
  }
}

}  // namespace radrecon
