// A surface's (u, v) <-> point mapping, both ways; triangles; the regularisation of a modeller's
// quads (repeated corners, warped or concave quads become triangles).

#include <gtest/gtest.h>

#include <random>

#include "core/error.h"

#include "scene/scene.h"

#include "support/scenes.h"

namespace radrecon {
namespace surface_test {

/// A black quad (reflectance and emission 0).
Surface quad(const std::string& name, const Vec3& c0, const Vec3& c1, const Vec3& c2, const Vec3& c3) {
  return testing_support::quad(name, c0, c1, c2, c3, 0.0);
}

TEST(QuadParameters, InvertsTheBilinearMapOfAGeneralConvexQuad) {
  // A planar, convex, non-parallelogram quad in a tilted plane.
  const Vec3 o(0.3, -0.2, 1.0), a(1, 0.2, 0.5), b(-0.1, 1, 0.3);
  const Surface s = quad("q", o, o + 2.0 * a, o + 1.6 * a + 1.3 * b, o + 0.2 * a + 1.0 * b);
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> U(0, 1);
  for (int k = 0; k < 1000; ++k) {
    const double u = U(rng), v = U(rng);
    const auto uv = s.parameters(s.point(u, v));
    ASSERT_TRUE(uv.has_value());
    EXPECT_NEAR(uv->x(), u, 1e-10);
    EXPECT_NEAR(uv->y(), v, 1e-10);
  }
  EXPECT_FALSE(s.parameters(s.point(1.2, 0.5)).has_value());
  EXPECT_FALSE(s.parameters(s.point(0.5, -0.1)).has_value());
}

TEST(QuadParameters, InvertTheMapOfAQuadBarelyNoParallelogram) {
  // A unit square with one corner moved by 2e-12 to 1e-8: the bilinear term is just above the
  // parallelogram threshold (tol::kParallelogramRelative), and the textbook root of its quadratic
  // cancelled to a few digits: v in steps of 3e-5, and points 2e-5 outside the quad taken in (a
  // review). The stable root gives (u, v) to rounding, and refuses points beyond the border.
  std::mt19937 rng(33);
  std::uniform_real_distribution<double> U(0, 1);
  for (const double moved : {2e-12, 1e-10, 1e-8}) {
    const Surface s = quad("q", {0, 0, 0}, {1, 0, 0}, {1 + moved, 1, 0}, {0, 1, 0});
    for (int k = 0; k < 1000; ++k) {
      const double u = U(rng), v = U(rng);
      const auto uv = s.parameters(s.point(u, v));
      ASSERT_TRUE(uv.has_value()) << moved;
      EXPECT_NEAR(uv->x(), u, 1e-12) << moved;
      EXPECT_NEAR(uv->y(), v, 1e-12) << moved;
    }
    for (const double beyond : {1e-6, 2e-5})
      for (const Vec2& uv : {Vec2(0.5, 1 + beyond), Vec2(1 + beyond, 0.5), Vec2(-beyond, 0.3), Vec2(0.3, -beyond)})
        EXPECT_FALSE(s.parameters(s.point(uv.x(), uv.y())).has_value()) << moved << " at " << uv.transpose();
  }
}

TEST(QuadParameters, StraightLinesBendInTheFrameByAtMostTheFrameBend) {
  // The image in (s, t) of a straight line of the quad against the straight line between its
  // ends' images, by brute force (the exact inverse, 19 points a line, 300 random lines): within
  // frame_bend_m() on a twisted and a strongly sheared quad (the bound's stretch), 0 on a
  // parallelogram. Half the twist alone, in 3-D metres, was 2.25 times too small at 15 degrees
  // (a review).
  std::mt19937 rng(34);
  std::uniform_real_distribution<double> U(0, 1);
  const std::vector<Surface> quads = {quad("twisted", {0, 0, 0}, {4, 0, 0}, {3.6, 4, 0}, {0, 4, 0}),
                                      quad("sheared", {0, 0, 0}, {8, 0, 0}, {15.3105, 3.5089, 0}, {7.5175, 2.7362, 0}),
                                      quad("parallelogram", {0, 0, 0}, {4, 0, 0}, {6, 1, 0}, {2, 1, 0})};
  for (const Surface& s : quads) {
    const SurfaceFrame f = s.frame();
    double worst = 0;
    for (int k = 0; k < 300; ++k) {
      const Vec3 a = s.point(U(rng), U(rng)), b = s.point(U(rng), U(rng));
      const Vec2 sa = f.st(s.parameters(a).value()), sb = f.st(s.parameters(b).value());
      const Vec2 across = Vec2(sa.y() - sb.y(), sb.x() - sa.x()).normalized();
      for (int i = 1; i < 20; ++i)
        worst = std::max(worst, std::abs((f.st(s.parameters(a + (i / 20.0) * (b - a)).value()) - sa).dot(across)));
    }
    SCOPED_TRACE(s.name);
    EXPECT_LE(worst, s.frame_bend_m() + 1e-12);
    if (s.name == "parallelogram") EXPECT_EQ(s.frame_bend_m(), 0.0);
    else EXPECT_GT(worst, 0.1 * s.frame_bend_m());  // a bound, not far above
  }
}

Surface triangle(const std::string& name, const Vec3& c0, const Vec3& c1, const Vec3& c2) {
  Surface s;
  s.name = name;
  s.set_triangle(c0, c1, c2);
  return s;
}

TEST(TriangleParameters, InvertTheAffineMapAndGiveTheMetricFrame) {
  const Vec3 c0(0.3, -0.2, 1.0), c1(2.1, 0.4, 0.9), c2(0.5, 1.7, 0.2);
  const Surface s = triangle("t", c0, c1, c2);
  // Closed forms: area = |e1 x e2| / 2; length_u = |e1|; height = 2 area / |e1|; shear = e2.e1/|e1|.
  const Vec3 e1 = c1 - c0, e2 = c2 - c0;
  EXPECT_NEAR(s.area_m2(), 0.5 * e1.cross(e2).norm(), 1e-14);
  EXPECT_NEAR(s.normal().dot(e1.cross(e2).normalized()), 1.0, 1e-14);
  EXPECT_NEAR(s.length_u_m(), e1.norm(), 1e-14);
  EXPECT_NEAR(s.length_v_m() * s.length_u_m(), e1.cross(e2).norm(), 1e-13);
  EXPECT_NEAR(s.shear_m(), e2.dot(e1) / e1.norm(), 1e-14);
  // (s, t) = (u Lu + v shear, v Lv) is an isometry of the plane: distances agree with 3-D ones.
  auto st = [&](double u, double v) { return Vec2(u * s.length_u_m() + v * s.shear_m(), v * s.length_v_m()); };
  EXPECT_NEAR((st(0, 1) - st(1, 0)).norm(), (c2 - c1).norm(), 1e-13);
  std::mt19937 rng(32);
  std::uniform_real_distribution<double> U(0, 1);
  for (int k = 0; k < 1000; ++k) {
    double u = U(rng), v = U(rng);
    if (u + v > 1) u = 1 - u, v = 1 - v;
    const auto uv = s.parameters(s.point(u, v));
    ASSERT_TRUE(uv.has_value());
    EXPECT_NEAR(uv->x(), u, 1e-10);
    EXPECT_NEAR(uv->y(), v, 1e-10);
  }
  EXPECT_LT((s.point(1, 0) - c1).norm(), 1e-15);
  EXPECT_LT((s.point(0, 1) - c2).norm(), 1e-15);
  EXPECT_FALSE(s.parameters(s.point(0.6, 0.5)).has_value());  // beyond the hypotenuse
  EXPECT_FALSE(s.parameters(s.point(-0.1, 0.5)).has_value());
  EXPECT_TRUE(s.parameters(s.point(0.5, 0.5)).has_value());   // on it
}

Scene scene_of(std::vector<Surface> surfaces) {
  Scene scene;
  scene.name = "t";
  scene.surfaces = std::move(surfaces);
  scene.surfaces[0].emission_w_m2 = Rgb::Constant(1);
  return scene;
}

TEST(RegulariseSurfaces, ReadsAQuadWithARepeatedCornerAsATriangle) {
  Scene scene = scene_of({quad("q", Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0))});
  const auto warnings = regularise_surfaces(scene, "s.json");
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("repeated corner"), std::string::npos);
  ASSERT_EQ(scene.surfaces.size(), 1u);
  EXPECT_TRUE(scene.surfaces[0].is_triangle());
  EXPECT_NEAR(scene.surfaces[0].area_m2(), 0.5, 1e-15);
  EXPECT_NO_THROW(validate_scene(scene, "s.json"));
}

TEST(RegulariseSurfaces, SplitsAWarpedQuadAlongItsShorterDiagonalKeepingItsCorners) {
  // The published Cornell box's red wall: 0.8 mm off its plane over 0.55 m (Cornell University
  // Program of Computer Graphics, "Cornell Box Data"), in metres.
  const Vec3 c0(0.5528, 0, 0), c1(0.5496, 0, 0.5592), c2(0.556, 0.5488, 0.5592), c3(0.556, 0.5488, 0);
  Scene scene = scene_of({quad("red", c0, c1, c2, c3)});
  EXPECT_THROW(validate_scene(scene, "s.json"), UserError);  // as it stands: not planar
  const auto warnings = regularise_surfaces(scene, "s.json");
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("off its plane"), std::string::npos);
  ASSERT_EQ(scene.surfaces.size(), 2u);
  EXPECT_EQ(scene.surfaces[0].name, "red.a");
  EXPECT_EQ(scene.surfaces[1].name, "red.b");
  const double diagonal02 = (c2 - c0).norm(), diagonal13 = (c3 - c1).norm();
  const bool split13 = diagonal13 < diagonal02;
  // Both triangles together cover the quad's corners, and share the shorter diagonal.
  const Vec3 shared_a = split13 ? c1 : c0, shared_b = split13 ? c3 : c2;
  for (const Surface& t : scene.surfaces) {
    EXPECT_TRUE(t.is_triangle());
    EXPECT_EQ(t.corners[0], shared_a);
    EXPECT_TRUE(t.corners[1] == shared_b || t.corners[2] == shared_b);
  }
  EXPECT_NO_THROW(validate_scene(scene, "s.json"));
}

TEST(RegulariseSurfaces, SplitsAConcaveQuadThroughItsReflexCorner) {
  // An arrowhead: corner 2 is reflex, so only the diagonal 0-2 cuts it into two triangles.
  Scene scene = scene_of({quad("q", Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0.5, 0.5, 0), Vec3(0, 2, 0))});
  ASSERT_EQ(regularise_surfaces(scene, "s.json").size(), 1u);
  ASSERT_EQ(scene.surfaces.size(), 2u);
  double area = 0;
  for (const Surface& t : scene.surfaces) area += t.area_m2();
  EXPECT_NEAR(area, 1.0, 1e-12);  // the shoelace formula's area of the arrowhead
  EXPECT_NO_THROW(validate_scene(scene, "s.json"));
}

TEST(RegulariseSurfaces, LeavesABowTieForValidationToRefuse) {
  Scene scene = scene_of({quad("q", Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(1, 0, 0), Vec3(0, 1, 0))});
  EXPECT_TRUE(regularise_surfaces(scene, "s.json").empty());
  EXPECT_THROW(validate_scene(scene, "s.json"), UserError);
}

}  // namespace surface_test
}  // namespace radrecon
