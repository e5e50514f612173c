// The test path tracer's own parts (tests/support/path_tracer.h, ray_scene.h): its area-uniform
// points on quads that are not parallelograms and on triangles, and its ray-triangle test.

#include <gtest/gtest.h>

#include <random>

#include "support/path_tracer.h"
#include "support/scenes.h"

namespace radrecon {
namespace path_tracer_test {

using testing_support::intersect_quad;
using testing_support::uniform_point;

/// Area centroid of a planar polygon: the area-weighted mean of a fan of triangles' centroids.
Vec3 area_centroid(const Surface& s) {
  const auto p = s.polygon();
  Vec3 sum = Vec3::Zero();
  double area = 0;
  for (size_t i = 1; i + 1 < p.size(); ++i) {
    const double a = 0.5 * (p[i] - p[0]).cross(p[i + 1] - p[0]).norm();
    sum += a * (p[0] + p[i] + p[i + 1]) / 3.0;
    area += a;
  }
  return sum / area;
}

/// Mean of uniform_point() over N x N stratified (a, b).
Vec3 sampled_mean(const Surface& s, int n) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> U(0, 1);
  Vec3 sum = Vec3::Zero();
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) sum += uniform_point(s, (i + U(rng)) / n, (j + U(rng)) / n);
  return sum / (double(n) * n);
}

TEST(PathTracerSupport, UniformPointsHaveTheAreaCentroidAsMean) {
  // A trapezoid (its bilinear map is not area-uniform: its (0.5, 0.5) is not the centroid).
  Surface trapezoid;
  trapezoid.corners = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(1.5, 1, 0), Vec3(0.5, 1, 0)};
  EXPECT_GT((trapezoid.point(0.5, 0.5) - area_centroid(trapezoid)).norm(), 0.03);
  EXPECT_LT((sampled_mean(trapezoid, 400) - area_centroid(trapezoid)).norm(), 1e-3);
  Surface triangle;
  triangle.set_triangle(Vec3(0, 0, 0), Vec3(1, 0, 0.5), Vec3(0.2, 1, 0));
  EXPECT_LT((sampled_mean(triangle, 400) - area_centroid(triangle)).norm(), 1e-3);
}

TEST(PathTracerSupport, RaysMeetATriangleInsideItsHypotenuseOnly) {
  Surface t;
  t.set_triangle(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0));  // faces +z
  const Vec3 down(0, 0, -1);
  EXPECT_TRUE(intersect_quad(t, Vec3(0.49, 0.49, 1), down, 0, 10));   // just inside x + y = 1
  EXPECT_FALSE(intersect_quad(t, Vec3(0.51, 0.51, 1), down, 0, 10));  // just outside it
  EXPECT_FALSE(intersect_quad(t, Vec3(0.9, 0.9, 1), down, 0, 10));    // inside the quad it would span
  EXPECT_NEAR(*intersect_quad(t, Vec3(0.2, 0.3, 1), down, 0, 10), 1.0, 1e-15);
}

TEST(PathTracerSupport, ASurfaceLyingOnAnotherCoversItOnTheSideItShows) {
  // A two-sided slab at z = 1 and a smaller one-sided lamp lying on its underside, facing down
  // (the Cornell box's light on its ceiling), listed in either order.
  using testing_support::quad;
  const Surface slab = quad("slab", Vec3(0, 0, 1), Vec3(0, 4, 1), Vec3(4, 4, 1), Vec3(4, 0, 1), 0.5);  // faces -z
  Surface two_sided = slab;
  two_sided.two_sided = true;
  const Surface lamp = quad("lamp", Vec3(1, 1, 1), Vec3(1, 2, 1), Vec3(2, 2, 1), Vec3(2, 1, 1), 0, 10);  // faces -z
  ASSERT_LT(slab.normal().z(), 0);
  ASSERT_LT(lamp.normal().z(), 0);
  for (const bool lamp_first : {false, true}) {
    Scene scene;
    scene.surfaces = lamp_first ? std::vector<Surface>{lamp, two_sided} : std::vector<Surface>{two_sided, lamp};
    const size_t lamp_index = lamp_first ? 0 : 1, slab_index = 1 - lamp_index;
    const testing_support::PathTracer tracer(scene);
    const size_t none = scene.surfaces.size();
    // From below, under the lamp: the lamp, on its front.
    auto hit = tracer.nearest(Vec3(1.5, 1.5, 0), Vec3(0, 0, 1), none);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->surface, lamp_index);
    EXPECT_TRUE(hit->front);
    // From below, beside the lamp: the slab.
    hit = tracer.nearest(Vec3(3, 3, 0), Vec3(0, 0, 1), none);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->surface, slab_index);
    // From above, over the lamp: the slab's upper side; the lamp shows nothing that way.
    hit = tracer.nearest(Vec3(1.5, 1.5, 2), Vec3(0, 0, -1), none);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->surface, slab_index);
    EXPECT_FALSE(hit->front);
  }
}

}  // namespace path_tracer_test
}  // namespace radrecon
