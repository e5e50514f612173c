// The contract every reconstruction method keeps, checked over all of them (after pbrt's
// filters_test.cpp): each Method of all_methods() with its parameter variants, built by the
// factories from a regular node grid (make_nodal_interpolant: every method) and from scattered
// samples (make_scattered_interpolant: every method that takes them). A new method, or a new
// variant in cases(), gets the whole contract:
//   exact at the samples; reproduces constants; a NaN query gives NaN; channels are independent;
//   a batch equals one point at a time; 1 and 2 threads agree bit for bit. Every method is also
//   run with barriers.

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "core/thread_pool.h"
#include "reconstruct/methods.h"
#include "reconstruct/local_multiquadric.h"
#include "reconstruct/multiquadric.h"

namespace radrecon {
namespace contract_test {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Reproducing a constant costs rounding only, for a method whose value is a weighted mean of
/// the samples' (weights summing to one up to a few ulps) or a copy of one.
constexpr double kRoundingRelative = 1e-14;

/// Hardy's multiquadric has no polynomial term, so it does not reproduce constants: the
/// interpolant of c is c sum_j alpha_j phi_j with sum_j alpha_j phi_j(p_i) = 1 at the samples
/// only, and nothing pulls it back to 1 between them; outside the samples' hull it drifts away
/// as phi grows (measured: 30-60% at 0.3 box widths out, so not checked there). Inside the hull
/// the deviation depends on the spacing and on r and mu; measured on these data sets: global
/// systems <= 0.049 (mu = -0.5; 0.007 for the default). The bound leaves a factor of about two.
/// The local patches fit the deviations from their samples' mean, so they reproduce constants.
constexpr double kGlobalMultiquadricConstantRelative = 0.1;

/// A method with one setting of its parameters, and what it promises beyond the common contract.
struct Case {
  std::string name;
  Method method;
  MethodParams params;
  /// Largest relative deviation from a constant inside the samples' hull.
  double constant_relative = kRoundingRelative;
};

/// Every method with its default parameters, plus the variants that take other code paths.
std::vector<Case> cases() {
  std::vector<Case> out;
  for (Method m : all_methods()) {
    Case c{method_name(m), m, {}};
    switch (m) {
      case Method::shepard:
        out.push_back(c);
        c.params.shepard_mu = 2;  // the other pow()-free weight
        c.name = "shepard mu=2";
        out.push_back(c);
        c.params.shepard_mu = 2.5;  // pow()
        c.name = "shepard mu=2.5";
        out.push_back(c);
        c.params = {};
        c.params.shepard_k = 12;  // k nearest (k-d tree), mu = 4
        c.name = "shepard k=12";
        out.push_back(c);
        c.params.shepard_mu = 2;
        c.params.shepard_k = 7;
        c.name = "shepard mu=2 k=7";
        out.push_back(c);
        break;
      case Method::multiquadric:
        c.constant_relative = kGlobalMultiquadricConstantRelative;
        out.push_back(c);
        c.params.multiquadric_mu = -0.5;  // inverse multiquadric
        c.name = "multiquadric mu=-0.5";
        out.push_back(c);
        c.params.multiquadric_mu = 1.5;  // pow()
        c.name = "multiquadric mu=1.5";
        out.push_back(c);
        c.params = {};
        c.params.multiquadric_r = 0.1;  // one radius for all instead of Eck's
        c.name = "multiquadric r=0.1";
        out.push_back(c);
        c.params = {};
        c.params.multiquadric_k = 24;  // a partition of unity of local patches
        c.constant_relative = kRoundingRelative;  // each patch fits the deviations from its mean
        c.name = "multiquadric k=24";
        out.push_back(c);
        c.params.multiquadric_mu = -0.5;
        c.name = "multiquadric mu=-0.5 k=24";
        out.push_back(c);
        c.params = {};
        c.params.multiquadric_poly = 1;  // a linear polynomial: constants are reproduced
        c.constant_relative = kRoundingRelative;
        c.name = "multiquadric poly=1";
        out.push_back(c);
        c.params.multiquadric_k = 24;
        c.name = "multiquadric poly=1 k=24";
        out.push_back(c);
        break;
      case Method::thin_plate:
        out.push_back(c);  // always with the linear polynomial: constants are reproduced
        c.params.thin_plate_k = 24;
        c.name = "thin-plate k=24";
        out.push_back(c);
        break;
      case Method::natural_neighbour:
        out.push_back(c);                 // outside = nearest, the default
        c.params.outside = OutsideHull::none;
        c.name = "natural-neighbour outside=none";
        out.push_back(c);
        break;
      default:
        out.push_back(c);
        break;
    }
    // With barriers: an L-shaped wall with free ends inside both data sets' boxes, so that every
    // query sees some sample (visibility paths, local triangulations, subset systems).
    if (!takes_barriers(m)) continue;
    Case walled{method_name(m) + " with barriers", m, {}};
    walled.params.barriers =
        Barriers::from_polylines(std::vector<Polyline>{{{0.3, 0.6}, {1.3, 0.6}, {1.3, 1.9}}}).value();
    if (m == Method::multiquadric) walled.constant_relative = kGlobalMultiquadricConstantRelative;
    out.push_back(walled);
  }
  return out;
}

/// The reciprocal condition estimate of the linear system(s) `f` solved, or nothing.
std::optional<double> reciprocal_condition(const Interpolant& f) {
  if (const auto* g = dynamic_cast<const Multiquadric*>(&f)) return g->reciprocal_condition();
  if (const auto* g = dynamic_cast<const LocalMultiquadric*>(&f)) return g->reciprocal_condition();
  return std::nullopt;
}

/// Sample positions with values, as a node grid or as scattered points.
struct DataSet {
  std::string name;
  bool grid;
  GridNodes nodes;              ///< positions when grid (its values are unused)
  std::vector<Vec2> points;     ///< the sample positions, either way
  std::vector<double> values;   ///< points.size() * channels
  int channels = 3;
  Vec2 lo, hi;                  ///< the samples' bounding box
  Vec2 inner_lo, inner_hi;      ///< a box inside the samples' convex hull

  InterpolantResult build(const Case& c, const std::vector<double>& v, int channels_) const {
    if (grid) {
      GridNodes n = nodes;
      n.values = v;
      n.channels = channels_;
      return make_nodal_interpolant(c.method, n, c.params);
    }
    ScatteredSamples s;
    s.points = points;
    s.values = v;
    s.channels = channels_;
    return make_scattered_interpolant(c.method, s, c.params);
  }
  InterpolantResult build(const Case& c) const { return build(c, values, channels); }
};

std::vector<double> random_values(size_t n, std::mt19937& rng) {
  std::uniform_real_distribution<double> value(0.5, 2);  // radiosity-like: positive
  std::vector<double> v(n);
  for (double& x : v) x = value(rng);
  return v;
}

/// 9 x 7 nodes; dyadic spacing, so a node's grid coordinate (x - x0) / dx is an exact integer.
DataSet node_grid() {
  DataSet d;
  d.name = "node grid";
  d.grid = true;
  d.nodes.nx = 9;
  d.nodes.ny = 7;
  d.nodes.x0 = -1;
  d.nodes.y0 = 0.25;
  d.nodes.dx = 0.5;
  d.nodes.dy = 0.375;
  for (int j = 0; j < d.nodes.ny; ++j)
    for (int i = 0; i < d.nodes.nx; ++i) d.points.emplace_back(d.nodes.x0 + i * d.nodes.dx, d.nodes.y0 + j * d.nodes.dy);
  std::mt19937 rng(101);
  d.values = random_values(d.points.size() * 3, rng);
  d.lo = d.inner_lo = d.points.front();
  d.hi = d.inner_hi = d.points.back();
  return d;
}

/// A 10 x 10 lattice (ties and co-circular points everywhere) plus 150 random points.
DataSet scattered() {
  DataSet d;
  d.name = "scattered";
  d.grid = false;
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 10; ++i) d.points.emplace_back(0.125 + 0.25 * i, 0.125 + 0.25 * j);
  std::mt19937 rng(102);
  std::uniform_real_distribution<double> xy(0, 2.5);
  for (int k = 0; k < 150; ++k) d.points.emplace_back(xy(rng), xy(rng));
  d.values = random_values(d.points.size() * 3, rng);
  d.lo = d.hi = d.points[0];
  for (const Vec2& p : d.points) d.lo = d.lo.cwiseMin(p), d.hi = d.hi.cwiseMax(p);
  d.inner_lo = d.points.front();  // the lattice's corners are samples
  d.inner_hi = d.points[99];
  return d;
}

std::vector<DataSet> data_sets() { return {node_grid(), scattered()}; }

/// Query points over the samples' box and a margin around it (outside), the samples, midpoints
/// of neighbouring samples and lattice cell centres (on Delaunay edges, equidistant from several
/// samples), and NaN queries among them. More than 32768 + 512 points: natural-neighbour runs
/// its parallel loop over chunks of 64 queries, which goes parallel from 512 chunks on.
std::vector<Vec2> queries(const DataSet& d) {
  std::vector<Vec2> q;
  const Vec2 margin = 0.3 * (d.hi - d.lo);
  const Vec2 lo = d.lo - margin, hi = d.hi + margin;
  constexpr int kSide = 185;
  for (int j = 0; j < kSide; ++j)
    for (int i = 0; i < kSide; ++i)
      q.emplace_back(lo.x() + (hi.x() - lo.x()) * i / (kSide - 1), lo.y() + (hi.y() - lo.y()) * j / (kSide - 1));
  for (size_t i = 0; i < d.points.size(); ++i) {
    q.push_back(d.points[i]);
    if (i + 1 < d.points.size()) q.push_back(0.5 * (d.points[i] + d.points[i + 1]));
  }
  const Vec2 half = d.grid ? Vec2(0.5 * d.nodes.dx, 0.5 * d.nodes.dy) : Vec2(0.125, 0.125);
  for (size_t i = 0; i < d.points.size(); i += 3) q.push_back(d.points[i] + half);
  for (size_t i = 0; i < q.size(); i += 997) q[i] = Vec2(kNaN, q[i].y());
  q.emplace_back(kNaN, kNaN);
  q.emplace_back(0.5, kNaN);
  return q;
}

std::vector<double> evaluate(const Interpolant& f, std::span<const Vec2> q) {
  std::vector<double> out(q.size() * static_cast<size_t>(f.channels()));
  f.evaluate(q, out);
  return out;
}

/// Equal bit for bit (so +0 is not -0), any NaN matching any NaN.
bool same(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b) || (std::isnan(a) && std::isnan(b));
}

/// Runs `check` for every case on every data set it can be built from.
void for_each_case(const std::function<void(const Case&, const DataSet&)>& check) {
  for (const DataSet& d : data_sets())
    for (const Case& c : cases()) {
      if (!d.grid && is_grid_method(c.method)) continue;
      if (is_cell_method(c.method)) continue;  // cells, not points: gouraud_test.cpp
      SCOPED_TRACE(c.name + " on " + d.name);
      check(c, d);
    }
}

TEST(InterpolantContract, EveryMethodIsCovered) {
  for (Method m : all_methods()) {
    if (is_cell_method(m)) continue;
    int built = 0;
    for_each_case([&](const Case& c, const DataSet& d) {
      if (c.method != m) return;
      const auto f = d.build(c);
      EXPECT_TRUE(f.ok()) << f.reason();
      built += f.ok();
    });
    EXPECT_GE(built, 1) << method_name(m);
  }
}

TEST(InterpolantContract, ExactAtTheSamples) {
  for_each_case([](const Case& c, const DataSet& d) {
    const auto f = d.build(c).value();
    const std::vector<double> at = evaluate(*f, d.points);
    // A method that solves a linear system is exact up to the solve's rounding: partial-pivoting
    // LU is backward stable, its residual relative to the values grows like eps / rcond (measured
    // here: 10 to 40 times below that). The others are exact to the bit.
    const std::optional<double> rcond = reciprocal_condition(*f);
    const double relative = rcond ? std::numeric_limits<double>::epsilon() / *rcond : 0.0;
    for (size_t k = 0; k < at.size(); ++k)
      ASSERT_LE(std::abs(at[k] - d.values[k]), relative * std::abs(d.values[k]))
          << "value " << k << ": " << at[k] << " instead of " << d.values[k];
  });
}

TEST(InterpolantContract, ReproducesConstants) {
  for_each_case([](const Case& c, const DataSet& d) {
    const double constant[3] = {1.5, 0.0625, 1000};
    std::vector<double> v(d.values.size());
    for (size_t k = 0; k < v.size(); ++k) v[k] = constant[k % 3];
    const auto f = d.build(c, v, 3).value();
    const std::vector<Vec2> q = queries(d);
    const std::vector<double> out = evaluate(*f, q);
    const bool nan_outside = c.method == Method::natural_neighbour && c.params.outside == OutsideHull::none;
    // A method that reproduces constants does so everywhere it has a value; the others are held
    // to their bound inside the hull only.
    const bool reproduces_constants = c.constant_relative <= kRoundingRelative;
    for (size_t k = 0; k < q.size(); ++k) {
      if (!q[k].allFinite()) continue;
      auto within = [&](const Vec2& lo, const Vec2& hi) {
        return (q[k].array() >= lo.array()).all() && (q[k].array() <= hi.array()).all();
      };
      const bool inside_hull = within(d.inner_lo, d.inner_hi), outside_hull = !within(d.lo, d.hi);
      for (int ch = 0; ch < 3; ++ch) {
        const double got = out[k * 3 + static_cast<size_t>(ch)];
        if (nan_outside && outside_hull) {
          EXPECT_TRUE(std::isnan(got)) << "query " << k << " outside the hull: " << got;
          continue;
        }
        if (nan_outside && !inside_hull && std::isnan(got)) continue;  // near the hull: either
        const double relative = std::abs(got - constant[ch]) / constant[ch];
        if (reproduces_constants || inside_hull) {
          ASSERT_LE(relative, c.constant_relative)
              << "query " << k << " (" << q[k].x() << ", " << q[k].y() << ") channel " << ch << ": " << got;
        }
      }
    }
  });
}

TEST(InterpolantContract, NanQueryGivesNan) {
  for_each_case([](const Case& c, const DataSet& d) {
    const auto f = d.build(c).value();
    const std::vector<Vec2> q = {Vec2(kNaN, d.lo.y()), Vec2(d.lo.x(), kNaN), Vec2(kNaN, kNaN)};
    const std::vector<double> out = evaluate(*f, q);
    for (size_t k = 0; k < out.size(); ++k) EXPECT_TRUE(std::isnan(out[k])) << "value " << k << ": " << out[k];
  });
}

TEST(InterpolantContract, SlowChannelsAreIndependent) {
  // Bit for bit: each channel's arithmetic does not depend on the others (the multiquadrics' LU
  // solves all channels as right-hand sides of one system, column by column).
  for_each_case([](const Case& c, const DataSet& d) {
    const std::vector<Vec2> q = queries(d);
    const std::vector<double> all = evaluate(*d.build(c).value(), q);
    for (int ch = 0; ch < 3; ++ch) {
      std::vector<double> v(d.points.size());
      for (size_t i = 0; i < v.size(); ++i) v[i] = d.values[i * 3 + static_cast<size_t>(ch)];
      const std::vector<double> alone = evaluate(*d.build(c, v, 1).value(), q);
      for (size_t k = 0; k < q.size(); ++k)
        ASSERT_TRUE(same(alone[k], all[k * 3 + static_cast<size_t>(ch)]))
            << "query " << k << " channel " << ch << ": alone " << alone[k] << ", with the others "
            << all[k * 3 + static_cast<size_t>(ch)];
    }
  });
}

TEST(InterpolantContract, SlowBatchEqualsOnePointAtATime) {
  // Bit for bit: lattice data put many queries on Delaunay edges and co-circular points, where
  // natural-neighbour's walk could end in either face (it starts from the canonical one).
  for_each_case([](const Case& c, const DataSet& d) {
    const auto f = d.build(c).value();
    const std::vector<Vec2> q = queries(d);
    const std::vector<double> batch = evaluate(*f, q);
    for (size_t k = 0; k < q.size(); ++k) {
      const std::vector<double> one = evaluate(*f, std::span(&q[k], 1));
      for (size_t ch = 0; ch < 3; ++ch) {
        const double b = batch[k * 3 + ch];
        ASSERT_TRUE(same(one[ch], b)) << c.name << ", query " << k << " (" << q[k].x() << ", " << q[k].y()
                                      << ") channel " << ch << ": alone " << one[ch] << ", in the batch " << b;
      }
    }
  });
}

TEST(InterpolantContract, SlowOneAndTwoThreadsGiveIdenticalResults) {
  const int threads = worker_thread_count();
  for_each_case([&](const Case& c, const DataSet& d) {
    const std::vector<Vec2> q = queries(d);
    set_worker_thread_count(1);
    const auto f1 = d.build(c).value();  // built on one thread too (local multiquadric patches)
    const std::vector<double> one = evaluate(*f1, q);
    set_worker_thread_count(2);
    const auto f2 = d.build(c).value();
    const std::vector<double> two = evaluate(*f2, q), two_by_f1 = evaluate(*f1, q);
    set_worker_thread_count(threads);
    for (size_t k = 0; k < one.size(); ++k) {
      ASSERT_TRUE(same(one[k], two[k])) << "value " << k << ": " << one[k] << " on 1 thread, " << two[k] << " on 2";
      ASSERT_TRUE(same(one[k], two_by_f1[k])) << "value " << k;
    }
  });
}

}  // namespace contract_test
}  // namespace radrecon
