// Triangles in the mesh: parameter cells (half-boxes), their 4-way split, the regular subdivision
// of a triangle and the quadtree over one, against closed forms (areas, centroids, counts) and
// defining properties (the parts tile the parent; every point has exactly one leaf).

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mesh/grid_mesh.h"
#include "mesh/quadtree.h"
#include "scene/param_cell.h"
#include "support/scenes.h"

namespace radrecon {
namespace triangle_mesh_test {

/// Whether (u, v) lies in the closed cell, by its vertices' half-planes (independent of
/// ParamCell::quarter_of()).
bool contains(const ParamCell& c, const Vec2& p, double slack = 1e-12) {
  const auto v = c.vertices();
  const int n = c.vertex_count();
  for (int k = 0; k < n; ++k) {
    const Vec2 e = v[(k + 1) % n] - v[k], d = p - v[k];
    if (e.x() * d.y() - e.y() * d.x() < -slack) return false;
  }
  return true;
}

Surface triangle() {
  Surface s;
  s.name = "t";
  s.set_triangle(Vec3(0.2, 0.1, 0.0), Vec3(2.2, 0.4, 0.3), Vec3(0.7, 1.9, -0.2));
  return s;
}

TEST(ParamCell, QuartersTileEachShapeAndQuarterOfAgreesWithContainment) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(0, 1);
  for (const CellShape shape : {CellShape::box, CellShape::lower, CellShape::upper}) {
    const ParamCell cell{0.25, 0.5, 0.75, 0.625, shape};
    double area = 0;
    for (const ParamCell& q : cell.quarters()) {
      area += q.area();
      // Each quarter lies in the cell: its vertices do.
      for (int k = 0; k < q.vertex_count(); ++k) EXPECT_TRUE(contains(cell, q.vertices()[k]));
    }
    EXPECT_NEAR(area, cell.area(), 1e-15);
    for (int k = 0; k < 2000; ++k) {
      const Vec2 p(cell.u0 + U(rng) * (cell.u1 - cell.u0), cell.v0 + U(rng) * (cell.v1 - cell.v0));
      if (!contains(cell, p, 0)) continue;
      const int q = cell.quarter_of(p.x(), p.y());
      EXPECT_TRUE(contains(cell.quarters()[static_cast<size_t>(q)], p)) << cell_shape_name(shape) << " " << p.transpose();
    }
  }
}

TEST(ParamCell, MidpointsAreNSquaredPointsAveragingToTheCentroid) {
  for (const CellShape shape : {CellShape::box, CellShape::lower, CellShape::upper}) {
    const ParamCell cell{0.1, 0.2, 0.5, 0.4, shape};
    for (const int n : {1, 2, 5}) {
      int count = 0;
      Vec2 sum = Vec2::Zero();
      cell.for_each_midpoint(n, [&](const Vec2& p) {
        ++count;
        sum += p;
        EXPECT_TRUE(contains(cell, p, 0));
      });
      EXPECT_EQ(count, n * n);
      // Equal-area parts: the mean of their centroids is the cell's centroid.
      EXPECT_NEAR((sum / count - cell.centroid()).norm(), 0, 1e-15);
    }
  }
}

TEST(ParamCell, SubcellsTileTheCellWithTheMidpointsAsCentroids) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(0, 1);
  for (const CellShape shape : {CellShape::box, CellShape::lower, CellShape::upper}) {
    const ParamCell cell{0.1, 0.2, 0.5, 0.4, shape};
    for (const int n : {1, 2, 4, 5}) {
      std::vector<Vec2> midpoints;
      cell.for_each_midpoint(n, [&](const Vec2& p) { midpoints.push_back(p); });
      std::vector<ParamCell> cells;
      cell.for_each_subcell(n, [&](const ParamCell& c) { cells.push_back(c); });
      ASSERT_EQ(cells.size(), midpoints.size());
      for (size_t k = 0; k < cells.size(); ++k) {
        EXPECT_NEAR((cells[k].centroid() - midpoints[k]).norm(), 0, 1e-15) << cell_shape_name(shape) << " n " << n << " cell " << k;
        EXPECT_NEAR(cells[k].area(), cell.area() / (n * n), 1e-15);
      }
      // A tiling: every point of the cell lies in exactly one subcell (up to their shared edges).
      for (int k = 0; k < 500; ++k) {
        const Vec2 p(cell.u0 + U(rng) * (cell.u1 - cell.u0), cell.v0 + U(rng) * (cell.v1 - cell.v0));
        if (!contains(cell, p, 0)) continue;
        int holders = 0;
        for (const ParamCell& c : cells) holders += contains(c, p, 0) ? 1 : 0;
        EXPECT_EQ(holders, 1) << cell_shape_name(shape) << " n " << n << " at " << p.transpose();
      }
    }
  }
}

TEST(TriangleGridMesh, AQuadCutAlongItsDiagonalMeshesAsItsGridOfSquaresCutInTwo) {
  // A unit square, and beside it the same square as two triangles (as a modeller exports it, or
  // as a warped quad is split): at any grid:N the triangles' cells are the square's cells, each
  // cut in two along its diagonal: the same n, half the area, corners on the same lattice.
  using testing_support::quad;
  Scene scene;
  scene.surfaces.push_back(quad("square", {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, 0.5));
  Scene halves;
  halves.surfaces.push_back(quad("halves", {2, 0, 0}, {3, 0, 0}, {3, 1, 0}, {2, 1, 0}, 0.5));
  for (const Surface& t : testing_support::as_triangles(halves).surfaces) scene.surfaces.push_back(t);
  for (const int divisions : {3, 8, 13, 40}) {
    const Mesh mesh = make_grid_mesh(scene, {divisions, 1});
    ASSERT_EQ(mesh.surfaces.size(), 3u);
    const MeshSurface& square = mesh.surfaces[0];
    ASSERT_EQ(square.nu, square.nv);
    const int n = square.nu;
    const double cell_m2 = 1.0 / (double(n) * n);
    for (size_t k : {1u, 2u}) {
      const MeshSurface& half = mesh.surfaces[k];
      EXPECT_EQ(half.nu, n) << "divisions " << divisions;
      ASSERT_EQ(half.elements.size(), static_cast<size_t>(n) * n);
      for (const MeshElement& e : half.elements) {
        EXPECT_NEAR(e.area_m2, 0.5 * cell_m2, 1e-12);
        for (int c = 0; c < e.corner_count(); ++c)
          for (const double x : {e.corners[c].x() - 2.0, e.corners[c].y()})
            EXPECT_NEAR(x * n, std::round(x * n), 1e-9) << "a corner off the square's lattice, divisions " << divisions;
      }
    }
  }
}

TEST(TriangleGridMesh, TheMeshDoesNotDependOnWhichCornerIsListedFirst) {
  // A right triangle of legs 4 m beside a wall: listed from its right-angled corner, its base
  // (edge 0 -> 1) is a leg; from another corner, the hypotenuse. grid:N's element size came from
  // the base or the height, so one listing meshed the whole scene with 256 floor elements and
  // the other with 121 (an outside-in trial). Now 1/N of the longest edge, 5.66 m, either way.
  using testing_support::quad;
  const Vec3 a(0, 0, 0), b(4, 0, 0), c(0, 4, 0);
  std::vector<size_t> counts;
  for (const std::array<Vec3, 3>& corners : {std::array{a, b, c}, std::array{b, c, a}, std::array{c, a, b}}) {
    Scene scene;
    Surface floor;
    floor.name = "floor";
    floor.set_triangle(corners[0], corners[1], corners[2]);
    scene.surfaces = {floor, quad("wall", {1, 0.5, 0}, {1, 0.5, 1}, {1, 2.5, 1}, {1, 2.5, 0}, 0.5)};
    EXPECT_NEAR(longest_edge_m(scene), 4 * std::sqrt(2.0), 1e-12);
    const Mesh mesh = make_grid_mesh(scene, {16, 1});
    // The floor: round(5.66 / (sqrt 2 x 5.66 / 16)) = 11 cells along every edge, 121 elements;
    // the wall 2 m x 1 m: round(2 / 0.354) x round(1 / 0.354) = 6 x 3.
    EXPECT_EQ(mesh.surfaces[0].elements.size(), 121u);
    EXPECT_EQ(mesh.surfaces[1].elements.size(), 18u);
    counts.push_back(mesh.element_count());
  }
  EXPECT_EQ(counts[0], counts[1]);
  EXPECT_EQ(counts[1], counts[2]);
}

TEST(TriangleGridMesh, IsTheRegularSubdivisionIntoNSquaredEqualTriangles) {
  Scene scene;
  scene.surfaces = {triangle()};
  const Surface& s = scene.surfaces[0];
  const Mesh mesh = make_grid_mesh(scene, {9, 1});
  ASSERT_EQ(mesh.surfaces.size(), 1u);
  const MeshSurface& m = mesh.surfaces[0];
  // Elements of 1/9 of the longest edge, 2.18 m (edge 1 -> 2), that edge against a square
  // element's diagonal: round(2.18 / (sqrt 2 x 2.18 / 9)) = round(6.36) = 6.
  const double longest_m = (s.corners[2] - s.corners[1]).norm();
  ASSERT_NEAR(longest_m, 2.1794, 1e-4);
  ASSERT_EQ(m.nu, 6);
  ASSERT_EQ(m.elements.size(), 36u);
  EXPECT_EQ(grid_element_count(scene, {9, 1}), 36u);
  Vec3 moment = Vec3::Zero();
  for (const MeshElement& e : m.elements) {
    EXPECT_NEAR(e.area_m2, s.area_m2() / 36, 1e-14);
    EXPECT_EQ(e.corner_count(), 3);
    moment += e.area_m2 * e.center;
    // Front side: counter-clockwise about the surface's normal.
    EXPECT_GT((e.corners[1] - e.corners[0]).cross(e.corners[2] - e.corners[0]).dot(s.normal()), 0);
  }
  const Vec3 centroid = (s.corners[0] + s.corners[1] + s.corners[2]) / 3;
  EXPECT_NEAR((moment / s.area_m2() - centroid).norm(), 0, 1e-14);
  // Cells beyond the hypotenuse hold nothing; on it, only a lower half.
  EXPECT_EQ(m.cell_elements(5, 0).second - m.cell_elements(5, 0).first, 1u);
  EXPECT_EQ(m.cell_elements(5, 1).second - m.cell_elements(5, 1).first, 0u);
  EXPECT_EQ(m.cell_elements(1, 3).second - m.cell_elements(1, 3).first, 2u);
}

TEST(TriangleQuadtree, SplitsIntoFourCongruentTrianglesAndLocatesEveryPoint) {
  const Surface s = triangle();
  Quadtree tree(s, false);
  const int first = tree.split(0);
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(tree.node(first + c).area_m2, s.area_m2() / 4, 1e-14);
  tree.split(first + 3);  // the middle, an upper half
  tree.split(first + 1);
  EXPECT_EQ(tree.leaf_count(), 10);
  double area = 0;
  for (const int k : tree.leaves()) area += tree.node(k).area_m2;
  EXPECT_NEAR(area, s.area_m2(), 1e-14);
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> U(0, 1);
  for (int k = 0; k < 2000; ++k) {
    double u = U(rng), v = U(rng);
    if (u + v > 1) u = 1 - u, v = 1 - v;
    const QuadNode& leaf = tree.node(tree.locate(u, v));
    EXPECT_TRUE(leaf.is_leaf());
    EXPECT_TRUE(contains(leaf, Vec2(u, v)));
  }
  // The longest edge of a quarter is half the triangle's.
  EXPECT_NEAR(tree.node(first).size_m, 0.5 * (s.corners[2] - s.corners[1]).norm(), 1e-14);
}

TEST(TriangleGridMesh, BackSideElementsTurnTheOtherWay) {
  Scene scene;
  scene.surfaces = {triangle()};
  scene.surfaces[0].two_sided = true;
  const Mesh mesh = make_grid_mesh(scene, {3, 1});
  ASSERT_EQ(mesh.surfaces.size(), 2u);
  const MeshSurface& back = mesh.surfaces[1];
  for (const MeshElement& e : back.elements)
    EXPECT_GT((e.corners[1] - e.corners[0]).cross(e.corners[2] - e.corners[0]).dot(back.normal), 0);
}

}  // namespace triangle_mesh_test
}  // namespace radrecon
