// The renderer against independent answers: where primary rays land, the inverse of the quad
// parametrisation, and the pixel value of a surface of known constant radiosity.

#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include <OpenEXR/ImfRgbaFile.h>
#include <OpenEXR/ImfArray.h>

#include "reconstruct/constant.h"
#include "reconstruct/methods.h"
#include "render/ground_map.h"
#include "io/image_io.h"
#include "render/renderer.h"

#include "support/scenes.h"

namespace radrecon {
namespace {

/// A black quad (reflectance and emission 0).
Surface quad(const std::string& name, const Vec3& c0, const Vec3& c1, const Vec3& c2, const Vec3& c3) {
  return testing_support::quad(name, c0, c1, c2, c3, 0.0);
}

TEST(Renderer, PrimaryRaysHitTheRightSurfaceAtTheRightPlace) {
  Scene scene;
  scene.surfaces.push_back(quad("floor", {0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}));
  scene.surfaces.push_back(quad("card", {1.5, 1.5, 1}, {2.5, 1.5, 1}, {2.5, 2.5, 1}, {1.5, 2.5, 1}));  // faces up
  // Looking straight down from (2, 2, 5) with up = +y: image x runs along +x, image y along -y.
  const Camera cam{"down", Vec3(2, 2, 5), Vec3(2, 2, 0), Vec3(0, 1, 0), 60.0};
  const int W = 200, H = 200;
  const double half = 5 * std::tan(30.0 * std::numbers::pi / 180);  // floor half-extent seen
  for (int k = 0; k < 50; ++k) {
    const double px = 3 + 3.9 * k, py = 197 - 3.7 * k;
    const auto [o, d] = camera_ray(cam, W, H, px, py);
    const auto hit = intersect_scene(scene, o, d);
    const double x = 2 + (2 * px / W - 1) * half, y = 2 - (2 * py / H - 1) * half;  // on the floor
    if (std::abs(x - 2) >= 2 || std::abs(y - 2) >= 2) {
      EXPECT_FALSE(hit.has_value()) << "beyond the floor";
      continue;
    }
    ASSERT_TRUE(hit.has_value());
    const bool on_card = std::abs((x - 2) * 4 / 5.0) <= 0.5 && std::abs((y - 2) * 4 / 5.0) <= 0.5;
    if (on_card) {  // the card at z = 1 is seen at 4/5 of the floor's offset from the centre
      EXPECT_EQ(hit->surface, 1u);
      EXPECT_NEAR(hit->u, 2 + (x - 2) * 4 / 5.0 - 1.5, 1e-9);
      EXPECT_NEAR(hit->v, 2 + (y - 2) * 4 / 5.0 - 1.5, 1e-9);
      EXPECT_NEAR(hit->t, 4 / d.dot(-Vec3::UnitZ()), 1e-9);
    } else {
      EXPECT_EQ(hit->surface, 0u);
      EXPECT_NEAR(hit->u, x / 4, 1e-9);
      EXPECT_NEAR(hit->v, y / 4, 1e-9);
    }
    EXPECT_FALSE(hit->back_side);
  }
}

TEST(Renderer, ConstantRadiosityRendersToThePredictedPixelValue) {
  Scene scene;
  scene.surfaces.push_back(quad("wall", {-5, -5, 0}, {5, -5, 0}, {5, 5, 0}, {-5, 5, 0}));
  const Camera cam{"c", Vec3(0.3, -0.2, 4), Vec3(0, 0, 0), Vec3(0, 1, 0), 40.0};
  const double B = 0.37;
  CellSamples cells;
  cells.channels = 3;
  cells.cells = {Rect{0, 0, 10, 10}};
  cells.values = {B, 2 * B, 3 * B};
  const PiecewiseConstant f(cells);
  RenderOptions options;
  options.width = 32;
  options.height = 24;
  const Image img = render(scene, cam, [&](SideRef side) { return side.back_side ? nullptr : &f; }, options);
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x) {
      EXPECT_NEAR(img.at(x, y)[0], B, 1e-15);  // the mean of 9 equal rays
      EXPECT_NEAR(img.at(x, y)[2], 3 * B, 1e-15);
    }
  // The tone mapping of the PNG: B / white, then sRGB.
  EXPECT_DOUBLE_EQ(tone_map(B, 1.48), 0.25);
  EXPECT_NEAR(srgb_encode(0.25), 0.5370987, 1e-6);
}

TEST(Renderer, BackOfAOneSidedSurfaceWithoutSolutionIsBlack) {
  Scene scene;
  scene.surfaces.push_back(quad("floor", {-5, -5, 0}, {5, -5, 0}, {5, 5, 0}, {-5, 5, 0}));  // faces +z
  const Camera below{"below", Vec3(0, 0, -3), Vec3(0, 0, 0), Vec3(0, 1, 0), 40.0};
  RenderOptions options;
  options.width = 8;
  options.height = 8;
  CellSamples cells;
  cells.channels = 3;
  cells.cells = {Rect{0, 0, 10, 10}};
  cells.values = {1, 1, 1};
  const PiecewiseConstant f(cells);
  const Image img = render(scene, below, [&](SideRef side) { return side.back_side ? nullptr : &f; }, options);
  EXPECT_EQ(img.at(4, 4)[0], 0.0);
}

TEST(ImageFiles, ExrHoldsTheLinearValuesAsHalfFloats) {
  Image img(5, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x) img.at(x, y) = Rgb(0.1 * x, 0.37 * y, 40.0);
  const auto path = std::filesystem::temp_directory_path() / "radrecon_exr_test.exr";
  write_exr(path, img);
  Imf::RgbaInputFile file(path.c_str());
  const auto dw = file.dataWindow();
  ASSERT_EQ(dw.max.x - dw.min.x + 1, 5);
  ASSERT_EQ(dw.max.y - dw.min.y + 1, 3);
  Imf::Array2D<Imf::Rgba> px(3, 5);
  file.setFrameBuffer(&px[0][0], 1, 5);
  file.readPixels(dw.min.y, dw.max.y);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x) {
      // Half floats keep 11 significant bits: relative error below 2^-11.
      EXPECT_NEAR(float(px[y][x].r), 0.1 * x, 1e-3 * (0.1 * x) + 1e-7);
      EXPECT_NEAR(float(px[y][x].g), 0.37 * y, 1e-3 * (0.37 * y) + 1e-7);
      EXPECT_NEAR(float(px[y][x].b), 40.0, 0.04);
    }
  std::filesystem::remove(path);
}

TEST(Renderer, BandsOfRowsGiveTheSameImageAsOneTrace) {
  // 1500 x 9 rays a row: kRenderBandRays (2^20) gives bands of 77 rows, so 200 rows take 3 bands.
  Scene scene;
  scene.surfaces.push_back(quad("floor", {0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}));
  scene.surfaces.push_back(quad("wall", {2, 0, 0}, {2, 4, 0}, {2, 4, 1}, {2, 0, 1}));
  const Camera cam{"oblique", Vec3(5, -3, 3), Vec3(2, 2, 0), Vec3(0, 0, 1), 50.0};
  RenderOptions options;
  options.width = 1500;
  options.height = 200;
  ASSERT_LT(kRenderBandRays / (static_cast<size_t>(options.width) * 9), static_cast<size_t>(options.height) / 2);
  ScatteredSamples samples;
  samples.channels = 3;
  for (double x : {0.0, 1.3, 4.0})
    for (double y : {0.0, 2.2, 4.0}) {
      samples.points.emplace_back(x, y);
      for (int c = 0; c < 3; ++c) samples.values.push_back(x + 2 * y + c);
    }
  const auto f = make_scattered_interpolant(Method::shepard, samples).value();
  const SideReconstruction recon = [&](SideRef) { return f.get(); };
  int calls = 0;
  const Image banded = render(scene, cam, recon, options, [&](double) { ++calls; });
  const Image whole = shade(scene, trace_camera(scene, cam, options), recon);
  EXPECT_EQ(calls, 3);
  for (int y = 0; y < options.height; ++y)
    for (int x = 0; x < options.width; ++x)
      for (int c = 0; c < 3; ++c) ASSERT_EQ(banded.at(x, y)[c], whole.at(x, y)[c]) << x << "," << y;
}

}  // namespace
}  // namespace radrecon
