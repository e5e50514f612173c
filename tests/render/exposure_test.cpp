// The default white point against its definition (the nearest-rank percentile of the reflecting
// pixels' brightest channel) and against a rendered scene whose lit surfaces are known.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "reconstruct/constant.h"
#include "render/exposure.h"
#include "render/renderer.h"

#include "support/scenes.h"

namespace radrecon {
namespace exposure_test {

Rendering strip(const std::vector<Rgb>& values, const std::vector<std::uint8_t>& reflecting) {
  Rendering r{Image(static_cast<int>(values.size()), 1), reflecting};
  for (size_t k = 0; k < values.size(); ++k) r.image.at(static_cast<int>(k), 0) = values[k];
  return r;
}

TEST(Exposure, NearestRankOfTheBrightestChannel) {
  // 1000 reflecting pixels of brightest channel 1..1000 W/m^2, in one channel or another,
  // shuffled; the 99th percentile by nearest rank is the 990th smallest.
  std::vector<Rgb> values;
  for (int k = 1; k <= 1000; ++k) values.push_back(k % 3 == 0 ? Rgb(k, 0.5, 0) : k % 3 == 1 ? Rgb(0, k, 0) : Rgb(0.25, 0, k));
  std::shuffle(values.begin(), values.end(), std::mt19937(7));
  const Rendering r = strip(values, std::vector<std::uint8_t>(1000, 1));
  EXPECT_EQ(percentile_white(r, 99).value(), 990);
  EXPECT_EQ(percentile_white(r, 50).value(), 500);
  EXPECT_EQ(percentile_white(r, 100).value(), 1000);
  EXPECT_EQ(percentile_white(r, 0.01).value(), 1);
}

TEST(Exposure, OnlyReflectingPixelsCount) {
  // 100 reflecting pixels at 2 W/m^2 and 50 at 3; 30 others (a light, the background) at 1000.
  std::vector<Rgb> values;
  std::vector<std::uint8_t> mask;
  for (int k = 0; k < 180; ++k) {
    values.push_back(Rgb::Constant(k < 100 ? 2.0 : k < 150 ? 3.0 : 1000.0));
    mask.push_back(k < 150);
  }
  const Rendering r = strip(values, mask);
  EXPECT_EQ(percentile_white(r, 99).value(), 3.0);
  EXPECT_EQ(percentile_white(r, 66).value(), 2.0);  // rank ceil(0.66 * 150) = 99
  EXPECT_EQ(percentile_white(r, 67).value(), 3.0);  // rank ceil(100.5) = 101
  EXPECT_FALSE(percentile_white(strip(values, std::vector<std::uint8_t>(180, 0)), 99).has_value());
  EXPECT_FALSE(percentile_white(strip(std::vector<Rgb>(10, Rgb::Zero()), std::vector<std::uint8_t>(10, 1)), 99).has_value());
}

TEST(Exposure, TheDefiningPropertyOnRandomPixels) {
  // At least p% of the reflecting pixels do not exceed the white point, fewer than p% lie below
  // it (counted directly, fixed seed).
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> value(0, 5);
  std::vector<Rgb> values;
  std::vector<std::uint8_t> mask;
  for (int k = 0; k < 777; ++k) {
    values.push_back(Rgb(value(rng), value(rng), value(rng)));
    mask.push_back(rng() % 4 != 0);
  }
  const Rendering r = strip(values, mask);
  for (double p : {1.0, 37.5, 90.0, 99.0, 100.0}) {
    const double w = percentile_white(r, p).value();
    double n = 0, at_most = 0, below = 0;
    for (size_t k = 0; k < values.size(); ++k)
      if (mask[k]) {
        n += 1;
        at_most += values[k].maxCoeff() <= w;
        below += values[k].maxCoeff() < w;
      }
    EXPECT_GE(at_most, p / 100 * n) << p;
    EXPECT_LT(below, p / 100 * n) << p;
  }
}

TEST(Exposure, ARenderedPictureIsExposedByItsLitSurfacesNotItsLight) {
  // Looking down on a floor of constant radiosity 0.8 W/m^2 with a panel facing up over a quarter
  // of the picture: a light (40 W/m^2) there does not count, a reflecting panel (5 W/m^2) does,
  // and one drawn black (no reconstruction) does not.
  using testing_support::quad;
  const Camera above{"above", Vec3(0, 0, 4), Vec3(0, 0, 0), Vec3(0, 1, 0), 60.0};
  const PiecewiseConstant floor(CellSamples{{Rect{0, 0, 10, 10}}, {0.8, 0.8, 0.8}, 3, {}});
  const PiecewiseConstant lit(CellSamples{{Rect{0, 0, 2, 2}}, {40, 40, 40}, 3, {}});
  const PiecewiseConstant card(CellSamples{{Rect{0, 0, 2, 2}}, {5, 5, 5}, 3, {}});
  RenderOptions options;
  options.width = 40;
  options.height = 40;
  struct Case {
    double emission;
    const Interpolant* panel;
    double white;
  };
  for (const Case& c : {Case{40, &lit, 0.8}, Case{0, &card, 5.0}, Case{0, nullptr, 0.8}}) {
    Scene scene;
    scene.surfaces.push_back(quad("floor", {-5, -5, 0}, {5, -5, 0}, {5, 5, 0}, {-5, 5, 0}, 0.5));
    scene.surfaces.push_back(quad("panel", {-1, -1, 0.5}, {1, -1, 0.5}, {1, 1, 0.5}, {-1, 1, 0.5}, 0.0, c.emission));
    const Rendering r = render(scene, above, [&](SideRef side) -> const Interpolant* {
      if (side.back_side) return nullptr;
      return side.surface == 0 ? &floor : c.panel;
    }, options);
    EXPECT_EQ(r.image.at(20, 20)[0], c.panel ? (c.emission > 0 ? 40.0 : 5.0) : 0.0);  // the panel is in sight
    // The mean of a pixel's 9 equal rays: within round-off of the value.
    EXPECT_NEAR(percentile_white(r, kDefaultWhitePercentile).value(), c.white, 1e-15 * c.white) << c.emission;
  }
}

/// No value anywhere (NaN): a side some method cannot reconstruct there (beyond a radius, past a
/// barrier).
class NoValue final : public Interpolant {
 public:
  int channels() const override { return 3; }
  void evaluate(std::span<const Vec2>, std::span<double> out) const override {
    std::fill(out.begin(), out.end(), std::numeric_limits<double>::quiet_NaN());
  }
};

TEST(Exposure, RaysDrawnBlackForWantOfAValueDoNotCount) {
  // The floor of 0.8 W/m^2 seen past a reflecting panel whose method gives no value: its pixels
  // are drawn black and do not count towards the white point, as the lights and the background
  // do not. They did (a review: 74% of rays without value lowered a white of 0.96 to 0.80).
  using testing_support::quad;
  const Camera above{"above", Vec3(0, 0, 4), Vec3(0, 0, 0), Vec3(0, 1, 0), 60.0};
  const PiecewiseConstant floor(CellSamples{{Rect{0, 0, 10, 10}}, {0.8, 0.8, 0.8}, 3, {}});
  const NoValue none;
  Scene scene;
  scene.surfaces.push_back(quad("floor", {-5, -5, 0}, {5, -5, 0}, {5, 5, 0}, {-5, 5, 0}, 0.5));
  scene.surfaces.push_back(quad("panel", {-1, -1, 0.5}, {1, -1, 0.5}, {1, 1, 0.5}, {-1, 1, 0.5}, 0.5));
  RenderOptions options;
  options.width = 40;
  options.height = 40;
  const Rendering r = render(scene, above, [&](SideRef side) -> const Interpolant* {
    if (side.back_side) return nullptr;
    return side.surface == 0 ? static_cast<const Interpolant*>(&floor) : &none;
  }, options);
  size_t black = 0, floor_only = 0, counted = 0;
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 40; ++x) {
      const double v = r.image.at(x, y)[0];
      black += v == 0;
      floor_only += v == 0.8 || std::abs(v - 0.8) <= 1e-15;
      counted += r.reflecting[static_cast<size_t>(y) * 40 + x];
    }
  EXPECT_GT(black, 100u);  // the panel is in sight
  EXPECT_EQ(counted, floor_only);
  EXPECT_NEAR(percentile_white(r, kDefaultWhitePercentile).value(), 0.8, 1e-15);
}

}  // namespace exposure_test
}  // namespace radrecon
