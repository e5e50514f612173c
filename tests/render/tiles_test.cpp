// Rendering tile by tile: the same pixels, bit for bit, as the rays traced and shaded one at a
// time, whatever the tiles and the number of threads; memory that a counting allocator finds
// independent of the rays per pixel; progress after every tile.

#include <gtest/gtest.h>


#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <new>

#include "core/thread_pool.h"
#include "reconstruct/constant.h"
#include "reconstruct/methods.h"
#include "render/renderer.h"

#include "support/scenes.h"

// Every operator new of this test program counted: the bytes live now and their peak. The size
// is kept in a 16-byte header (malloc's alignment is kept).
namespace {
std::atomic<long long> live_bytes{0}, peak_bytes{0};
void* counted_new(std::size_t n) {
  void* block = std::malloc(n + 16);
  if (!block) throw std::bad_alloc();
  *static_cast<std::size_t*>(block) = n;
  const long long now = live_bytes += static_cast<long long>(n);
  long long peak = peak_bytes.load();
  while (now > peak && !peak_bytes.compare_exchange_weak(peak, now)) {
  }
  return static_cast<char*>(block) + 16;
}
void counted_delete(void* p) noexcept {
  if (!p) return;
  void* block = static_cast<char*>(p) - 16;
  live_bytes -= static_cast<long long>(*static_cast<std::size_t*>(block));
  std::free(block);
}
}  // namespace
void* operator new(std::size_t n) { return counted_new(n); }
void* operator new[](std::size_t n) { return counted_new(n); }
void operator delete(void* p) noexcept { counted_delete(p); }
void operator delete[](void* p) noexcept { counted_delete(p); }
void operator delete(void* p, std::size_t) noexcept { counted_delete(p); }
void operator delete[](void* p, std::size_t) noexcept { counted_delete(p); }

namespace radrecon {
namespace tiles_test {

using testing_support::quad;

/// A floor, a wall standing on it and a light above, seen from over the floor (the background
/// too: about 1800 pixels of 97 x 61 see the floor and the wall, 56 the light).
struct TestScene {
  Scene scene;
  Camera camera{"inside", Vec3(3.5, 0.3, 1.6), Vec3(1.5, 2.2, 1.2), Vec3(0, 0, 1), 80.0};
  std::unique_ptr<Interpolant> floor, wall, light;
  TestScene() {
    scene.surfaces.push_back(quad("floor", {0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, 0.5));
    scene.surfaces.push_back(quad("wall", {2, 0, 0}, {2, 4, 0}, {2, 4, 1}, {2, 0, 1}, 0.5));
    scene.surfaces.push_back(quad("light", {1, 1, 2}, {1, 2, 2}, {2, 2, 2}, {2, 1, 2}, 0.0, 40.0));
    ScatteredSamples samples;
    samples.channels = 3;
    for (double x : {0.0, 1.3, 2.9, 4.0})
      for (double y : {0.0, 2.2, 0.7, 4.0}) {
        samples.points.emplace_back(x, y);
        for (int c = 0; c < 3; ++c) samples.values.push_back(1 + x + 2 * y + c);
      }
    floor = make_scattered_interpolant(Method::natural_neighbour, samples).value();
    wall = make_scattered_interpolant(Method::shepard, samples).value();
    CellSamples lit{{Rect{0, 0, 1, 1}}, {40, 40, 40}, 3, {}};
    light = std::make_unique<PiecewiseConstant>(lit);
  }
  SideReconstruction reconstruction() const {
    return [this](SideRef side) -> const Interpolant* {
      if (side.surface == 2) return side.back_side ? nullptr : light.get();
      return side.back_side ? nullptr : side.surface == 0 ? floor.get() : wall.get();
    };
  }
};

/// Every pixel as the mean of its rays, each ray traced and evaluated alone (the renderer's
/// definition, without tiles, batches or threads), and whether every ray met a lit reflecting
/// side.
Rendering one_ray_at_a_time(const TestScene& t, const RenderOptions& options) {
  const int S = options.samples_per_axis;
  Rendering out{Image(options.width, options.height),
                std::vector<std::uint8_t>(static_cast<size_t>(options.width) * options.height, 0)};
  const SideReconstruction recon = t.reconstruction();
  for (int y = 0; y < options.height; ++y)
    for (int x = 0; x < options.width; ++x) {
      Rgb sum = Rgb::Zero();
      bool reflecting = true;
      for (int k = 0; k < S * S; ++k) {
        const auto [o, d] = camera_ray(t.camera, options.width, options.height, x + (k % S + 0.5) / S, y + (k / S + 0.5) / S);
        const auto hit = intersect_scene(t.scene, o, d);
        const Interpolant* f = hit ? recon(SideRef{hit->surface, hit->back_side}) : nullptr;
        reflecting = reflecting && f && hit->surface != 2;
        if (!f) continue;  // background and unsolved sides: black
        const Surface& s = t.scene.surfaces[hit->surface];
        const Vec2 at(hit->u * s.length_u_m(), hit->v * s.length_v_m());
        double v[3];
        f->evaluate(std::span<const Vec2>(&at, 1), v);
        for (int c = 0; c < 3; ++c) sum[c] += v[c];
      }
      out.image.at(x, y) = sum / (S * S);
      out.reflecting[static_cast<size_t>(y) * options.width + x] = reflecting;
    }
  return out;
}

/// The tests' picture: 97 x 61 pixels (odd sizes: tiles and bands that do not divide them).
RenderOptions odd_picture(int samples_per_axis) {
  RenderOptions options;
  options.width = 97;
  options.height = 61;
  options.samples_per_axis = samples_per_axis;
  return options;
}

TEST(Tiles, SamePixelsBitForBitForAnyTileAndThreads) {
  const TestScene t;
  RenderOptions options = odd_picture(3);
  const Rendering expected = one_ray_at_a_time(t, options);
  // The picture shows all of it: background, floor, wall, light.
  int reflecting = 0, other = 0;
  for (std::uint8_t r : expected.reflecting) (r ? reflecting : other)++;
  ASSERT_GT(reflecting, 1000);
  ASSERT_GT(other, 100);
  // The whole image traced at once (the paper's views) is the same.
  const Image whole = shade(t.scene, trace_camera(t.scene, t.camera, options), t.reconstruction());
  const int threads = worker_thread_count();
  for (int n_threads : {1, 2})
    for (int tile : {1, 5, 16, 64, 0, 500}) {
      set_worker_thread_count(n_threads);
      options.tile_size = tile;
      const Rendering got = render(t.scene, t.camera, t.reconstruction(), options);
      ASSERT_EQ(got.reflecting, expected.reflecting) << "tile " << tile << ", threads " << n_threads;
      for (int y = 0; y < options.height; ++y)
        for (int x = 0; x < options.width; ++x)
          for (int c = 0; c < 3; ++c) {
            ASSERT_EQ(got.image.at(x, y)[c], expected.image.at(x, y)[c])
                << x << "," << y << " tile " << tile << ", threads " << n_threads;
            ASSERT_EQ(whole.at(x, y)[c], expected.image.at(x, y)[c]) << x << "," << y;
          }
    }
  set_worker_thread_count(threads);
}

TEST(Tiles, BandsJoinedAreTheWholeTrace) {
  // join_bands() of bands of rows traced one by one (the paper's views, traced beside the
  // solves) against the whole image traced at once: the same rays, sides and points.
  const TestScene t;
  const RenderOptions options = odd_picture(2);
  const CameraHits whole = trace_camera(t.scene, t.camera, options);
  for (const int rows : {1, 7, 16, 61}) {
    std::vector<CameraHits> bands;
    for (int y = 0; y < options.height; y += rows)
      bands.push_back(trace_camera(t.scene, t.camera, options, {0, y, options.width, std::min(options.height, y + rows)}));
    const CameraHits joined = join_bands(bands);
    EXPECT_EQ(joined.rays, whole.rays) << rows;
    EXPECT_EQ(joined.pixels.pixels(), whole.pixels.pixels()) << rows;
    ASSERT_EQ(joined.sides.size(), whole.sides.size()) << rows;
    for (size_t s = 0; s < whole.sides.size(); ++s) {
      EXPECT_EQ(joined.sides[s].slot, whole.sides[s].slot) << rows;
      EXPECT_EQ(joined.sides[s].rays, whole.sides[s].rays) << rows;
      EXPECT_EQ(joined.sides[s].st, whole.sides[s].st) << rows;
    }
  }
}

TEST(Tiles, AutomaticTilesHoldAtMostTheirRaysWhateverTheRaysPerPixel) {
  RenderOptions options;
  for (int S = 1; S <= 16; ++S) {
    options.samples_per_axis = S;
    const auto side = static_cast<size_t>(tile_side(options));
    EXPECT_LE(side * side * S * S, kRenderTileRays) << S;
    EXPECT_GT(4 * side * side * S * S, kRenderTileRays) << S;  // and not needlessly small
  }
  options.samples_per_axis = 4;
  EXPECT_EQ(tile_side(options), 64);
}

TEST(Tiles, SlowPeakMemoryDoesNotGrowWithRaysPerPixel) {
  // Measured by the counting operator new above, not by the renderer's own estimate.
  const TestScene t;
  RenderOptions options;
  options.width = 300;
  options.height = 200;
  auto peak_of_render = [&](int samples) {
    options.samples_per_axis = samples;
    const long long before = live_bytes.load();
    peak_bytes = before;
    const Rendering r = render(t.scene, t.camera, t.reconstruction(), options);
    const long long peak = peak_bytes.load() - before;
    double sum = 0;
    for (int y = 0; y < options.height; ++y)
      for (int x = 0; x < options.width; ++x) sum += r.image.at(x, y).sum();
    EXPECT_GT(sum, 0.0);
    std::printf("render 300 x 200 at %d rays a pixel: peak %.2f MB allocated\n", samples * samples, peak / 1e6);
    return peak;
  };
  const long long one = peak_of_render(1), many = peak_of_render(16);
  const long long image = 300 * 200 * (static_cast<long long>(sizeof(Rgb)) + 1);
  // The image and its mask, and at most one tile of kRenderTileRays rays at ~120 bytes a ray
  // (plus the reconstructions' scratch): 256 times the rays do not take more memory. Traced at
  // once, the 16 x 16 rays would take 60,000 x 256 x 48 bytes for the hits alone (737 MB).
  EXPECT_LT(one, image + 160 * static_cast<long long>(kRenderTileRays));
  EXPECT_LT(many, image + 160 * static_cast<long long>(kRenderTileRays));
  EXPECT_LT(many, 2 * one);
}

TEST(Tiles, ProgressAfterEveryTileUpToTheWhole) {
  const TestScene t;
  RenderOptions options;
  options.width = 50;
  options.height = 30;
  options.samples_per_axis = 2;
  options.tile_size = 16;  // 4 x 2 tiles
  std::vector<double> calls;
  render(t.scene, t.camera, t.reconstruction(), options, [&](double done) { calls.push_back(done); });
  ASSERT_EQ(calls.size(), 8u);
  EXPECT_DOUBLE_EQ(calls[0], 16.0 * 16 / (50 * 30));
  for (size_t k = 1; k < calls.size(); ++k) EXPECT_GT(calls[k], calls[k - 1]);
  EXPECT_EQ(calls.back(), 1.0);
}

}  // namespace tiles_test
}  // namespace radrecon
