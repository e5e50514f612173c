#pragma once
// Shared cases of the barrier tests: samples on both sides of a wall, walls, queries, and the
// brute-force visible set.

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "reconstruct/barriers.h"
#include "reconstruct/interpolant.h"
#include "reconstruct/samples.h"

namespace radrecon::testing_support {

/// Random samples on both sides of x = 0.5, values a step across it plus a slope.
inline ScatteredSamples two_sided_samples(double left_value, double right_value) {
  ScatteredSamples s;
  s.channels = 1;
  std::mt19937 rng(77);
  std::uniform_real_distribution<double> u(0, 1);
  for (int k = 0; k < 200; ++k) {
    const Vec2 p(u(rng), u(rng));
    if (std::abs(p.x() - 0.5) < 1e-3) continue;
    s.points.push_back(p);
    s.values.push_back((p.x() < 0.5 ? left_value : right_value) + 0.3 * p.y());
  }
  return s;
}

/// A wall across the whole domain (and beyond it), at x = 0.5.
inline Barriers wall() { return Barriers::from_polylines(std::vector<Polyline>{{{0.5, -1}, {0.5, 2}}}).value(); }

inline std::vector<Vec2> left_queries() {
  std::vector<Vec2> q;
  for (int j = 0; j < 30; ++j)
    for (int i = 0; i < 15; ++i) q.emplace_back(0.49 * i / 14.0, j / 29.0);
  return q;
}

inline std::vector<double> evaluate(const Interpolant& f, const std::vector<Vec2>& q) {
  std::vector<double> out(q.size() * static_cast<size_t>(f.channels()));
  f.evaluate(q, out);
  return out;
}

/// A wall from below the domain to y = 0.7 (light passes above it) and a corner.
inline Barriers wall_and_corner() {
  return Barriers::from_polylines(std::vector<Polyline>{{{0.5, -1}, {0.5, 0.7}}, {{0.2, 0.3}, {0.3, 0.3}, {0.3, 0.2}}})
      .value();
}

inline std::vector<Vec2> random_queries(unsigned seed, int count) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Vec2> q;
  for (int i = 0; i < count; ++i) q.emplace_back(u(rng), u(rng));
  return q;
}

/// Brute force: the samples visible from q (every barrier segment tested), by (squared
/// distance, index).
inline std::vector<std::pair<double, size_t>> visible_by_distance(const ScatteredSamples& s, const Barriers& barriers,
                                                           const Vec2& q) {
  std::vector<std::pair<double, size_t>> visible;
  for (size_t j = 0; j < s.points.size(); ++j) {
    bool hidden = false;
    for (const BarrierSegment& b : barriers.segments()) hidden = hidden || segment_blocked(q, s.points[j], b);
    if (!hidden) visible.emplace_back((s.points[j] - q).squaredNorm(), j);
  }
  std::sort(visible.begin(), visible.end());
  return visible;
}

/// The paper's ground as 16 x 16 cell centres over 4 m, two wall feet meeting in a corner at
/// (2.6, 2.6), darker on the walls' inner side (values 0.4..1.02); and 100 x 100 queries over it.
struct WallCornerGround {
  ScatteredSamples samples;
  std::vector<Polyline> walls = {{{2.6, 0.6}, {2.6, 2.6}}, {{0.6, 2.6}, {2.6, 2.6}}};
  std::vector<Vec2> queries;
};
inline WallCornerGround wall_corner_ground() {
  WallCornerGround g;
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i) {
      const Vec2 p(0.125 + 0.25 * i, 0.125 + 0.25 * j);
      const bool shade = p.x() < 2.6 && p.y() < 2.6;
      g.samples.points.push_back(p);
      g.samples.values.push_back(shade ? 0.4 + 0.05 * p.y() : 0.9 + 0.03 * p.x());
    }
  for (int j = 0; j < 100; ++j)
    for (int i = 0; i < 100; ++i) g.queries.emplace_back(0.02 + 0.04 * i, 0.02 + 0.04 * j);
  return g;
}

}  // namespace radrecon::testing_support
