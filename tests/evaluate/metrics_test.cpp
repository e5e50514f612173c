// SSIM, the gradient error and overshoot against independent computations: SSIM by the textbook
// formula over every window with the 2-D Gaussian weights written out, and closed forms; the
// gradient error on functions whose finite-difference gradients are known exactly; overshoot on
// constructed cases whose natural neighbours are worked out by hand.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <bit>
#include <cstdint>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "core/thread_pool.h"
#include "core/image.h"
#include "evaluate/metrics.h"

namespace radrecon {
namespace metrics_test {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
/// Sums of a few hundred terms of size ~1: the two computations differ in the last bits only.
constexpr double kRoundOff = 1e-12;

/// Wang et al.'s SSIM written out: for every window position wholly inside the image, the
/// 11 x 11 weights exp(-(dx^2 + dy^2) / (2 * 1.5^2)) normalised to sum 1, the weighted means,
/// and the variances and covariance as weighted sums of products of deviations (two passes,
/// unlike the library's E[x^2] - mu^2); the mean over windows and channels.
double textbook_ssim(const std::vector<double>& x, const std::vector<double>& y, int width, int height, int channels) {
  double g[11][11], total = 0;
  for (int v = 0; v < 11; ++v)
    for (int u = 0; u < 11; ++u) total += g[v][u] = std::exp(-((u - 5.0) * (u - 5.0) + (v - 5.0) * (v - 5.0)) / 4.5);
  const double c1 = 0.0001, c2 = 0.0009;  // (0.01 * 1)^2, (0.03 * 1)^2
  double sum = 0;
  int count = 0;
  for (int c = 0; c < channels; ++c)
    for (int y0 = 0; y0 + 11 <= height; ++y0)
      for (int x0 = 0; x0 + 11 <= width; ++x0) {
        auto X = [&](int u, int v) { return x[((y0 + v) * width + x0 + u) * channels + c]; };
        auto Y = [&](int u, int v) { return y[((y0 + v) * width + x0 + u) * channels + c]; };
        double mx = 0, my = 0;
        for (int v = 0; v < 11; ++v)
          for (int u = 0; u < 11; ++u) mx += g[v][u] / total * X(u, v), my += g[v][u] / total * Y(u, v);
        double vx = 0, vy = 0, cxy = 0;
        for (int v = 0; v < 11; ++v)
          for (int u = 0; u < 11; ++u) {
            const double w = g[v][u] / total, dx = X(u, v) - mx, dy = Y(u, v) - my;
            vx += w * dx * dx, vy += w * dy * dy, cxy += w * dx * dy;
          }
        sum += (2 * mx * my + c1) * (2 * cxy + c2) / ((mx * mx + my * my + c1) * (vx + vy + c2));
        ++count;
      }
  return sum / count;
}

std::vector<double> random_image(size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> v(n);
  for (double& x : v) x = u(rng);
  return v;
}

TEST(Ssim, MatchesTheTextbookFormulaOnSmallRandomImages) {
  for (const ImageShape shape : {ImageShape{13, 12, 1}, ImageShape{13, 12, 3}, ImageShape{11, 11, 2}, ImageShape{20, 14, 1}}) {
    SCOPED_TRACE(std::to_string(shape.width) + "x" + std::to_string(shape.height) + "x" + std::to_string(shape.channels));
    const std::vector<double> a = random_image(shape.size(), 17), r = random_image(shape.size(), 29);
    // Correlated too (a noisy copy), where SSIM is far from 0.
    std::vector<double> b = r;
    for (size_t k = 0; k < b.size(); ++k) b[k] = 0.8 * r[k] + 0.2 * a[k];
    EXPECT_NEAR(*ssim(a, r, shape), textbook_ssim(a, r, shape.width, shape.height, shape.channels), kRoundOff);
    EXPECT_NEAR(*ssim(b, r, shape), textbook_ssim(b, r, shape.width, shape.height, shape.channels), kRoundOff);
    EXPECT_GT(*ssim(b, r, shape), 0.5);
  }
}

TEST(Ssim, GreyImagesOfThreeChannelsMatchTheTextbookFormula) {
  // Every pixel's three channels equal in both images (ssim() then computes one channel), and
  // one pixel's channels differing (all three computed).
  const ImageShape shape{15, 13, 3};
  const std::vector<double> a1 = random_image(15 * 13, 31), r1 = random_image(15 * 13, 37);
  std::vector<double> a(shape.size()), r(shape.size());
  for (size_t k = 0; k < a.size(); ++k) a[k] = a1[k / 3], r[k] = r1[k / 3];
  EXPECT_NEAR(*ssim(a, r, shape), textbook_ssim(a, r, shape.width, shape.height, shape.channels), kRoundOff);
  a[100] += 0.25;
  EXPECT_NEAR(*ssim(a, r, shape), textbook_ssim(a, r, shape.width, shape.height, shape.channels), kRoundOff);
}

TEST(Ssim, IsOneForIdenticalImages) {
  const ImageShape shape{15, 13, 3};
  const std::vector<double> a = random_image(shape.size(), 5);
  EXPECT_NEAR(*ssim(a, a, shape), 1.0, 1e-15);
}

TEST(Ssim, ConstantImagesGiveTheLuminanceTermAlone) {
  // Constant images m and n: no variance or covariance, so SSIM = (2 m n + C1) / (m^2 + n^2 + C1)
  // in every window.
  const ImageShape shape{12, 12, 1};
  for (const auto& [m, n] : {std::pair{0.3, 0.5}, std::pair{0.0, 1.0}, std::pair{0.7, 0.7}}) {
    const std::vector<double> a(shape.size(), m), r(shape.size(), n);
    const double c1 = 1e-4;
    EXPECT_NEAR(*ssim(a, r, shape), (2 * m * n + c1) / (m * m + n * n + c1), kRoundOff) << m << " vs " << n;
  }
}

TEST(Ssim, AReversedImageIsNegativelyCorrelated) {
  // r = 1 - a: the covariance is minus the variance in every window, so SSIM < 0.
  const ImageShape shape{16, 16, 1};
  const std::vector<double> a = random_image(shape.size(), 3);
  std::vector<double> r(a.size());
  for (size_t k = 0; k < a.size(); ++k) r[k] = 1 - a[k];
  const double s = *ssim(a, r, shape);
  EXPECT_LT(s, 0.0);
  EXPECT_NEAR(s, textbook_ssim(a, r, shape.width, shape.height, 1), kRoundOff);
}

TEST(Ssim, NotDefinedBelowTheWindowAndNanForNan) {
  const std::vector<double> small(10 * 20, 0.5);
  EXPECT_FALSE(ssim(small, small, {10, 20, 1}).has_value());
  EXPECT_FALSE(ssim(small, small, {20, 10, 1}).has_value());
  std::vector<double> a(12 * 12, 0.5);
  const std::vector<double> r = a;
  a[77] = kNaN;
  EXPECT_TRUE(std::isnan(*ssim(a, r, {12, 12, 1})));
  EXPECT_TRUE(std::isnan(*ssim(r, a, {12, 12, 1})));
}

TEST(Ssim, SameResultOnOneAndTwoThreads) {
  // 600 output rows: enough for the parallel loop to share them out.
  const ImageShape shape{30, 610, 1};
  const std::vector<double> a = random_image(shape.size(), 8), r = random_image(shape.size(), 9);
  const int threads = worker_thread_count();
  set_worker_thread_count(1);
  const double one = *ssim(a, r, shape);
  set_worker_thread_count(2);
  const double two = *ssim(a, r, shape);
  set_worker_thread_count(threads);
  EXPECT_EQ(one, two);
}

/// Values of f at the points (x0 + i dx, y0 + j dy) of a width x height grid, one channel.
template <typename F>
std::vector<double> sampled(F f, int width, int height, double dx, double dy) {
  std::vector<double> v(static_cast<size_t>(width) * height);
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) v[static_cast<size_t>(j) * width + i] = f(0.5 + i * dx, -1 + j * dy);
  return v;
}

TEST(GradientL2, ALinearRampAgainstZeroGivesTheSlopeSquared) {
  // Differences, central or one-sided, are exact for linear functions: |grad| = (3, -2) everywhere.
  const int W = 9, H = 7;
  const double dx = 0.25, dy = 0.5;
  const std::vector<double> ramp = sampled([](double x, double y) { return 3 * x - 2 * y + 1; }, W, H, dx, dy);
  const std::vector<double> zero(ramp.size(), 0.0);
  EXPECT_NEAR(gradient_l2(ramp, zero, {W, H, 1}, dx, dy), 13.0, 1e-12);
  EXPECT_NEAR(gradient_l2(zero, ramp, {W, H, 1}, dx, dy), 13.0, 1e-12);
  EXPECT_EQ(gradient_l2(ramp, ramp, {W, H, 1}, dx, dy), 0.0);
}

TEST(GradientL2, ABilinearDifferenceGivesItsExactGradient) {
  // a = x^2 + y^2 + 3xy, r = x^2 + y^2: the difference 3xy is linear along each grid line, so
  // every difference quotient of it is exact, (3y, 3x); the squares' one-sided quotients at the
  // border are not, but they are the same in a and r and cancel.
  const int W = 8, H = 6;
  const double dx = 0.1, dy = 0.3;
  auto r_of = [](double x, double y) { return x * x + y * y; };
  const std::vector<double> a = sampled([&](double x, double y) { return r_of(x, y) + 3 * x * y; }, W, H, dx, dy);
  const std::vector<double> r = sampled(r_of, W, H, dx, dy);
  double expected = 0;
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i) {
      const double x = 0.5 + i * dx, y = -1 + j * dy;
      expected += 9 * (x * x + y * y);
    }
  expected /= W * H;
  EXPECT_NEAR(gradient_l2(a, r, {W, H, 1}, dx, dy), expected, 1e-12 * expected);
}

TEST(GradientL2, AQuadraticAgainstZeroUsesCentralAndOneSidedDifferences) {
  // f = x^2 along a row of 5 points x = 0, 1, 2, 3, 4 (dx = 1), one row (no y direction):
  // central differences are exact inside (2x: 2, 4, 6), one-sided at the ends
  // ((1 - 0) / 1 = 1 and (16 - 9) / 1 = 7). Mean of squares: (1 + 4 + 16 + 36 + 49) / 5.
  const std::vector<double> f = {0, 1, 4, 9, 16}, zero(5, 0.0);
  EXPECT_NEAR(gradient_l2(f, zero, {5, 1, 1}, 1.0, 1.0), 106.0 / 5, 1e-12);
  // The same as a column, with dy = 2 halving the derivatives.
  EXPECT_NEAR(gradient_l2(f, zero, {1, 5, 1}, 1.0, 2.0), 106.0 / 5 / 4, 1e-12);
}

TEST(GradientL2, AveragesOverChannelsAndGivesNanForNan) {
  // Channel 0: slope 2 along x; channel 1: slope 4 along y: (4 + 16) / 2.
  const int W = 5, H = 4;
  std::vector<double> a(static_cast<size_t>(W) * H * 2), zero(a.size(), 0.0);
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i) a[(j * W + i) * 2] = 2.0 * i, a[(j * W + i) * 2 + 1] = 4.0 * j;
  EXPECT_NEAR(gradient_l2(a, zero, {W, H, 2}, 1, 1), 10.0, 1e-12);
  a[3] = kNaN;
  EXPECT_TRUE(std::isnan(gradient_l2(a, zero, {W, H, 2}, 1, 1)));
}

/// The unit square's corners and its centre. The Delaunay triangles are the four around the
/// centre; a point of the lower one, (0.5, 0.25), lies outside the circumcircles of the others
/// (the left one's: centre (0, 0.5), radius 0.5, distance 0.56), so its natural neighbours are
/// (0,0), (1,0) and the centre, values 1, 2, 3: range [1, 3], while the samples span [-5, 10].
ScatteredSamples square_with_centre() {
  ScatteredSamples s;
  s.points = {{0, 0}, {1, 0}, {0, 1}, {1, 1}, {0.5, 0.5}};
  s.values = {1, 2, 10, -5, 3};
  return s;
}

TEST(Overshoot, MeasuresTheDistanceOutOfTheNaturalNeighboursRange) {
  const ScatteredSamples s = square_with_centre();
  const std::vector<Vec2> q = {{0.5, 0.25}};
  EXPECT_NEAR(*overshoot(s, q, std::vector<double>{3.25}), 0.25, 1e-15);  // above max 3
  EXPECT_NEAR(*overshoot(s, q, std::vector<double>{0.75}), 0.25, 1e-15);  // below min 1
  EXPECT_EQ(*overshoot(s, q, std::vector<double>{2.9}), 0.0);           // inside [1, 3]
  // Several points: the largest.
  const std::vector<Vec2> two = {{0.5, 0.25}, {0.5, 0.25}};
  EXPECT_NEAR(*overshoot(s, two, std::vector<double>{3.1, 0.5}), 0.5, 1e-15);
}

TEST(Overshoot, ABarrierAcrossTheDomainLeavesEachSideTheRangesOfItsOwnSamples) {
  // A wall at x = 0.5 across the whole domain: a query on the left sees only the left samples,
  // so its ranges with the barrier are those of the left samples alone without it, bit for bit
  // (zero influence across a barrier). The right samples' values (100 and up) would widen them.
  std::mt19937 rng(91);
  std::uniform_real_distribution<double> u(0, 1);
  ScatteredSamples all, left;
  for (int k = 0; k < 200; ++k) {
    const Vec2 p(u(rng), u(rng));
    if (std::abs(p.x() - 0.5) < 0.05) continue;
    const double v = p.x() < 0.5 ? std::sin(7 * p.y()) + p.x() : 100 + 50 * p.y();
    all.points.push_back(p), all.values.push_back(v);
    if (p.x() < 0.5) left.points.push_back(p), left.values.push_back(v);
  }
  const Barriers wall = Barriers::from_polylines(std::vector<Polyline>{{{0.5, -1}, {0.5, 2}}}).value();
  std::vector<Vec2> q;
  for (int k = 0; k < 300; ++k) q.emplace_back(0.12 + 0.25 * u(rng), 0.12 + 0.76 * u(rng));  // inside the left hull
  const std::optional<NeighbourRanges> walled = neighbour_ranges(all, q, wall), alone = neighbour_ranges(left, q);
  ASSERT_TRUE(walled && alone);
  EXPECT_EQ(walled->lo, alone->lo);
  EXPECT_EQ(walled->hi, alone->hi);
  // Without the wall the right samples reach some of these queries: the test can tell.
  const std::optional<NeighbourRanges> open = neighbour_ranges(all, q);
  EXPECT_NE(open->hi, alone->hi);
}

TEST(Overshoot, TheNearestVisibleSampleIsAlwaysWithinTheRange) {
  // The paper's ground: 16 x 16 cell centres over 4 m, two walls meeting in a corner. A point on
  // the hull of what it sees (a row of samples below the wall, and one seen around the wall's
  // end, e.g. (2.215, 2.395) between (2.375, 2.375) and (0.375, 2.625)) had those two ends as
  // its natural neighbours, without the sample next to it: the nearest visible sample's value,
  // found here by brute force, scored an overshoot of 0.054 in the paper's Table 3.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  ScatteredSamples s;
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i) s.points.emplace_back(0.125 + 0.25 * i, 0.125 + 0.25 * j), s.values.push_back(u(rng));
  const std::vector<Polyline> walls = {{{2.6, 0.6}, {2.6, 2.6}}, {{0.6, 2.6}, {2.6, 2.6}}};
  const Barriers barriers = Barriers::from_polylines(walls).value();
  std::vector<Vec2> q = {{2.215, 2.395}};
  for (int k = 0; k < 2000; ++k) q.emplace_back(4 * u(rng), 4 * u(rng));
  std::vector<double> nearest_seen(q.size());
  for (size_t k = 0; k < q.size(); ++k) {
    double best = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < s.points.size(); ++i)
      if (const double d = (s.points[i] - q[k]).squaredNorm(); d < best && !barriers.blocks(q[k], s.points[i]))
        best = d, nearest_seen[k] = s.values[i];
    ASSERT_TRUE(std::isfinite(best));
  }
  const std::optional<NeighbourRanges> ranges = neighbour_ranges(s, q, barriers);
  ASSERT_TRUE(ranges);
  EXPECT_EQ(overshoot(*ranges, nearest_seen), 0.0);
}

TEST(Overshoot, APointThatSeesNoSampleMayHaveNoValue) {
  // Four samples inside a closed square of barriers, one query outside it: the query sees no
  // sample, so it has no range, and a method's NaN there (no value) leaves the figure to the
  // other points: here 0.5 above the range [1, 4] of the natural neighbours of (0.5, 0.5).
  ScatteredSamples s;
  s.points = {{0.25, 0.25}, {0.75, 0.25}, {0.75, 0.75}, {0.25, 0.75}};
  s.values = {1, 2, 3, 4};
  const Barriers box =
      Barriers::from_polylines(std::vector<Polyline>{{{0.1, 0.1}, {0.9, 0.1}, {0.9, 0.9}, {0.1, 0.9}, {0.1, 0.1}}}).value();
  const std::vector<Vec2> q = {{0.5, 0.5}, {2, 2}};
  const std::optional<NeighbourRanges> ranges = neighbour_ranges(s, q, box);
  ASSERT_TRUE(ranges);
  EXPECT_EQ(ranges->lo[1], -std::numeric_limits<double>::infinity());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NEAR(overshoot(*ranges, std::vector<double>{4.5, nan}), 0.5, 1e-15);
  // A NaN where the point has a range is still a NaN figure.
  EXPECT_TRUE(std::isnan(overshoot(*ranges, std::vector<double>{nan, 1.0})));
}

TEST(Overshoot, OutsideTheHullUsesTheNearestHullEdgeAndTheNearestSamples) {
  const ScatteredSamples s = square_with_centre();
  // Below the square: edge (0,0)-(1,0) and nearest samples (0,0), (1,0), centre: [1, 3].
  EXPECT_NEAR(*overshoot(s, std::vector<Vec2>{{0.5, -1}}, std::vector<double>{3.5}), 0.5, 1e-15);
  // Left of it: edge (0,0)-(0,1), nearest (0,0), (0,1), centre: [1, 10].
  EXPECT_NEAR(*overshoot(s, std::vector<Vec2>{{-1, 0.5}}, std::vector<double>{10.25}), 0.25, 1e-15);
  EXPECT_EQ(*overshoot(s, std::vector<Vec2>{{-1, 0.5}}, std::vector<double>{9}), 0.0);
}

TEST(Overshoot, TheNearestSampleValueNeverOvershoots) {
  // The nearest sample is always a natural neighbour (its Voronoi cell holds the query) and
  // always among the nearest samples outside the hull: the constant method's overshoot is 0.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1), wide(-0.5, 1.5);
  ScatteredSamples s;
  s.channels = 2;
  for (int k = 0; k < 40; ++k) {
    s.points.emplace_back(u(rng), u(rng));
    s.values.push_back(u(rng));
    s.values.push_back(10 * u(rng) - 5);
  }
  std::vector<Vec2> q;
  std::vector<double> approx;
  for (int k = 0; k < 2000; ++k) {
    const Vec2 p(wide(rng), wide(rng));
    size_t best = 0;
    for (size_t i = 1; i < s.points.size(); ++i)
      if ((s.points[i] - p).squaredNorm() < (s.points[best] - p).squaredNorm()) best = i;
    q.push_back(p);
    approx.push_back(s.values[best * 2]);
    approx.push_back(s.values[best * 2 + 1]);
  }
  EXPECT_EQ(*overshoot(s, q, approx), 0.0);
  // And one channel of one point moved past all samples by 0.125 shows.
  approx[2 * 1234 + 1] = 5.125;
  EXPECT_GE(*overshoot(s, q, approx), 0.125);
}

TEST(Overshoot, NanForNanAndNotDefinedWithoutNaturalNeighbours) {
  const ScatteredSamples s = square_with_centre();
  EXPECT_TRUE(std::isnan(*overshoot(s, std::vector<Vec2>{{0.5, 0.25}}, std::vector<double>{kNaN})));
  ScatteredSamples line;
  line.points = {{0, 0}, {1, 1}, {2, 2}};
  line.values = {0, 1, 2};
  EXPECT_FALSE(overshoot(line, std::vector<Vec2>{{0.5, 0.5}}, std::vector<double>{1}).has_value());
}

TEST(DisplayValues, AreTheSrgbEncodedToneMap) {
  // 50 of white 100: linear 0.5, sRGB 1.055 * 0.5^(1/2.4) - 0.055 = 0.7353569830524495.
  const std::vector<double> d = display_values(std::vector<double>{50, -3, 250, 0.1, kNaN}, 100);
  EXPECT_NEAR(d[0], 0.7353569830524495, 1e-12);
  EXPECT_EQ(d[1], 0.0);
  EXPECT_NEAR(d[2], 1.0, 1e-15);  // 1.055 - 0.055 in double
  EXPECT_NEAR(d[3], 12.92 * 0.001, 1e-15);  // the curve's linear toe
  EXPECT_TRUE(std::isnan(d[4]));
}

// Equal neighbours (a grey pixel's channels) share their display value: every entry is still
// the curve at its own value, bit for bit, whatever its neighbours (NaN, signed zeros, runs
// across pixels, a size that is not a multiple of 3).
TEST(DisplayValues, EachIsItsOwnValuesCurveWhateverItsNeighbours) {
  const std::vector<double> v = {50, 50, 50, 20, 20, 30, kNaN, kNaN, 0.0, -0.0, 0.0, 7, 7, 7, 7, 300, 300};
  const std::vector<double> d = display_values(v, 100);
  ASSERT_EQ(d.size(), v.size());
  for (size_t k = 0; k < v.size(); ++k) {
    if (std::isnan(v[k])) {
      EXPECT_TRUE(std::isnan(d[k])) << k;
      continue;
    }
    const double want = srgb_encode(tone_map(v[k], 100));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(d[k]), std::bit_cast<std::uint64_t>(want)) << k;
  }
}

TEST(FiguresJson, HasEveryKeyAndNullWhereNotDefined) {
  Figures f;
  f.norms = {.l1 = 1, .l2 = 4, .rmse = 2, .linf = 3, .count = 5};
  f.ssim = 0.5;
  f.gradient_l2 = kNaN;
  const nlohmann::json j = figures_json(f);
  EXPECT_EQ(j.size(), 7u);
  EXPECT_EQ(j["L1"], 1.0);
  EXPECT_EQ(j["L2"], 4.0);
  EXPECT_EQ(j["RMSE"], 2.0);
  EXPECT_EQ(j["Linf"], 3.0);
  EXPECT_EQ(j["SSIM"], 0.5);
  EXPECT_TRUE(j["gradient_L2"].is_null());
  EXPECT_TRUE(j["overshoot"].is_null());
}

}  // namespace metrics_test
}  // namespace radrecon
