#include "reconstruct/interpolant.h"

#include <vector>

#include "core/check.h"

namespace radrecon {

std::vector<Vec2> raster_points(const Raster& r) {
  std::vector<Vec2> points;
  raster_points(r, 0, static_cast<size_t>(r.width) * r.height, points);
  return points;
}

void raster_points(const Raster& r, size_t first, size_t count, std::vector<Vec2>& out) {
  RR_CHECK(r.width > 0 && r.height > 0, "raster size must be positive");
  RR_CHECK(first + count <= static_cast<size_t>(r.width) * r.height, "raster points out of range");
  out.resize(count);
  const size_t w = static_cast<size_t>(r.width);
  size_t i = first % w, j = first / w;  // the cell of point `first`, then row by row
  for (size_t k = 0; k < count; ++k) {
    out[k] = r.point(i, j);
    if (++i == w) i = 0, ++j;
  }
}

void Interpolant::evaluate_raster(const Raster& raster, size_t first, size_t count, std::span<double> out) const {
  std::vector<Vec2> points;
  raster_points(raster, first, count, points);
  evaluate(points, out);
}

}  // namespace radrecon
