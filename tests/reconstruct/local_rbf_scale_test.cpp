// The multiquadric and thin-plate, global (reconstruct/multiquadric.h) and local
// (reconstruct/local_multiquadric.h), in any unit of length: data and length parameters scaled
// together give the same function, and messages name places in the data's own units.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "core/error.h"
#include "reconstruct/local_multiquadric.h"
#include "reconstruct/methods.h"
#include "reconstruct/multiquadric.h"
#include "reconstruct/multiquadric_basis.h"

namespace radrecon {
namespace local_rbf_scale_test {

TEST(LocalMultiquadric, DoesNotDependOnTheUnitOfLength) {
  // The same data in another unit of length, with the parameters of length in that unit (a
  // given r scaled, Eck's radii and the patches scaling by themselves), is the same function:
  // the multiquadric's basis at s d and s r is s^(2 mu) times that at d and r, which the
  // coefficients absorb; the thin-plate spline's extra log(s) d^2 term is a polynomial the side
  // conditions cancel; and the patch grid is sized from the samples' box. Before, the box's
  // width had a floor of 1e-12 in absolute units: at 1e-12 the values moved by 0.16
  // (multiquadric) and 0.057 (thin-plate), at 1e-13 the local thin-plate was the global one, and
  // 3000 samples were refused as too clustered for patches of ~32.
  std::mt19937 rng(57);
  ScatteredSamples s;
  std::uniform_real_distribution<double> unit(0, 1);
  for (int i = 0; i < 150; ++i) {
    s.points.emplace_back(unit(rng), unit(rng));
    s.values.push_back(std::sin(4 * s.points.back().x()) * std::exp(s.points.back().y()));
  }
  std::vector<Vec2> q(400);
  for (Vec2& p : q) p = Vec2(0.1 + 0.8 * unit(rng), 0.1 + 0.8 * unit(rng));
  struct Case {
    const char* name;
    RbfKernel kernel;
    std::optional<double> r;
  };
  const Case cases[] = {{"multiquadric, Eck's r", RbfKernel::multiquadric(0.5), std::nullopt},
                        {"multiquadric, r = 0.05", RbfKernel::multiquadric(0.5), 0.05},
                        {"thin-plate", RbfKernel::thin_plate(), std::nullopt}};
  for (const Case& c : cases) {
    const LocalMultiquadric reference(s, c.kernel, c.r, 30);
    std::vector<double> want(q.size());
    reference.evaluate(q, want);
    for (const double scale : {1e-13, 1e-12, 1e13, 1e-99}) {
      ScatteredSamples scaled = s;
      for (Vec2& p : scaled.points) p *= scale;
      std::vector<Vec2> at = q;
      for (Vec2& p : at) p *= scale;
      const LocalMultiquadric f(scaled, c.kernel, c.r ? std::optional<double>(*c.r * scale) : std::nullopt, 30);
      EXPECT_NEAR(f.patch_radius() / scale, reference.patch_radius(), 1e-14 * reference.patch_radius())
          << c.name << ", scale " << scale;
      std::vector<double> got(q.size());
      f.evaluate(at, got);
      for (size_t k = 0; k < q.size(); ++k)
        ASSERT_NEAR(got[k], want[k], 1e-12 * std::max(1.0, std::abs(want[k]))) << c.name << ", scale " << scale << ", query " << k;
    }
  }
  // 3000 samples 1e-13 across take patches of ~32 as they do 1 across.
  ScatteredSamples many;
  for (int i = 0; i < 3000; ++i) {
    many.points.emplace_back(1e-13 * unit(rng), 1e-13 * unit(rng));
    many.values.push_back(many.points.back().x() * 1e13);
  }
  ScatteredSamples one = many;
  for (Vec2& p : one.points) p *= 1e13;
  const LocalMultiquadric tiny(many, RbfKernel::thin_plate(), std::nullopt, 32), wide(one, RbfKernel::thin_plate(), std::nullopt, 32);
  EXPECT_NEAR(tiny.patch_radius() * 1e13, wide.patch_radius(), 1e-12 * wide.patch_radius());
}

TEST(Multiquadric, DoesNotDependOnTheUnitOfLengthWhateverItsExponent) {
  // The basis at s d and s r is s^(2 mu) times that at d and r, which alpha absorbs: the same
  // function in any unit. With the basis taken in the data's unit, samples 1e50 apart gave
  // (1e100)^7.5 = inf, and 1e-50 apart 0: both refused as "singular" (an outside-in trial).
  // Exact at the samples in every unit; by a power of 2 (a power of 4 in d^2), the mu = 1/2
  // interpolant without a polynomial is the same to the bit.
  std::mt19937 rng(58);
  std::uniform_real_distribution<double> unit(0, 1);
  ScatteredSamples s;
  for (int i = 0; i < 40; ++i) {
    s.points.emplace_back(unit(rng), unit(rng));
    s.values.push_back(std::sin(3 * s.points.back().x()) + s.points.back().y());
  }
  std::vector<Vec2> q(50);
  for (Vec2& p : q) p = Vec2(unit(rng), unit(rng));
  for (const double mu : {0.5, 2.5, 7.5, -1.5})
    for (const int poly : {0, 1}) {
      const RbfKernel kernel = RbfKernel::multiquadric(mu, poly);
      const Multiquadric reference(s, kernel, std::nullopt);
      std::vector<double> want(q.size());
      reference.evaluate(q, want);
      // mu = 7.5's system is poorly conditioned (rcond ~1e-19): its solve's rounding, not the unit.
      const double tolerance = mu == 7.5 ? 1e-7 : 1e-11;
      for (const double scale : {1e-50, 1e50, 0x1p20}) {
        ScatteredSamples scaled = s;
        for (Vec2& p : scaled.points) p *= scale;
        std::vector<Vec2> at = q;
        for (Vec2& p : at) p *= scale;
        const std::string where = "mu " + std::to_string(mu) + ", poly " + std::to_string(poly) + ", scale " + std::to_string(scale);
        const Multiquadric f(scaled, kernel, std::nullopt);
        std::vector<double> got(q.size()), at_samples(s.points.size());
        f.evaluate(at, got);
        f.evaluate(scaled.points, at_samples);
        for (size_t k = 0; k < s.points.size(); ++k)
          ASSERT_NEAR(at_samples[k], s.values[k], tolerance) << where << ", sample " << k;
        for (size_t k = 0; k < q.size(); ++k) {
          if (mu == 0.5 && poly == 0 && scale == 0x1p20) ASSERT_EQ(got[k], want[k]) << where << ", query " << k;
          ASSERT_NEAR(got[k], want[k], tolerance * std::max(1.0, std::abs(want[k]))) << where << ", query " << k;
        }
      }
    }
}

TEST(Multiquadric, InterpolateWarnsThatAnOffsetInTheValuesBendsTheGlobalFormAndPolyReproducesIt) {
  // 200 samples of the constant 1000: the global multiquadric (no constant in its span) is off
  // it between and past the samples, the form with a linear polynomial is 1000 to rounding, and
  // interpolate's entry warns of the first only (an outside-in trial).
  std::mt19937 rng(59);
  std::uniform_real_distribution<double> unit(0, 15);
  ScatteredSamples s;
  for (int i = 0; i < 200; ++i) s.points.emplace_back(unit(rng), unit(rng));
  s.values.assign(s.points.size(), 1000.0);
  const std::vector<Vec2> q = {Vec2(15.2, 15.6), Vec2(-0.5, 7)};
  MethodParams params;
  ::testing::internal::CaptureStderr();
  const InterpolantResult hardy = make_point_interpolant(Method::multiquadric, s, params);
  const std::string warned = ::testing::internal::GetCapturedStderr();
  ASSERT_TRUE(hardy) << hardy.reason();
  EXPECT_NE(warned.find("the values' mean, 1000, is large against their range, 0"), std::string::npos) << warned;
  std::vector<double> got(q.size());
  hardy.value()->evaluate(q, got);
  EXPECT_GT(std::abs(got[0] - 1000), 1.0);  // 1119 in the trial
  params.multiquadric_poly = 1;
  ::testing::internal::CaptureStderr();
  const InterpolantResult with_poly = make_point_interpolant(Method::multiquadric, s, params);
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
  ASSERT_TRUE(with_poly) << with_poly.reason();
  with_poly.value()->evaluate(q, got);
  for (const double v : got) EXPECT_NEAR(v, 1000, 1e-9);
  // Values about 0 (mean within their range): no warning.
  for (size_t k = 0; k < s.points.size(); ++k) s.values[k] = std::sin(s.points[k].x());
  ::testing::internal::CaptureStderr();
  const InterpolantResult centred = make_point_interpolant(Method::multiquadric, s, MethodParams{});
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

TEST(LocalMultiquadric, ARefusedPatchIsLocatedInTheSamplesUnits) {
  // A cluster of 2500 samples within 1e-13 of (5e-11, 5e-11), among samples 1e-10 apart: the
  // patch holding it is refused, and its centre is printed as a number of the data's scale
  // (printed with %f it read "(0.000000, 0.000000)").
  ScatteredSamples s;
  for (const Vec2& c : {Vec2(0, 0), Vec2(1e-10, 0), Vec2(0, 1e-10), Vec2(1e-10, 1e-10)}) s.points.push_back(c);
  for (int j = 0; j < 50; ++j)
    for (int i = 0; i < 50; ++i) s.points.emplace_back(5e-11 + 2e-15 * i, 5e-11 + 2e-15 * j);
  s.values.assign(s.points.size(), 1.0);
  try {
    const LocalMultiquadric f(s, RbfKernel::thin_plate(), std::nullopt, 3);
    FAIL() << "not refused";
  } catch (const ReconstructionError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("holds 2500 samples"), std::string::npos) << what;
    EXPECT_NE(what.find("e-11"), std::string::npos) << what;
    EXPECT_EQ(what.find("0.000000"), std::string::npos) << what;
  }
}

}  // namespace local_rbf_scale_test
}  // namespace radrecon
