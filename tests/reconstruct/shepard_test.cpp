// Shepard's method: its defining properties and the k-nearest variant against brute force.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

#include "reconstruct/nearest.h"
#include "reconstruct/shepard.h"

namespace radrecon {
namespace shepard_test {

ScatteredSamples random_samples(int n, std::mt19937& rng, int channels = 1) {
  std::uniform_real_distribution<double> xy(0, 4), value(-1, 3);
  ScatteredSamples s;
  s.channels = channels;
  for (int i = 0; i < n; ++i) {
    s.points.emplace_back(xy(rng), xy(rng));
    for (int c = 0; c < channels; ++c) s.values.push_back(value(rng));
  }
  return s;
}

double eval1(const Interpolant& f, const Vec2& q) {
  double v;
  f.evaluate(std::span(&q, 1), std::span(&v, 1));
  return v;
}

TEST(Shepard, ExactAtTheSamples) {
  std::mt19937 rng(1);
  const ScatteredSamples s = random_samples(50, rng);
  for (int k : {0, 8}) {
    const Shepard f(s, 4, k);
    for (size_t i = 0; i < s.points.size(); ++i) EXPECT_EQ(eval1(f, s.points[i]), s.values[i]);
  }
}

TEST(Shepard, StaysWithinTheSampleRangeAndReproducesConstants) {
  std::mt19937 rng(2);
  ScatteredSamples s = random_samples(40, rng);
  const auto [lo, hi] = std::minmax_element(s.values.begin(), s.values.end());
  const Shepard f(s, 4, 0);
  std::uniform_real_distribution<double> xy(-1, 5);
  for (int k = 0; k < 500; ++k) {
    const double v = eval1(f, Vec2(xy(rng), xy(rng)));
    EXPECT_GE(v, *lo);
    EXPECT_LE(v, *hi);
  }
  std::fill(s.values.begin(), s.values.end(), 2.5);
  const Shepard c(s, 3, 0);
  for (int k = 0; k < 100; ++k) EXPECT_NEAR(eval1(c, Vec2(xy(rng), xy(rng))), 2.5, 1e-14);
}

TEST(Shepard, MatchesTheFormulaAndItsKNearestRestriction) {
  std::mt19937 rng(3);
  const ScatteredSamples s = random_samples(60, rng);
  std::uniform_real_distribution<double> xy(0, 4);
  for (int k : {0, 10}) {
    const Shepard f(s, 2.5, k);
    for (int t = 0; t < 100; ++t) {
      const Vec2 q(xy(rng), xy(rng));
      std::vector<size_t> order(s.points.size());
      std::iota(order.begin(), order.end(), 0);
      std::sort(order.begin(), order.end(),
                [&](size_t a, size_t b) { return (s.points[a] - q).norm() < (s.points[b] - q).norm(); });
      const size_t used = k ? static_cast<size_t>(k) : s.points.size();
      double num = 0, den = 0;
      for (size_t j = 0; j < used; ++j) {
        const double w = std::pow((s.points[order[j]] - q).norm(), -2.5);
        num += w * s.values[order[j]];
        den += w;
      }
      EXPECT_NEAR(eval1(f, q), num / den, 1e-12) << "k=" << k;
    }
  }
}

// The global method's paths against the formula in long double, relative to the nearest sample's
// weight, with sample counts that leave whole packet pairs, a packet and a masked tail: the one
// pass in SIMD packets (mu 2 and 4, up to 3 channels; pairs of packets share a division) where
// squared distances lie in [1e-60, 1e60] and values' magnitudes in [1e-150, 1e150] (scales up to
// 1e+-29 and 1e+-140: near those limits, some queries of 1e-29 beyond them), and the Eigen path
// with weights relative to the nearest sample's where they could overflow or underflow (1e+-45
// and beyond, 1e+-200).
TEST(Shepard, GlobalVectorPathMatchesTheFormulaAtEveryScale) {
  for (const double scale : {1.0, 1e-29, 1e29, 1e-45, 1e45, 1e-60, 1e60})
    for (const double value_scale : {1.0, 1e140, 1e-140, 1e200, 1e-200})
      for (const int n : {61, 64, 7})
        for (const int channels : {1, 3})
          for (const double mu : {2.0, 4.0}) {
            std::mt19937 rng(static_cast<unsigned>(n * 7 + channels));
            ScatteredSamples s = random_samples(n, rng, channels);
            for (Vec2& p : s.points) p *= scale;
            for (double& v : s.values) v *= value_scale;
            const Shepard f(s, mu, 0);
            std::uniform_real_distribution<double> xy(-0.5, 4.5);
            for (int t = 0; t < 40; ++t) {
              const Vec2 q = Vec2(xy(rng), xy(rng)) * scale;
              long double nearest = std::numeric_limits<long double>::infinity();
              for (const Vec2& p : s.points) nearest = std::min(nearest, static_cast<long double>((p - q).norm()));
              std::vector<long double> num(static_cast<size_t>(channels), 0.0L);
              long double den = 0;
              for (size_t i = 0; i < s.points.size(); ++i) {
                const long double w = std::pow(nearest / static_cast<long double>((s.points[i] - q).norm()), static_cast<long double>(mu));
                den += w;
                for (int c = 0; c < channels; ++c) num[static_cast<size_t>(c)] += w * s.values[i * static_cast<size_t>(channels) + c];
              }
              std::vector<double> got(static_cast<size_t>(channels));
              f.evaluate(std::span(&q, 1), got);
              for (int c = 0; c < channels; ++c)
                EXPECT_NEAR(got[static_cast<size_t>(c)], static_cast<double>(num[static_cast<size_t>(c)] / den), 1e-13 * value_scale)
                    << "scale " << scale << " values " << value_scale << " n " << n << " channels " << channels << " mu " << mu;
            }
          }
}

// Local Shepard finds its k nearest for a batch of queries at once, by tiles (kdtree.h
// CoherentNearest): a query's value must not depend on the batch it comes in. Bitwise: the raster
// at once (tiles of many queries, far ones included) against one query at a time.
TEST(Shepard, LocalValuesDoNotDependOnTheBatch) {
  std::mt19937 rng(17);
  const ScatteredSamples s = random_samples(2000, rng, 3);
  std::vector<Vec2> queries;
  for (int j = 0; j < 40; ++j)
    for (int i = 0; i < 40; ++i) queries.emplace_back(-1 + 6.0 * i / 39, -1 + 6.0 * j / 39);
  queries.emplace_back(300, -200);  // far from every sample: its tile may search the tree
  queries.emplace_back(-1e5, 2);
  for (const int k : {1, 12, 32}) {
    const Shepard f(s, 4, k);
    std::vector<double> together(queries.size() * 3), alone(3);
    f.evaluate(queries, together);
    for (size_t q = 0; q < queries.size(); ++q) {
      f.evaluate(std::span(&queries[q], 1), alone);
      for (int c = 0; c < 3; ++c) EXPECT_EQ(together[q * 3 + c], alone[c]) << "k=" << k << " query " << q << " channel " << c;
    }
  }
}

// gdal_grid's radius and min_points: only the samples within the radius count (of the k
// nearest, if k is set), and fewer than min_points of them give no value. Brute force here.
TEST(Shepard, SearchRadiusUsesExactlyTheSamplesWithinItAsBruteForce) {
  std::mt19937 rng(31);
  const ScatteredSamples s = random_samples(80, rng);
  std::uniform_real_distribution<double> xy(-1, 5);
  int some = 0, none = 0, too_few = 0;
  for (const int k : {0, 12})
    for (const int min_points : {1, 4}) {
      const double radius = 0.6;
      const Shepard f(s, 2, k, Barriers{}, radius, min_points);
      for (int t = 0; t < 300; ++t) {
        const Vec2 q(xy(rng), xy(rng));
        std::vector<size_t> order(s.points.size());
        std::iota(order.begin(), order.end(), 0);
        std::sort(order.begin(), order.end(),
                  [&](size_t a, size_t b) { return (s.points[a] - q).norm() < (s.points[b] - q).norm(); });
        const size_t candidates = k ? static_cast<size_t>(k) : s.points.size();
        double num = 0, den = 0;
        int within = 0;
        for (size_t j = 0; j < candidates; ++j) {
          const double d = (s.points[order[j]] - q).norm();
          if (d > radius) continue;
          ++within;
          num += s.values[order[j]] / (d * d);
          den += 1 / (d * d);
        }
        const double v = eval1(f, q);
        if (within < min_points) {
          EXPECT_TRUE(std::isnan(v)) << "k=" << k << " min_points=" << min_points << ": " << within << " within";
          (within == 0 ? none : too_few)++;
        } else {
          EXPECT_NEAR(v, num / den, 1e-12) << "k=" << k;
          ++some;
        }
      }
    }
  EXPECT_GT(some, 100);
  EXPECT_GT(none, 10);
  EXPECT_GT(too_few, 10);
}

TEST(Shepard, FastPathsForMu4AndMu2MatchTheFormulaWithPow) {
  // mu = 4 and mu = 2 skip pow() (squares and quotients of d^2, relative to the nearest sample's);
  // they must agree with sum d^-mu B / sum d^-mu, d^-mu by std::pow, on every path: global (one
  // pass in SIMD packets for up to 3 channels, Eigen arrays beyond) and k nearest (channels 0..2
  // and the rest apart), with 70 samples (not a multiple of the packets' 4 or 8 lanes). Positive values, so no
  // cancellation: each side rounds every weight and sums <= 70 positive terms, a few ulps each,
  // hence 1e-14 relative.
  constexpr double kRelative = 1e-14;
  double worst = 0;
  for (const int channels : {1, 3, 4}) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> xy(0, 4), value(0.5, 2);
    ScatteredSamples s;
    s.channels = channels;
    for (int i = 0; i < 70; ++i) {
      s.points.emplace_back(xy(rng), xy(rng));
      for (int c = 0; c < channels; ++c) s.values.push_back(value(rng));
    }
    std::uniform_real_distribution<double> around(-3, 7);  // inside and well outside the samples
    for (double mu : {4.0, 2.0}) {
      for (int k : {0, 1, 9, 69}) {
        const Shepard f(s, mu, k);
        for (int t = 0; t < 200; ++t) {
          const Vec2 q(around(rng), around(rng));
          std::vector<size_t> order(s.points.size());
          std::iota(order.begin(), order.end(), 0);
          std::sort(order.begin(), order.end(),
                    [&](size_t a, size_t b) { return (s.points[a] - q).norm() < (s.points[b] - q).norm(); });
          const size_t used = k ? static_cast<size_t>(k) : s.points.size();
          std::vector<double> got(static_cast<size_t>(channels));
          f.evaluate(std::span(&q, 1), std::span(got));
          for (int c = 0; c < channels; ++c) {
            double num = 0, den = 0;
            for (size_t j = 0; j < used; ++j) {
              const double w = std::pow((s.points[order[j]] - q).norm(), -mu);
              num += w * s.values[order[j] * channels + c];
              den += w;
            }
            const double expected = num / den, relative = std::abs(got[static_cast<size_t>(c)] - expected) / expected;
            worst = std::max(worst, relative);
            EXPECT_LE(relative, kRelative) << channels << " channels, mu=" << mu << " k=" << k << " channel " << c
                                           << ": got " << got[static_cast<size_t>(c)] << ", formula " << expected;
          }
        }
      }
    }
  }
  RecordProperty("worst_relative_error", ::testing::PrintToString(worst));
}

TEST(NearestSample, IsTheValueOfTheClosestSample) {
  std::mt19937 rng(4);
  const ScatteredSamples s = random_samples(80, rng, 2);
  const NearestSample f(s);
  std::uniform_real_distribution<double> xy(-1, 5);
  for (int t = 0; t < 200; ++t) {
    const Vec2 q(xy(rng), xy(rng));
    size_t best = 0;
    for (size_t i = 1; i < s.points.size(); ++i)
      if ((s.points[i] - q).squaredNorm() < (s.points[best] - q).squaredNorm()) best = i;
    double v[2];
    f.evaluate(std::span(&q, 1), std::span(v, 2));
    EXPECT_EQ(v[0], s.values[2 * best]);
    EXPECT_EQ(v[1], s.values[2 * best + 1]);
  }
}

}  // namespace shepard_test
}  // namespace radrecon
