// Polygon work of mesh import (io/mesh_polygons.h): ear clipping against the shoelace area, the
// merging of coplanar triangle pairs into quads (a cube of 12 triangles becomes 6 quads), repeated
// corners dropped, and the distance off the plane of a warped polygon against its closed form.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <numeric>
#include <vector>

#include "io/mesh_polygons.h"

namespace radrecon {
namespace mesh_polygons_test {

constexpr double kExact = 1e-12;

Surface triangle(const std::string& name, const Vec3& a, const Vec3& b, const Vec3& c, double rho = 0.5) {
  Surface s;
  s.name = name;
  s.set_triangle(a, b, c);
  s.reflectance = Rgb::Constant(rho);
  return s;
}

double total_area(const std::vector<Surface>& surfaces) {
  return std::accumulate(surfaces.begin(), surfaces.end(), 0.0, [](double a, const Surface& s) { return a + s.area_m2(); });
}

/// The 12 triangles of the cube [0, s]^3, outward, each face split along a diagonal (alternating
/// which one, as exporters do either).
std::vector<Surface> cube_triangles(double s) {
  std::vector<Surface> out;
  const auto corner = [&](int x, int y, int z) { return Vec3(x * s, y * s, z * s); };
  // Each face: 4 corners counter-clockwise seen from outside.
  const std::array<std::array<Vec3, 4>, 6> faces = {{
      {corner(0, 0, 0), corner(0, 1, 0), corner(1, 1, 0), corner(1, 0, 0)},  // bottom, -z
      {corner(0, 0, 1), corner(1, 0, 1), corner(1, 1, 1), corner(0, 1, 1)},  // top, +z
      {corner(0, 0, 0), corner(1, 0, 0), corner(1, 0, 1), corner(0, 0, 1)},  // front, -y
      {corner(0, 1, 0), corner(0, 1, 1), corner(1, 1, 1), corner(1, 1, 0)},  // back, +y
      {corner(0, 0, 0), corner(0, 0, 1), corner(0, 1, 1), corner(0, 1, 0)},  // left, -x
      {corner(1, 0, 0), corner(1, 1, 0), corner(1, 1, 1), corner(1, 0, 1)},  // right, +x
  }};
  for (size_t f = 0; f < faces.size(); ++f) {
    const auto& q = faces[f];
    const int d = static_cast<int>(f % 2);  // diagonal 0-2 or 1-3
    out.push_back(triangle("f" + std::to_string(f) + "a", q[d], q[d + 1], q[(d + 2) % 4]));
    out.push_back(triangle("f" + std::to_string(f) + "b", q[d], q[(d + 2) % 4], q[(d + 3) % 4]));
  }
  return out;
}

TEST(MergeTrianglePairs, CubeOfTwelveTrianglesBecomesSixQuadsOfTheSameArea) {
  std::vector<Surface> cube = cube_triangles(0.7);
  const double area_before = total_area(cube);
  EXPECT_NEAR(area_before, 6 * 0.49, kExact);
  EXPECT_EQ(merge_coplanar_triangle_pairs(cube), 6u);
  ASSERT_EQ(cube.size(), 6u);
  EXPECT_NEAR(total_area(cube), area_before, kExact);
  for (size_t f = 0; f < cube.size(); ++f) {
    const Surface& q = cube[f];
    EXPECT_EQ(q.corner_count, 4);
    EXPECT_EQ(q.name, "f" + std::to_string(f) + "a");  // the first triangle's name and place
    // The face's four corners lie in one face plane of the cube, and its normal points out.
    const Vec3 n = q.normal();
    const Vec3 centre = 0.25 * (q.corners[0] + q.corners[1] + q.corners[2] + q.corners[3]);
    EXPECT_NEAR(n.dot(centre - Vec3::Constant(0.35)), 0.35, kExact);
    EXPECT_NEAR(q.area_m2(), 0.49, kExact);
    for (const Vec3& c : q.corners) EXPECT_NEAR((c - centre).dot(n), 0.0, kExact);
  }
}

TEST(MergeTrianglePairs, TrianglesOfDifferentMaterialOrPlaneOrMakingAConcaveQuadStay) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(1, 1, 0), d(0, 1, 0);
  std::vector<Surface> materials = {triangle("t0", a, b, c, 0.5), triangle("t1", a, c, d, 0.6)};
  EXPECT_EQ(merge_coplanar_triangle_pairs(materials), 0u);
  EXPECT_EQ(materials.size(), 2u);
  std::vector<Surface> folded = {triangle("t0", a, b, c), triangle("t1", a, c, Vec3(0, 1, 0.01))};
  EXPECT_EQ(merge_coplanar_triangle_pairs(folded), 0u);
  // A dart: (0,0) (1,0) (0.3,0.3) and (0,0) (0.3,0.3) (0,1) meet at a reflex corner.
  std::vector<Surface> dart = {triangle("t0", a, b, Vec3(0.3, 0.3, 0)), triangle("t1", a, Vec3(0.3, 0.3, 0), d)};
  EXPECT_EQ(merge_coplanar_triangle_pairs(dart), 0u);
  // On a straight line: (0,0) (1,0) (2,0) as corners of the union is no quad.
  std::vector<Surface> straight = {triangle("t0", a, b, Vec3(1, 1, 0)), triangle("t1", b, Vec3(2, 0, 0), Vec3(1, 1, 0))};
  EXPECT_EQ(merge_coplanar_triangle_pairs(straight), 0u);
  // Clockwise partner (the shared edge walked the same way): not merged.
  std::vector<Surface> flipped = {triangle("t0", a, b, c), triangle("t1", a, d, c)};
  EXPECT_EQ(merge_coplanar_triangle_pairs(flipped), 0u);
}

TEST(MergeTrianglePairs, GridOfTrianglesPairsAcrossTheLongestSharedEdges) {
  // A 3 x 2 grid of unit squares, each split along its 0-2 diagonal: every pair merges back into
  // its square (the diagonal, sqrt 2, is the longest edge), whatever the order.
  std::vector<Surface> grid;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i) {
      const Vec3 p(i, j, 0), q(i + 1, j, 0), r(i + 1, j + 1, 0), s(i, j + 1, 0);
      grid.push_back(triangle("a" + std::to_string(i) + std::to_string(j), p, q, r));
      grid.push_back(triangle("b" + std::to_string(i) + std::to_string(j), p, r, s));
    }
  EXPECT_EQ(merge_coplanar_triangle_pairs(grid), 6u);
  ASSERT_EQ(grid.size(), 6u);
  for (const Surface& s : grid) {
    EXPECT_EQ(s.corner_count, 4);
    EXPECT_NEAR(s.area_m2(), 1.0, kExact);
    EXPECT_NEAR(s.length_u_m(), 1.0, kExact);
    EXPECT_NEAR(s.length_v_m(), 1.0, kExact);
  }
}

double shoelace(const std::vector<Vec3>& p) {
  double twice = 0;
  for (size_t i = 0; i < p.size(); ++i) twice += p[i].x() * p[(i + 1) % p.size()].y() - p[(i + 1) % p.size()].x() * p[i].y();
  return 0.5 * twice;
}

TEST(TriangulatePolygon, ConcaveLShapeIsCoveredByCounterClockwiseTrianglesOfItsArea) {
  const std::vector<Vec3> l = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
  const auto tris = triangulate_polygon(l);
  ASSERT_EQ(tris.size(), 4u);
  double area = 0;
  for (const auto& t : tris) {
    const double signed_twice = (l[t[1]] - l[t[0]]).cross(l[t[2]] - l[t[0]]).z();
    EXPECT_GT(signed_twice, 0);
    area += 0.5 * signed_twice;
  }
  EXPECT_NEAR(area, shoelace(l), kExact);
  EXPECT_NEAR(area, 3.0, kExact);
  // Tilted out of the z = 0 plane the same polygon keeps its area.
  std::vector<Vec3> tilted;
  for (const Vec3& p : l) tilted.push_back(Vec3(p.x(), p.y() * std::cos(0.3), p.y() * std::sin(0.3)));
  double tilted_area = 0;
  for (const auto& t : triangulate_polygon(tilted))
    tilted_area += 0.5 * (tilted[t[1]] - tilted[t[0]]).cross(tilted[t[2]] - tilted[t[0]]).norm();
  EXPECT_NEAR(tilted_area, 3.0, kExact);
  EXPECT_TRUE(triangulate_polygon(std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}).empty());
}

TEST(TriangulatePolygon, ARingAndItsHoleJoinedByAnEdgeWalkedTwiceIsCoveredOnceAndACrossingOneRefused) {
  // A weakly simple polygon, as assimp's sample concave_polygon.obj holds one: the 4 x 4 square,
  // the edge to its 2 x 2 hole, the hole clockwise, and back. Every ear had a corner at the place
  // of one of its own inside it, so none was cut ("crosses itself"). Its area: 16 - 4 = 12.
  const std::vector<Vec3> ring = {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, {0, 0, 0},
                                  {1, 1, 0}, {1, 3, 0}, {3, 3, 0}, {3, 1, 0}, {1, 1, 0}};
  const auto tris = triangulate_polygon(ring);
  ASSERT_EQ(tris.size(), 8u);  // n - 2
  double area = 0;
  for (const auto& t : tris) {
    const double signed_twice = (ring[t[1]] - ring[t[0]]).cross(ring[t[2]] - ring[t[0]]).z();
    EXPECT_GT(signed_twice, 0);
    area += 0.5 * signed_twice;
    // No triangle reaches into the hole: its centroid lies outside (1, 3) x (1, 3).
    const Vec3 c = (ring[t[0]] + ring[t[1]] + ring[t[2]]) / 3;
    EXPECT_FALSE(c.x() > 1 && c.x() < 3 && c.y() > 1 && c.y() < 3) << c.transpose();
  }
  EXPECT_NEAR(area, 12.0, kExact);
  // A bow tie crosses itself: refused, not cut into triangles of the wrong area.
  EXPECT_TRUE(triangulate_polygon(std::vector<Vec3>{{0, 0, 0}, {2, 2, 0}, {2, 0, 0}, {0, 2, 0}}).empty());
  // A figure eight of a counter-clockwise and a clockwise loop meeting at a corner: refused.
  EXPECT_TRUE(triangulate_polygon(std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {2, 2, 0}, {2, 1, 0}, {1, 1, 0}, {0, 1, 0}}).empty());
}

TEST(DropRepeatedCorners, APolygonClosedOnItsFirstCornerOrWithACornerTwiceLosesTheRepeats) {
  const Vec3 a(0, 0, 0), b(2, 0, 0), c(2, 1, 0), d(1, 1.5, 0), e(0, 1, 0);
  std::vector<Vec3> closed = {a, b, c, d, e, a};  // `f 1 2 3 4 5 1`
  drop_repeated_corners(closed);
  EXPECT_EQ(closed, (std::vector<Vec3>{a, b, c, d, e}));
  std::vector<Vec3> twice = {a, b, b, c, a};  // a quad written with its corner b twice, closed
  drop_repeated_corners(twice);
  EXPECT_EQ(twice, (std::vector<Vec3>{a, b, c}));
  // Within 1e-9 of the longest edge (2 m) is the same corner; 1e-6 m is not.
  std::vector<Vec3> near = {a, b, b + Vec3(1e-10, 0, 0), c};
  drop_repeated_corners(near);
  EXPECT_EQ(near.size(), 3u);
  std::vector<Vec3> apart = {a, b, b + Vec3(0, 1e-6, 0), c};
  drop_repeated_corners(apart);
  EXPECT_EQ(apart.size(), 4u);
  std::vector<Vec3> point = {a, a, a};
  drop_repeated_corners(point);
  EXPECT_EQ(point.size(), 1u);
}

TEST(PolygonOffPlane, ACrownOfAlternatingHeightsIsItsHeightOverItsSideOffItsPlane) {
  // A regular hexagon of circumradius R (side R in plan) whose corners rise and fall by h in turn:
  // each edge's z-sum is 0, so Newell's normal is the z axis, the corners' mean lies in z = 0, and
  // every corner is h off that plane; each edge is hypot(R, 2h) long.
  const double kR = 1.5, kH = 0.003;
  std::vector<Vec3> crown, flat;
  for (int k = 0; k < 6; ++k) {
    const double phi = k * std::numbers::pi / 3;
    crown.emplace_back(kR * std::cos(phi), kR * std::sin(phi), k % 2 == 0 ? kH : -kH);
    flat.emplace_back(kR * std::cos(phi), kR * std::sin(phi), 0.0);
  }
  const double want = kH / std::hypot(kR, 2 * kH);
  EXPECT_NEAR(polygon_off_plane(crown), want, kExact);
  EXPECT_NEAR(polygon_off_plane(flat), 0.0, kExact);
  // Turned and moved, the same.
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  for (Vec3& p : crown) p = turn * p + Vec3(10, -4, 2);
  EXPECT_NEAR(polygon_off_plane(crown), want, kExact);
}

}  // namespace mesh_polygons_test
}  // namespace radrecon
