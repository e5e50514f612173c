#include "reconstruct/sample_set.h"

#include <algorithm>
#include <cmath>

#include "core/check.h"
#include "core/tolerances.h"

namespace radrecon {

namespace {

// --- grid detection ---------------------------------------------------------------------------

/// The sorted distinct values of `v`, values within `tol` of the previous distinct one merged.
std::vector<double> distinct_values(std::vector<double> v, double tol) {
  std::sort(v.begin(), v.end());
  std::vector<double> out;
  for (double x : v)
    if (out.empty() || x - out.back() > tol) out.push_back(x);
  return out;
}


struct Axis {
  double lo = 0, hi = 0, tol = 0;
  std::vector<double> distinct;
};

Axis axis_of(const ScatteredSamples& s, int dim) {
  Axis a;
  std::vector<double> v(s.points.size());
  for (size_t k = 0; k < v.size(); ++k) v[k] = s.points[k][dim];
  if (v.empty()) return a;
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  a.lo = *lo;
  a.hi = *hi;
  a.tol = tol::kGridCoordinateRelative * (a.hi - a.lo);
  a.distinct = distinct_values(std::move(v), a.tol);
  return a;
}
}  // namespace

std::size_t merge_duplicate_points(ScatteredSamples& s) {
  const size_t n = s.points.size(), ch = static_cast<size_t>(s.channels);
  RR_CHECK(s.values.size() == n * ch, "sample values do not match the points");
  // Sorted by (x, y, index): equal points are adjacent, the first of them first.
  struct Key {
    double x, y;
    size_t index;
  };
  std::vector<Key> keys(n);
  for (size_t k = 0; k < n; ++k) keys[k] = {s.points[k].x(), s.points[k].y(), k};
  std::sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) {
    if (a.x != b.x) return a.x < b.x;
    if (a.y != b.y) return a.y < b.y;
    return a.index < b.index;
  });
  // rep[k]: the first sample at sample k's point.
  std::vector<size_t> rep(n);
  size_t removed = 0;
  for (size_t a = 0; a < n;) {
    size_t b = a + 1;
    while (b < n && keys[b].x == keys[a].x && keys[b].y == keys[a].y) ++b;
    for (size_t k = a; k < b; ++k) rep[keys[k].index] = keys[a].index;
    removed += b - a - 1;
    a = b;
  }
  if (removed == 0) return 0;

  std::vector<double> sum(n * ch, 0.0);
  std::vector<size_t> count(n, 0);
  for (size_t k = 0; k < n; ++k) {
    ++count[rep[k]];
    for (size_t c = 0; c < ch; ++c) sum[rep[k] * ch + c] += s.values[k * ch + c];
  }
  ScatteredSamples merged;
  merged.channels = s.channels;
  for (size_t k = 0; k < n; ++k) {
    if (rep[k] != k) continue;
    merged.points.push_back(s.points[k]);
    for (size_t c = 0; c < ch; ++c) merged.values.push_back(sum[k * ch + c] / static_cast<double>(count[k]));
  }
  s = std::move(merged);
  return removed;
}

// --- regular grids ----------------------------------------------------------------------------

DistinctCoordinates count_distinct_coordinates(const ScatteredSamples& samples) {
  return {axis_of(samples, 0).distinct.size(), axis_of(samples, 1).distinct.size()};
}

std::optional<GridNodes> as_regular_grid(const ScatteredSamples& s) {
  const Axis ax = axis_of(s, 0), ay = axis_of(s, 1);
  const size_t nx = ax.distinct.size(), ny = ay.distinct.size();
  if (nx < 2 || ny < 2 || nx * ny != s.points.size()) return std::nullopt;
  const double dx = (ax.hi - ax.lo) / static_cast<double>(nx - 1);
  const double dy = (ay.hi - ay.lo) / static_cast<double>(ny - 1);
  // The index of coordinate v on an axis, or -1 when v is not within tolerance of a node.
  const auto index = [](double v, double lo, double d, size_t count, double tol) -> long {
    const long i = std::lround((v - lo) / d);
    if (i < 0 || i >= static_cast<long>(count)) return -1;
    return std::abs(v - (lo + static_cast<double>(i) * d)) <= tol ? i : -1;
  };
  const size_t ch = static_cast<size_t>(s.channels);
  GridNodes g;
  g.nx = static_cast<int>(nx);
  g.ny = static_cast<int>(ny);
  g.x0 = ax.lo;
  g.y0 = ay.lo;
  g.dx = dx;
  g.dy = dy;
  g.channels = s.channels;
  g.values.assign(nx * ny * ch, 0.0);
  std::vector<char> seen(nx * ny, 0);
  for (size_t k = 0; k < s.points.size(); ++k) {
    const long i = index(s.points[k].x(), ax.lo, dx, nx, ax.tol);
    const long j = index(s.points[k].y(), ay.lo, dy, ny, ay.tol);
    if (i < 0 || j < 0) return std::nullopt;
    const size_t node = static_cast<size_t>(j) * nx + static_cast<size_t>(i);
    if (seen[node]) return std::nullopt;
    seen[node] = 1;
    for (size_t c = 0; c < ch; ++c) g.values[node * ch + c] = s.values[k * ch + c];
  }
  return g;  // nx * ny samples, none twice: every node is present
}

}  // namespace radrecon
