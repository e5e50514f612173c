// Hardy's multiquadrics: exact at the samples, Eck's radii, and the coefficients against an
// independent solve (Householder QR with full pivoting instead of partial-pivoting LU); the local
// partition of unity rebuilt from its definition.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include "core/error.h"
#include "reconstruct/local_multiquadric.h"
#include "reconstruct/multiquadric.h"
#include "reconstruct/border_samples.h"
#include "reconstruct/methods.h"
#include "reconstruct/multiquadric_basis.h"
#include "reconstruct/natural_neighbour.h"
#include "support/barrier_cases.h"

namespace radrecon {
namespace multiquadric_test {

ScatteredSamples random_samples(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> xy(0, 4), value(0, 1);
  ScatteredSamples s;
  for (int i = 0; i < n; ++i) {
    s.points.emplace_back(xy(rng), xy(rng));
    s.values.push_back(value(rng));
  }
  return s;
}

TEST(RbfBasis, PacketThinPlateMatchesTheFormulaWithLibmLog) {
  // phi(v) = v log(v) / 2 in packets (Eigen's log) against std::log, over 24 decades and at 0:
  // a few units in the last place, relative (phi's zero at v = 1 aside: there absolute).
  constexpr double kRelative = 4e-16;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> decade(-12, 12);
  Eigen::ArrayXd v(4001);
  v[0] = 0;
  v[1] = 1;
  for (Eigen::Index i = 2; i < v.size(); ++i) v[i] = std::pow(10.0, decade(rng));
  Eigen::ArrayXd phi = v;
  rbf_basis_in_place(phi, RbfKernel::thin_plate());
  EXPECT_EQ(phi[0], 0.0);
  EXPECT_EQ(phi[1], 0.0);
  for (Eigen::Index i = 2; i < v.size(); ++i) {
    const double expected = 0.5 * v[i] * std::log(v[i]);
    EXPECT_NEAR(phi[i], expected, kRelative * std::max(std::abs(expected), 0.5 * v[i])) << "v=" << v[i];
  }
}

TEST(Multiquadric, ThreeChannelsExactAtTheSamplesAndEachAsAlone) {
  // The multiquadric's one-pass sums (up to three channels, 4 samples a vector; 61 leaves a
  // tail) and the general path (4 channels): exact at the samples, and each channel the same
  // interpolant as its values fitted alone.
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> xy(0, 4), value(-1, 2);
  for (const int channels : {3, 4}) {
    ScatteredSamples s;
    s.channels = channels;
    for (int i = 0; i < 61; ++i) {
      s.points.emplace_back(xy(rng), xy(rng));
      for (int c = 0; c < channels; ++c) s.values.push_back(value(rng));
    }
    const Multiquadric f(s, 0.5, std::nullopt);
    std::vector<double> at(s.values.size());
    f.evaluate(s.points, at);
    for (size_t k = 0; k < at.size(); ++k) EXPECT_NEAR(at[k], s.values[k], 1e-8) << channels << " channels, value " << k;
    std::vector<Vec2> queries(200);
    for (Vec2& q : queries) q = Vec2(xy(rng), xy(rng));
    std::vector<double> together(queries.size() * static_cast<size_t>(channels));
    f.evaluate(queries, together);
    for (int c = 0; c < channels; ++c) {
      ScatteredSamples one;
      one.points = s.points;
      for (size_t i = 0; i < s.points.size(); ++i) one.values.push_back(s.values[i * static_cast<size_t>(channels) + c]);
      const Multiquadric g(one, 0.5, std::nullopt);
      std::vector<double> alone(queries.size());
      g.evaluate(queries, alone);
      for (size_t q = 0; q < queries.size(); ++q)
        EXPECT_NEAR(together[q * static_cast<size_t>(channels) + c], alone[q], 1e-9) << channels << " channels, channel " << c;
    }
  }
}

TEST(Multiquadric, EckRadiusIsTheNearestOtherSample) {
  std::mt19937 rng(8);
  const ScatteredSamples s = random_samples(40, rng);
  const Multiquadric f(s, 0.5, std::nullopt);
  for (size_t i = 0; i < s.points.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    for (size_t j = 0; j < s.points.size(); ++j)
      if (j != i) best = std::min(best, (s.points[i] - s.points[j]).squaredNorm());
    EXPECT_DOUBLE_EQ(f.r_sq()[i], best);
  }
}

TEST(Multiquadric, ExactAtTheSamplesAndAgreesWithAnIndependentSolve) {
  std::mt19937 rng(9);
  const ScatteredSamples s = random_samples(60, rng);
  for (double mu : {0.5, -0.5, 1.5}) {
    const Multiquadric f(s, mu, std::nullopt);
    std::vector<double> at(s.points.size());
    f.evaluate(s.points, at);
    for (size_t i = 0; i < s.points.size(); ++i) EXPECT_NEAR(at[i], s.values[i], 1e-8) << "mu=" << mu;
    // Independent: the same system by full-pivoting Householder QR.
    const Eigen::Index n = static_cast<Eigen::Index>(s.points.size());
    Eigen::MatrixXd A(n, n);
    Eigen::VectorXd b(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      b(i) = s.values[static_cast<size_t>(i)];
      for (Eigen::Index j = 0; j < n; ++j)
        A(i, j) = std::pow((s.points[static_cast<size_t>(i)] - s.points[static_cast<size_t>(j)]).squaredNorm() +
                               f.r_sq()[static_cast<size_t>(j)], mu);
    }
    const Eigen::VectorXd alpha = A.fullPivHouseholderQr().solve(b);
    std::uniform_real_distribution<double> xy(0, 4);
    for (int t = 0; t < 50; ++t) {
      const Vec2 q(xy(rng), xy(rng));
      double expected = 0;
      for (Eigen::Index j = 0; j < n; ++j)
        expected += alpha(j) * std::pow((q - s.points[static_cast<size_t>(j)]).squaredNorm() + f.r_sq()[static_cast<size_t>(j)], mu);
      double got;
      f.evaluate(std::span(&q, 1), std::span(&got, 1));
      EXPECT_NEAR(got, expected, 1e-7 * (1 + std::abs(expected))) << "mu=" << mu;
    }
  }
}

TEST(Multiquadric, EckRadiiOnBothThreadsAndTheFirstDuplicateNamed) {
  // 600 samples: the radii are found in parallel (from 512 on).
  std::mt19937 rng(9);
  ScatteredSamples s = random_samples(600, rng);
  const Multiquadric f(s, 0.5, std::nullopt);
  for (size_t i = 0; i < s.points.size(); i += 7) {
    double best = std::numeric_limits<double>::infinity();
    for (size_t j = 0; j < s.points.size(); ++j)
      if (j != i) best = std::min(best, (s.points[i] - s.points[j]).squaredNorm());
    EXPECT_EQ(f.r_sq()[i], best) << "sample " << i;
  }
  // Two pairs of duplicates: the one of lowest index is named, whatever the threads.
  s.points[500] = s.points[100] = Vec2(3.5, 0.75);
  s.points[550] = s.points[50] = Vec2(1.25, 2.5);
  try {
    const Multiquadric g(s, 0.5, std::nullopt);
    ADD_FAILURE() << "duplicates accepted";
  } catch (const ReconstructionError& e) {
    EXPECT_NE(std::string(e.what()).find("(1.25, 2.5)"), std::string::npos) << e.what();
  }
}

TEST(Multiquadric, ConstantRadiusAndRefusals) {
  std::mt19937 rng(10);
  const ScatteredSamples s = random_samples(20, rng);
  const Multiquadric f(s, 0.5, 0.3);
  for (double r2 : f.r_sq()) EXPECT_DOUBLE_EQ(r2, 0.09);
  ScatteredSamples dup = s;
  dup.points.push_back(dup.points[3]);
  dup.values.push_back(0.5);
  EXPECT_THROW(Multiquadric(dup, 0.5, std::nullopt), ReconstructionError);
  ScatteredSamples one;
  one.points = {Vec2(1, 1)};
  one.values = {2};
  EXPECT_THROW(Multiquadric(one, 0.5, std::nullopt), ReconstructionError);
  const Multiquadric single(one, 0.5, 1.0);  // one sample with a given r: a scaled basis function
  double v;
  const Vec2 q(1, 1);
  single.evaluate(std::span(&q, 1), std::span(&v, 1));
  EXPECT_NEAR(v, 2.0, 1e-14);
}

TEST(LocalMultiquadric, ExactAtTheSamplesAndWeightsCoverTheBox) {
  std::mt19937 rng(11);
  const ScatteredSamples s = random_samples(3000, rng);
  const LocalMultiquadric f(s, 0.5, std::nullopt, 32);
  std::vector<double> at(s.points.size());
  f.evaluate(s.points, at);
  for (size_t i = 0; i < s.points.size(); ++i) ASSERT_NEAR(at[i], s.values[i], 1e-8) << "sample " << i;
  // Anywhere in the box the blend is a finite weighted mean of local interpolants.
  std::uniform_real_distribution<double> xy(0, 4);
  std::vector<Vec2> q(2000);
  for (Vec2& p : q) p = Vec2(xy(rng), xy(rng));
  std::vector<double> v(q.size());
  f.evaluate(q, v);
  for (double x : v) EXPECT_TRUE(std::isfinite(x));
}

/// Whether p lies inside the convex hull of the points: no half-plane through p holds them all,
/// i.e. no angular gap of more than pi between the directions from p to them.
bool inside_hull_of(const Vec2& p, const std::vector<Vec2>& points) {
  std::vector<double> angles;
  for (const Vec2& q : points) angles.push_back(std::atan2(q.y() - p.y(), q.x() - p.x()));
  std::sort(angles.begin(), angles.end());
  double gap = angles.front() + 2 * std::numbers::pi - angles.back();
  for (size_t a = 1; a < angles.size(); ++a) gap = std::max(gap, angles[a] - angles[a - 1]);
  return gap < std::numbers::pi - 1e-9;
}

TEST(LocalMultiquadric, TheBlendRebuiltFromItsDefinition) {
  // The partition of unity rebuilt from the header's words alone, at queries inside every
  // contributing patch's hull: patches centred on the grid origin + (i h, j h) over the samples'
  // box (h = patch_radius()), each through every sample within 1.5 h of its centre, fitting the
  // deviations from their mean (the multiquadric system solved here by full-pivoting QR) and
  // adding the mean back; blended by Wendland's C2 weights (1 - t)^4 (4 t + 1), t = d / h.
  std::mt19937 rng(31);
  const ScatteredSamples s = random_samples(400, rng);
  constexpr double kMu = 0.5, kR = 0.15;
  const LocalMultiquadric f(s, kMu, kR, 24);
  const double h = f.patch_radius();
  Vec2 lo = s.points[0], hi = s.points[0];
  for (const Vec2& p : s.points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const int nx = static_cast<int>(std::ceil((hi.x() - lo.x()) / h)) + 1;
  const int ny = static_cast<int>(std::ceil((hi.y() - lo.y()) / h)) + 1;
  const auto basis = [&](const Vec2& a, const Vec2& b) { return std::pow((a - b).squaredNorm() + kR * kR, kMu); };
  std::uniform_real_distribution<double> xy(0.3, 3.7);
  int checked = 0, skipped = 0;
  double worst = 0;
  for (int t = 0; t < 200; ++t) {
    const Vec2 q(xy(rng), xy(rng));
    double weighted = 0, weights = 0;
    bool every_hull_holds_q = true;
    for (int j = 0; j < ny && every_hull_holds_q; ++j)
      for (int i = 0; i < nx && every_hull_holds_q; ++i) {
        const Vec2 c = lo + Vec2(i * h, j * h);
        const double d = (q - c).norm();
        if (d >= h) continue;
        std::vector<Vec2> points;
        std::vector<double> values;
        for (size_t k = 0; k < s.points.size(); ++k)
          if ((s.points[k] - c).norm() <= 1.5 * h) points.push_back(s.points[k]), values.push_back(s.values[k]);
        ASSERT_GE(points.size(), 3u) << "the disc holds enough samples here";
        if (!inside_hull_of(q, points)) {
          every_hull_holds_q = false;
          break;
        }
        const Eigen::Index m = static_cast<Eigen::Index>(points.size());
        double mean = 0;
        for (double v : values) mean += v / static_cast<double>(m);
        Eigen::MatrixXd A(m, m);
        Eigen::VectorXd b(m);
        for (Eigen::Index a = 0; a < m; ++a) {
          b(a) = values[static_cast<size_t>(a)] - mean;
          for (Eigen::Index e = 0; e < m; ++e) A(a, e) = basis(points[static_cast<size_t>(a)], points[static_cast<size_t>(e)]);
        }
        const Eigen::VectorXd alpha = A.fullPivHouseholderQr().solve(b);
        double value = mean;
        for (Eigen::Index e = 0; e < m; ++e) value += alpha(e) * basis(q, points[static_cast<size_t>(e)]);
        const double x = d / h, w = std::pow(1 - x, 4) * (4 * x + 1);
        weighted += w * value;
        weights += w;
      }
    if (!every_hull_holds_q) {
      ++skipped;
      continue;
    }
    ASSERT_GT(weights, 0);
    double got;
    f.evaluate(std::span(&q, 1), std::span(&got, 1));
    const double expected = weighted / weights;
    EXPECT_NEAR(got, expected, 1e-8) << "query (" << q.x() << ", " << q.y() << ")";
    worst = std::max(worst, std::abs(got - expected));
    ++checked;
  }
  EXPECT_GT(checked, 100) << skipped << " queries lay outside some patch's hull";
  std::printf("%d queries (%d outside some patch's hull, not checked): largest difference %.2e\n", checked, skipped, worst);
}

TEST(LocalMultiquadric, ApproachesTheGlobalInterpolantAsPatchesGrow) {
  // A smooth function sampled densely: the partition of unity's error falls towards the global
  // interpolant's as the patches hold more samples.
  std::mt19937 rng(12);
  ScatteredSamples s = random_samples(1500, rng);
  auto f = [](const Vec2& p) { return std::sin(p.x()) * std::cos(0.7 * p.y()); };
  for (size_t i = 0; i < s.points.size(); ++i) s.values[i] = f(s.points[i]);
  std::uniform_real_distribution<double> xy(0.2, 3.8);
  std::vector<Vec2> q(500);
  for (Vec2& p : q) p = Vec2(xy(rng), xy(rng));
  auto max_error = [&](const Interpolant& g) {
    std::vector<double> v(q.size());
    g.evaluate(q, v);
    double worst = 0;
    for (size_t t = 0; t < q.size(); ++t) worst = std::max(worst, std::abs(v[t] - f(q[t])));
    return worst;
  };
  const double global = max_error(Multiquadric(s, 0.5, std::nullopt));
  const double k40 = max_error(LocalMultiquadric(s, 0.5, std::nullopt, 40));
  const double k100 = max_error(LocalMultiquadric(s, 0.5, std::nullopt, 100));
  const double k200 = max_error(LocalMultiquadric(s, 0.5, std::nullopt, 200));
  std::printf("max error: global %.3g, local k=40 %.3g, k=100 %.3g, k=200 %.3g\n", global, k40, k100, k200);
  EXPECT_GT(k40, k100);
  EXPECT_GT(k100, k200);
  EXPECT_LT(k200, 2 * global);
}

TEST(LocalMultiquadric, PatchesOnSurveyTracksTakeASampleOffTheirLineAndReproduceLinearFunctions) {
  // Samples on three tracks far apart against their spacing: each patch's disc holds one track,
  // which determines no polynomial term across it. Every patch then gave way to none, and a
  // linear function erred by up to 1.3 between the tracks (found by an outside-in trial); each
  // patch now takes the nearest sample off its line. With a polynomial (thin-plate, multiquadric
  // poly=1) the blend reproduces linear functions, as the global fit does.
  auto f = [](const Vec2& p) { return 3 + 2 * p.x() - 5 * p.y(); };
  ScatteredSamples s;
  for (int k = 0; k < 50; ++k) {
    const double x = k / 49.0;
    for (const Vec2& p : {Vec2(x, 0.2), Vec2(x, 0.5 + 0.1 * x), Vec2(x, 0.9 - 0.05 * x)}) {
      s.points.push_back(p);
      s.values.push_back(f(p));
    }
  }
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> x(0.02, 0.98), y(0.21, 0.84);
  std::vector<Vec2> q(500);
  for (Vec2& p : q) p = Vec2(x(rng), y(rng));
  for (const RbfKernel& kernel : {RbfKernel::thin_plate(), RbfKernel::multiquadric(0.5, 1)})
    for (const int k : {16, 32}) {
      const LocalMultiquadric local(s, kernel, kernel.is_thin_plate() ? std::nullopt : std::optional<double>(0.1), k);
      std::vector<double> v(q.size());
      local.evaluate(q, v);
      for (size_t t = 0; t < q.size(); ++t)
        ASSERT_NEAR(v[t], f(q[t]), 1e-10) << kernel.name() << " k=" << k << " at " << q[t].transpose();
    }
}

TEST(LocalMultiquadric, AnOffsetInTheValuesIsAddedUnchanged) {
  // Each patch fits the deviations from its samples' mean: f(values + c) = f(values) + c, and a
  // constant is reproduced exactly, inside the box and outside it (poly=0 and poly=1 alike).
  std::mt19937 rng(21);
  const ScatteredSamples s = random_samples(800, rng);
  ScatteredSamples raised = s, flat = s;
  for (double& v : raised.values) v += 900;
  for (double& v : flat.values) v = 900;
  std::uniform_real_distribution<double> xy(-1, 5);
  std::vector<Vec2> q(1000);
  for (Vec2& p : q) p = Vec2(xy(rng), xy(rng));
  for (const int poly : {0, 1}) {
    const RbfKernel kernel = RbfKernel::multiquadric(0.5, poly);
    std::vector<double> a(q.size()), b(q.size()), c(q.size());
    LocalMultiquadric(s, kernel, std::nullopt, 16).evaluate(q, a);
    LocalMultiquadric(raised, kernel, std::nullopt, 16).evaluate(q, b);
    LocalMultiquadric(flat, kernel, std::nullopt, 16).evaluate(q, c);
    for (size_t t = 0; t < q.size(); ++t) {
      ASSERT_NEAR(b[t] - a[t], 900, 1e-9) << "poly=" << poly << " query " << t;
      ASSERT_NEAR(c[t], 900, 1e-10) << "poly=" << poly << " query " << t;
    }
  }
}

TEST(LocalMultiquadric, AsAccurateAsNaturalNeighbourOverallAndAlongTheEdges) {
  // Terrain-like data (a large offset, a slope, hills) at random points; held-out points against
  // the closed form, in the box and in the band along its edges and corners. Before the patches
  // held their hull's value and fitted deviations from their mean, the band's largest error at
  // k = 16 was several times natural neighbour's.
  std::mt19937 rng(22);
  auto terrain = [](const Vec2& p) {
    return 900 + 40 * p.x() + 60 * std::sin(2.1 * p.x()) * std::cos(1.7 * p.y()) + 25 * std::cos(3.3 * p.y());
  };
  ScatteredSamples s = random_samples(2000, rng);
  for (size_t i = 0; i < s.points.size(); ++i) s.values[i] = terrain(s.points[i]);
  std::uniform_real_distribution<double> xy(0, 4);
  std::vector<Vec2> q(20000);
  for (Vec2& p : q) p = Vec2(xy(rng), xy(rng));
  struct Errors {
    double rms = 0, max = 0, edge_max = 0;
  };
  auto errors = [&](const Interpolant& f) {
    std::vector<double> v(q.size());
    f.evaluate(q, v);
    Errors e;
    for (size_t t = 0; t < q.size(); ++t) {
      const double d = std::abs(v[t] - terrain(q[t]));
      const double to_edge = std::min({q[t].x(), 4 - q[t].x(), q[t].y(), 4 - q[t].y()});
      e.rms += d * d;
      e.max = std::max(e.max, d);
      if (to_edge < 0.2) e.edge_max = std::max(e.edge_max, d);
    }
    e.rms = std::sqrt(e.rms / static_cast<double>(q.size()));
    return e;
  };
  const Errors nn = errors(NaturalNeighbour(s, OutsideHull::nearest));
  std::printf("natural neighbour: rms %.3g, max %.3g, edge band max %.3g\n", nn.rms, nn.max, nn.edge_max);
  for (const int k : {16, 32}) {
    const Errors mq = errors(LocalMultiquadric(s, 0.5, std::nullopt, k));
    std::printf("local multiquadric k=%d: rms %.3g, max %.3g, edge band max %.3g\n", k, mq.rms, mq.max, mq.edge_max);
    EXPECT_LE(mq.rms, nn.rms) << "k=" << k;
    EXPECT_LE(mq.max, 1.5 * nn.max) << "k=" << k;
    EXPECT_LE(mq.edge_max, 1.5 * nn.edge_max) << "k=" << k;
  }
}

TEST(Multiquadric, BorderSamplesWithBarriersAndOneRadiusStayOnTheDomainsBorder) {
  // As the thin-plate spline (ThinPlate.BorderSamplesWithBarriersStayOnTheDomainsBorder): with
  // one radius r for every sample (r given), samples beside a wall made a point past its free end
  // see two of them 2e-6 m apart with values a step apart, and the multiquadric through both swung
  // far past the data (an outside-in trial: -266..109 for data in [-1, 2] at r = 0.1, -12..27 at
  // r = 0.01). Such a multiquadric takes border samples on the domain's border only; with its
  // default radii (Eck's: each sample's nearest neighbour's distance) it keeps those beside the
  // walls, whose radii of 2e-6 disturb nothing past them.
  const testing_support::WallCornerGround ground = testing_support::wall_corner_ground();
  const ScatteredSamples& s = ground.samples;
  const std::vector<Polyline>& walls = ground.walls;
  const std::vector<Vec2>& q = ground.queries;
  for (const std::string radius : {"r=0.1", "r=1", ""}) {
    MethodParams params = parse_params(Method::multiquadric, radius.empty() ? std::vector<std::string>{}
                                                                            : std::vector<std::string>{radius}, "test");
    params.barriers = Barriers::from_polylines(walls).value();
    ScatteredSamples bordered = s;
    const Result<size_t> added = add_border_samples(Method::multiquadric, bordered, Rect{0, 0, 4, 4}, params);
    ASSERT_TRUE(added) << added.reason();
    if (radius.empty()) EXPECT_GT(added.value(), 64u);  // beside the walls too
    else EXPECT_EQ(added.value(), 64u) << radius;       // 4 sides of 16 parts at the data's spacing
    const InterpolantResult f = make_point_interpolant(Method::multiquadric, bordered, params);
    ASSERT_TRUE(f) << f.reason();
    std::vector<double> v(q.size());
    f.value()->evaluate(q, v);
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    EXPECT_GT(*lo, 0.4 - 0.5 * (1.02 - 0.4)) << radius;
    EXPECT_LT(*hi, 1.02 + 0.5 * (1.02 - 0.4)) << radius;
  }
}

TEST(Multiquadric, PolyTakesTheNumbersZeroAndOneInAnyNotation) {
  // Python's poly=1.0 arrives as "1.0": it was refused while k=3.0 was taken.
  EXPECT_EQ(parse_params(Method::multiquadric, {"poly=1.0"}, "test").multiquadric_poly, 1);
  EXPECT_EQ(parse_params(Method::multiquadric, {"poly=0e0"}, "test").multiquadric_poly, 0);
  for (const std::string bad : {"poly=2", "poly=0.5", "poly=one", "poly=nan"})
    EXPECT_THROW(parse_params(Method::multiquadric, {bad}, "test"), UserError) << bad;
}

}  // namespace multiquadric_test
}  // namespace radrecon
