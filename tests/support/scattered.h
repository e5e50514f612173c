#pragma once
// Helpers shared by the scattered-method tests: random samples with a fixed generator, and one
// interpolant evaluated at one point.

#include <random>
#include <span>
#include <vector>

#include "reconstruct/interpolant.h"
#include "reconstruct/samples.h"

namespace radrecon::testing {

/// n samples uniform in [lo, hi]^2 with values uniform in [-1, 1], drawn from rng.
inline ScatteredSamples random_samples(int n, std::mt19937& rng, double lo = 0, double hi = 4) {
  std::uniform_real_distribution<double> xy(lo, hi), value(-1, 1);
  ScatteredSamples s;
  for (int i = 0; i < n; ++i) {
    s.points.emplace_back(xy(rng), xy(rng));
    s.values.push_back(value(rng));
  }
  return s;
}

/// The first channel of f at q.
inline double eval1(const Interpolant& f, const Vec2& q) {
  std::vector<double> v(static_cast<size_t>(f.channels()));
  f.evaluate(std::span(&q, 1), v);
  return v[0];
}

}  // namespace radrecon::testing
