#include "reconstruct/sample_set.h"

#include <algorithm>
#include <numeric>
#include <utility>
#include <string>
#include <cmath>
#include <cstdio>

#include "core/check.h"
#include "core/error.h"
#include "core/parse.h"
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
  a.tol = std::max(tol::kGridCoordinateRelative * (a.hi - a.lo),
                   tol::kCoordinateRounding * std::max(std::abs(a.lo), std::abs(a.hi)));
  a.distinct = distinct_values(std::move(v), a.tol);
  return a;
}
}  // namespace

Result<std::size_t> merge_duplicate_points(ScatteredSamples& s, const Barriers& barriers, const std::string& array_name) {
  const size_t n = s.points.size(), ch = static_cast<size_t>(s.channels);
  RR_CHECK(s.values.size() == n * ch, "sample values do not match the points");
  if (n < 2) return 0;
  Vec2 lo = s.points[0], hi = lo;
  for (const Vec2& p : s.points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double eps = tol::kNearDuplicateRelative * (hi - lo).maxCoeff();
  // Sorted by x: the points within eps of a point follow it within eps in x. (The groups below
  // are the components of "within eps", whatever the order among equal x; the pairs sort
  // without reaching back into the points.)
  std::vector<std::pair<double, size_t>> by_x(n);
  for (size_t k = 0; k < n; ++k) by_x[k] = {s.points[k].x(), k};
  std::sort(by_x.begin(), by_x.end());
  // Union-find, the root of a group its first sample.
  std::vector<size_t> root(n);
  std::iota(root.begin(), root.end(), size_t{0});
  const auto find = [&](size_t k) {
    while (root[k] != k) k = root[k] = root[root[k]];
    return k;
  };
  for (size_t a = 0; a < n; ++a)
    for (size_t b = a + 1; b < n && by_x[b].first - by_x[a].first <= eps; ++b)
      if ((s.points[by_x[b].second] - s.points[by_x[a].second]).norm() <= eps) {
        const size_t ra = find(by_x[a].second), rb = find(by_x[b].second);
        if (ra != rb) root[std::max(ra, rb)] = std::min(ra, rb);
      }
  std::vector<size_t> rep(n);
  size_t removed = 0;
  for (size_t k = 0; k < n; ++k) {
    rep[k] = find(k);
    if (rep[k] != k) ++removed;
  }
  if (removed == 0) return 0;
  if (!barriers.empty()) {
    // Any two of a group (not only the pairs that joined it: a chain through a sample on the
    // barrier joins its two sides) that a barrier parts.
    std::vector<size_t> by_group(n);
    std::iota(by_group.begin(), by_group.end(), size_t{0});
    std::stable_sort(by_group.begin(), by_group.end(), [&](size_t a, size_t b) { return rep[a] < rep[b]; });
    for (size_t first = 0, end = 0; first < n; first = end) {
      for (end = first + 1; end < n && rep[by_group[end]] == rep[by_group[first]];) ++end;
      for (size_t a = first; a < end; ++a)
        for (size_t b = a + 1; b < end; ++b) {
          const size_t i = by_group[a], j = by_group[b];
          if (!barriers.blocks(s.points[i], s.points[j])) continue;
          const auto at = [&](size_t k) {
            return "(" + format_number(s.points[k].x()) + ", " + format_number(s.points[k].y()) + ")";
          };
          char within[32];
          std::snprintf(within, sizeof within, "%.3g", eps);
          const std::string named =
              array_name.empty() ? "samples " + std::to_string(i + 1) + " and " + std::to_string(j + 1) + " (in the order read)"
                                 : array_name + "[" + std::to_string(i) + "] and " + array_name + "[" + std::to_string(j) + "]";
          return Failure{named + ", at " + at(i) + " and " + at(j) + ", lie on either side of a barrier within " + within +
                         " of each other (1e-9 of the samples' extent), where samples are merged: merged, their mean "
                         "would be seen from both sides; move them apart or leave one out"};
        }
    }
  }

  // A group's point: the mean of its points (the first, when they are all the same point); its
  // values: their mean. A linear function stays linear.
  std::vector<double> sum(n * ch, 0.0);
  std::vector<Vec2> centre(n, Vec2::Zero());
  std::vector<size_t> count(n, 0);
  std::vector<bool> same(n, true);
  for (size_t k = 0; k < n; ++k) {
    const size_t r = rep[k];
    ++count[r];
    centre[r] += s.points[k];
    same[r] = same[r] && s.points[k] == s.points[r];
    for (size_t c = 0; c < ch; ++c) sum[r * ch + c] += s.values[k * ch + c];
  }
  ScatteredSamples merged;  // slopes unknown (samples.h): a merged point's is no one sample's
  merged.channels = s.channels;
  for (size_t k = 0; k < n; ++k) {
    if (rep[k] != k) continue;
    merged.points.push_back(same[k] ? s.points[k] : Vec2(centre[k] / static_cast<double>(count[k])));
    for (size_t c = 0; c < ch; ++c) merged.values.push_back(sum[k * ch + c] / static_cast<double>(count[k]));
  }
  s = std::move(merged);
  return removed;
}

std::string merged_samples_message(std::size_t removed, std::size_t before, std::size_t after) {
  const bool one = removed == 1;
  return std::to_string(removed) + (one ? " sample repeats" : " samples repeat") + " the point of an earlier one (or " +
         (one ? "lies" : "lie") + " within 1e-9 of the samples' extent of it, or of a sample merged with it); merged, " +
         "their values averaged (" + std::to_string(before) + " samples -> " + std::to_string(after) + " points)";
}

// --- regular grids ----------------------------------------------------------------------------

DistinctCoordinates count_distinct_coordinates(const ScatteredSamples& samples) {
  const auto uneven = [](const Axis& a) {
    const size_t n = a.distinct.size();
    if (n < 2 || !(a.hi > a.lo)) return 0.0;
    const double d = (a.hi - a.lo) / static_cast<double>(n - 1);
    double most = 0;
    for (size_t i = 0; i < n; ++i) most = std::max(most, std::abs(a.distinct[i] - (a.lo + static_cast<double>(i) * d)));
    return most / (a.hi - a.lo);
  };
  const auto tolerance = [](const Axis& a) { return a.hi > a.lo ? a.tol / (a.hi - a.lo) : tol::kGridCoordinateRelative; };
  const Axis ax = axis_of(samples, 0), ay = axis_of(samples, 1);
  return {ax.distinct.size(), ay.distinct.size(), uneven(ax), uneven(ay), tolerance(ax), tolerance(ay)};
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

std::string rect_text(const Rect& r) {
  return "[" + format_number(r.x0) + ", " + format_number(r.y0) + ", " + format_number(r.x1) + ", " + format_number(r.y1) + "]";
}

Rect bounding_box(const ScatteredSamples& samples) {
  RR_CHECK(!samples.points.empty(), "the bounding box of no samples");
  Vec2 lo = samples.points[0], hi = lo;
  for (const Vec2& p : samples.points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  return {lo.x(), lo.y(), hi.x(), hi.y()};
}

std::string domain_apart(const Rect& domain, const ScatteredSamples& samples) {
  if (samples.points.empty()) return {};
  const Rect box = bounding_box(samples);
  if (!(domain.x0 > box.x1 || domain.x1 < box.x0 || domain.y0 > box.y1 || domain.y1 < box.y0)) return {};
  return "the domain " + rect_text(domain) + " does not meet the samples' bounding box " + rect_text(box);
}

void warn_if_domain_apart(const Rect& domain, const ScatteredSamples& samples) {
  if (const std::string apart = domain_apart(domain, samples); !apart.empty())
    warn(apart + ": every value there is extrapolated, or none (outside=none)");
}

}  // namespace radrecon
