// Queries within rounding of a sample, as users compute them: a raster's cell centre
// x0 + (i + 0.5) dx against a sample written as the decimal (i + 0.5) / n, 1 ulp apart. The
// natural neighbours' areas cancel to nothing there; such a point must still get the value of the
// function the samples carry (a linear function: reproduced exactly, up to rounding), never NaN
// and never a hull edge's value.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <random>

#include "reconstruct/methods.h"
#include "reconstruct/natural_neighbour.h"

namespace radrecon {
namespace near_sample_test {

double f(const Vec2& p) { return 3 + 2 * p.x() - 1.5 * p.y(); }

/// The accepted error of a reproduced linear function at these points, in f's units.
constexpr double kLinearRounding = 1e-12;

TEST(NearSample, EveryNaturalNeighbourRuleTakesAPointOneUlpOffASampleAsThatSample) {
  // 300 random samples and the unit square's corners; each interior sample queried at the
  // nearest doubles around it (a batch, as a raster goes, and alone). Before, 1 in ~100 such
  // points was taken for one outside the hull: NaN with outside=none (natural-neighbour,
  // sibson-c1).
  std::mt19937 rng(2027);
  std::uniform_real_distribution<double> u(0.05, 0.95);
  ScatteredSamples s;
  for (const Vec2& c : {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1), Vec2(1, 1)}) s.points.push_back(c);
  for (int i = 0; i < 300; ++i) s.points.emplace_back(u(rng), u(rng));
  for (const Vec2& p : s.points) s.values.push_back(f(p));
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::vector<Vec2> q;
  for (size_t k = 4; k < s.points.size(); ++k) {
    const Vec2 p = s.points[k];
    for (const double towards : {-kInf, kInf}) {
      q.emplace_back(std::nextafter(p.x(), towards), p.y());
      q.emplace_back(p.x(), std::nextafter(p.y(), towards));
      q.emplace_back(std::nextafter(std::nextafter(p.x(), towards), towards), p.y());
    }
  }
  for (const Method m : {Method::natural_neighbour, Method::sibson_c1, Method::laplace}) {
    MethodParams params;
    params.outside = OutsideHull::none;
    const InterpolantResult made = make_scattered_interpolant(m, s, params);
    ASSERT_TRUE(made) << made.reason();
    std::vector<double> batch(q.size());
    made.value()->evaluate(q, batch);
    for (size_t k = 0; k < q.size(); ++k) {
      ASSERT_NEAR(batch[k], f(q[k]), kLinearRounding) << method_name(m) << ", query " << k << " in a batch";
      double alone = 0;
      made.value()->evaluate(std::span(&q[k], 1), std::span(&alone, 1));
      ASSERT_NEAR(alone, f(q[k]), kLinearRounding) << method_name(m) << ", query " << k << " alone";
    }
  }
}

TEST(NearSample, ARasterWhoseCellCentresLieWithinRoundingOfSamplesHasAValueInEveryCell) {
  // Samples at 150 cell centres of a 100 x 100 raster written as 6-digit decimals (some 1 ulp
  // off the raster's own centres) and 150 random points; the raster is served face by face
  // (SibsonRaster), whose weight and error at such a point were both infinite: inf / inf was
  // written as NaN (an outside-in trial; here cell 9782).
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(0, 1);
  std::uniform_int_distribution<int> cell(0, 99);
  ScatteredSamples s;
  for (const Vec2& c : {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1), Vec2(1, 1)}) s.points.push_back(c);
  Raster raster;
  raster.width = raster.height = 100;
  int off_by_rounding = 0;
  for (int k = 0; k < 150; ++k) {
    const int i = cell(rng), j = cell(rng);
    char text[64];
    std::snprintf(text, sizeof text, "%.6g %.6g", (i + 0.5) / 100, (j + 0.5) / 100);
    char* end = nullptr;
    const double x = std::strtod(text, &end), y = std::strtod(end, nullptr);
    s.points.emplace_back(x, y);
    if (raster.point(static_cast<size_t>(i), static_cast<size_t>(j)) != Vec2(x, y)) ++off_by_rounding;
  }
  for (int k = 0; k < 150; ++k) s.points.emplace_back(u(rng), u(rng));
  // Drop exact repeats (two cells drawn twice), which the interpolant would refuse.
  std::sort(s.points.begin(), s.points.end(), [](const Vec2& a, const Vec2& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  s.points.erase(std::unique(s.points.begin(), s.points.end()), s.points.end());
  for (const Vec2& p : s.points) s.values.push_back(f(p));
  ASSERT_GT(off_by_rounding, 10);  // the case at hand: centres 1 ulp off samples
  const NaturalNeighbour nn(s, OutsideHull::none);
  const size_t count = static_cast<size_t>(raster.width) * static_cast<size_t>(raster.height);
  std::vector<double> got(count);
  nn.evaluate_raster(raster, 0, count, got);
  for (size_t k = 0; k < count; ++k) {
    const Vec2 p = raster.point(k % 100, k / 100);
    ASSERT_NEAR(got[k], f(p), kLinearRounding) << "cell " << k << " at (" << p.x() << ", " << p.y() << ")";
  }
}

}  // namespace near_sample_test
}  // namespace radrecon
