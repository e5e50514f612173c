// The renderer against independent answers: where primary rays land, the inverse of the quad
// parametrisation, and the pixel value of a surface of known constant radiosity.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <random>

#include <OpenEXR/ImfRgbaFile.h>
#include <OpenEXR/ImfArray.h>

#include "reconstruct/constant.h"
#include "reconstruct/methods.h"
#include "render/ground_map.h"
#include "io/image_io.h"
#include "core/parse.h"
#include "io/scene_json.h"
#include "render/renderer.h"

#include "support/scenes.h"

namespace radrecon {
namespace renderer_test {

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

TEST(Renderer, AWidePictureSpansTheVerticalFieldOfViewUpAndDownAndTheAspectAcross) {
  // fov_deg is the vertical field of view (scene.h): looking straight down from 5 m with up = +y,
  // a 200 x 100 picture sees the floor 5 tan(fov / 2) either side of the centre in y and twice
  // that in x. A pixel (px, py) sees x = 2 + (2 px / W - 1) 5 tan(fov / 2) W / H and
  // y = 2 - (2 py / H - 1) 5 tan(fov / 2). A horizontal field of view, or W and H swapped, fails.
  Scene scene;
  scene.surfaces.push_back(quad("floor", {-8, -8, 0}, {12, -8, 0}, {12, 12, 0}, {-8, 12, 0}));
  const Camera cam{"down", Vec3(2, 2, 5), Vec3(2, 2, 0), Vec3(0, 1, 0), 60.0};
  const int W = 200, H = 100;
  const double half = 5 * std::tan(30.0 * std::numbers::pi / 180);
  for (const auto& [px, py] : {std::pair{0.0, 0.0}, {200.0, 100.0}, {50.0, 25.0}, {173.5, 91.25}, {100.0, 50.0}}) {
    const auto [o, d] = camera_ray(cam, W, H, px, py);
    const auto hit = intersect_scene(scene, o, d);
    ASSERT_TRUE(hit.has_value());
    const Vec3 p = o + hit->t * d;
    EXPECT_NEAR(p.x(), 2 + (2 * px / W - 1) * half * W / H, 1e-9) << "pixel (" << px << ", " << py << ")";
    EXPECT_NEAR(p.y(), 2 - (2 * py / H - 1) * half, 1e-9) << "pixel (" << px << ", " << py << ")";
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
  const Image img = render(scene, cam, [&](SideRef side) { return side.back_side ? nullptr : &f; }, options).image;
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
  const Image img = render(scene, below, [&](SideRef side) { return side.back_side ? nullptr : &f; }, options).image;
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

/// A room's ceiling (z = 2.5, facing down, 4 m square) with a 1 m light in its plane, listed
/// before or after it, `offset` metres below it (negative: above, behind the ceiling).
Scene ceiling_with_light(bool light_first, double offset = 0) {
  const std::string z = format_number(2.5 - offset);
  const std::string ceiling = R"({"name": "ceiling", "corners": [[0,0,2.5], [0,4,2.5], [4,4,2.5], [4,0,2.5]], "reflectance": 0.5})";
  const std::string light = R"({"name": "light", "corners": [[1.5,1.5,)" + z + "], [1.5,2.5," + z + "], [2.5,2.5," + z +
                            "], [2.5,1.5," + z + R"(]], "reflectance": 0, "emission": 40})";
  const std::string floor = R"({"name": "floor", "corners": [[0,0,0], [4,0,0], [4,4,0], [0,4,0]], "reflectance": 0.5})";
  const std::string text = R"({"name": "coplanar", "surfaces": [)" + (light_first ? light + ", " + ceiling : ceiling + ", " + light) +
                           ", " + floor + R"(], "cameras": [{"name": "up", "eye": [2,2,0.5], "target": [2,2,2.5], "up": [0,1,0], "fov_deg": 60}]})";
  return parse_scene_json(text, "coplanar.json");
}

TEST(EmitterTie, ALightInTheCeilingsPlaneIsHitWhicheverIsListedFirst) {
  for (bool light_first : {true, false}) {
    const Scene scene = ceiling_with_light(light_first);
    const size_t light = light_first ? 0 : 1, ceiling = 1 - light;
    for (const Vec3& target : {Vec3(2, 2, 2.5), Vec3(1.6, 2.4, 2.5), Vec3(2.49, 1.51, 2.5)}) {
      const Vec3 o(2.3, 1.9, 0.5);
      const auto hit = intersect_scene(scene, o, (target - o).normalized());
      ASSERT_TRUE(hit.has_value());
      EXPECT_EQ(hit->surface, light) << light_first;
      EXPECT_FALSE(hit->back_side);
    }
    const Vec3 o(2, 2, 0.5), beside(3.2, 2, 2.5);  // beside the light: the ceiling
    EXPECT_EQ(intersect_scene(scene, o, (beside - o).normalized())->surface, ceiling);
    // Seen from above (through the back of both, neither emits nor faces the ray): the smaller,
    // lying on the other, whichever is listed first (the first listed, before).
    const Vec3 above(2, 2, 4);
    EXPECT_EQ(intersect_scene(scene, above, Vec3(0, 0, -1))->surface, light);
  }
  // A millimetre behind the ceiling the light is hidden; a millimetre in front, it is seen.
  for (bool light_first : {true, false}) {
    const size_t light = light_first ? 0 : 1;
    const Vec3 o(2, 2, 0.5);
    EXPECT_NE(intersect_scene(ceiling_with_light(light_first, -1e-3), o, Vec3(0, 0, 1))->surface, light);
    EXPECT_EQ(intersect_scene(ceiling_with_light(light_first, 1e-3), o, Vec3(0, 0, 1))->surface, light);
  }
}

/// A scene of the surfaces `a` and `b` (JSON objects), in that order or the other, then `rest`
/// (more surfaces and the cameras, JSON text after them).
Scene in_either_order(const std::string& a, const std::string& b, bool a_first, const std::string& rest) {
  return parse_scene_json(R"({"name": "tie", "surfaces": [)" + (a_first ? a + ", " + b : b + ", " + a) + rest, "tie.json");
}

TEST(EmitterTie, OfTwoOneSidedFacesBackToBackTheOneFacingTheRayIsSeenWhicheverIsListedFirst) {
  // A plate of no thickness: a top facing +z and a bottom facing -z in one plane. The first
  // listed was hit from both sides, its back drawn black from one (an outside-in trial).
  const std::string top = R"({"name": "top", "corners": [[1,1,1], [2,1,1], [2,2,1], [1,2,1]], "reflectance": 0.6})";
  const std::string bottom = R"({"name": "bottom", "corners": [[1,1,1], [1,2,1], [2,2,1], [2,1,1]], "reflectance": 0.6})";
  for (const bool top_first : {true, false}) {
    const Scene scene = in_either_order(top, bottom, top_first, R"(, {"name": "lamp", "corners": [[5,5,5], [5,6,5], [6,6,5], [6,5,5]], "reflectance": 0, "emission": 1}], "cameras": [{"name": "c", "eye": [0,0,3], "target": [1.5,1.5,1], "up": [0,0,1], "fov_deg": 60}]})");
    const size_t top_index = top_first ? 0 : 1;
    for (const Vec3& target : {Vec3(1.5, 1.5, 1), Vec3(1.1, 1.9, 1), Vec3(1.93, 1.02, 1)}) {
      const Vec3 above(1.3, 1.6, 3), below(1.7, 1.4, -2);
      const auto from_above = intersect_scene(scene, above, (target - above).normalized());
      const auto from_below = intersect_scene(scene, below, (target - below).normalized());
      ASSERT_TRUE(from_above && from_below);
      EXPECT_EQ(from_above->surface, top_index) << top_first;
      EXPECT_FALSE(from_above->back_side);
      EXPECT_EQ(from_below->surface, 1 - top_index) << top_first;
      EXPECT_FALSE(from_below->back_side);
    }
  }
}

TEST(EmitterTie, ARugLyingOnAFloorIsSeenWhicheverIsListedFirst) {
  // Both facing up in one plane: the rug, the smaller, lies on the floor and is seen on it (it
  // was the floor when the floor came first in the list).
  const std::string floor = R"({"name": "floor", "corners": [[0,0,0], [4,0,0], [4,4,0], [0,4,0]], "reflectance": 0.5})";
  const std::string rug = R"({"name": "rug", "corners": [[1,1,0], [2,1,0], [2,2,0], [1,2,0]], "reflectance": 0.2})";
  for (const bool floor_first : {true, false}) {
    const Scene scene = in_either_order(floor, rug, floor_first, R"(, {"name": "lamp", "corners": [[0,0,3], [0,4,3], [4,4,3], [4,0,3]], "reflectance": 0, "emission": 1}], "cameras": [{"name": "c", "eye": [2,2,2], "target": [1.5,1.5,0], "up": [0,1,0], "fov_deg": 60}]})");
    const size_t rug_index = floor_first ? 1 : 0;
    const Vec3 above(1.3, 1.6, 2);
    for (const Vec3& target : {Vec3(1.5, 1.5, 0), Vec3(1.1, 1.9, 0), Vec3(1.93, 1.02, 0)}) {
      const auto hit = intersect_scene(scene, above, (target - above).normalized());
      ASSERT_TRUE(hit);
      EXPECT_EQ(hit->surface, rug_index) << floor_first;
    }
    // Beside the rug: the floor.
    EXPECT_EQ(intersect_scene(scene, above, (Vec3(3, 3, 0) - above).normalized())->surface, 1 - rug_index);
  }
}

TEST(EmitterTie, ALightInTheCeilingsPlaneRendersBright) {
  // Looking straight up from 2 m below the ceiling (60 degrees): the ceiling spans 2 tan 30 deg =
  // 1.1547 m either side of the centre, the light 0.5 m. Pixels whose rays all land within the
  // light show its 40 W/m^2, those all beside it the ceiling's 0.3 W/m^2.
  const PiecewiseConstant ceiling(CellSamples{{Rect{0, 0, 4, 4}}, {0.3, 0.3, 0.3}, 3, {}});
  const PiecewiseConstant light(CellSamples{{Rect{0, 0, 1, 1}}, {40, 40, 40}, 3, {}});
  RenderOptions options;
  options.width = 60;
  options.height = 60;
  const double half = 2 * std::tan(std::numbers::pi / 6);
  for (bool light_first : {true, false}) {
    const Scene scene = ceiling_with_light(light_first);
    const Image img = render(scene, scene.cameras[0], [&](SideRef side) -> const Interpolant* {
      if (side.back_side) return nullptr;
      const std::string& name = scene.surfaces[side.surface].name;
      return name == "light" ? &light : name == "ceiling" ? &ceiling : nullptr;
    }, options).image;
    int bright = 0;
    for (int y = 0; y < options.height; ++y)
      for (int x = 0; x < options.width; ++x) {
        // The farthest a ray of the pixel lands from the centre along each axis, and the nearest.
        auto far = [&](int k) { return std::max(std::abs(2.0 * k / 60 - 1), std::abs(2.0 * (k + 1) / 60 - 1)) * half; };
        auto near = [&](int k) { return std::min(std::abs(2.0 * k / 60 - 1), std::abs(2.0 * (k + 1) / 60 - 1)) * half; };
        if (far(x) < 0.5 && far(y) < 0.5) {
          EXPECT_EQ(img.at(x, y)[0], 40.0) << x << "," << y;
          ++bright;
        } else if (near(x) > 0.5 || near(y) > 0.5) {
          EXPECT_NEAR(img.at(x, y)[0], 0.3, 1e-15) << x << "," << y;
        }
      }
    EXPECT_EQ(bright, 24 * 24);  // pixels 18..41 along each axis: (0.5 / 1.1547) * 30 = 12.99 either side
  }
}

}  // namespace renderer_test
}  // namespace radrecon
