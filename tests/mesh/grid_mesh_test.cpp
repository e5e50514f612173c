// Regular-grid meshing of the paper scene: element counts from the element size and the
// surfaces' caps, and the geometry of every element against closed forms for rectangles.

#include <gtest/gtest.h>

#include <string>

#include "mesh/grid_mesh.h"
#include "scene/scene.h"

namespace radrecon {
namespace grid_mesh_test {

// Element geometry is a few multiplications of metre-scale numbers; sums over up to 160000
// elements accumulate round-off of order n * eps, far below 1e-9 relative.
constexpr double kGeometry = 1e-12;
constexpr double kAreaSumRelative = 1e-9;

struct Expected {
  std::string name;
  int nu, nv;
};

const MeshSurface& Side(const Mesh& mesh, const std::string& name) {
  auto i = mesh.find(name);
  EXPECT_TRUE(i.has_value()) << "no mesh surface " << name;
  if (!i) throw std::runtime_error("no mesh surface " + name);
  return mesh.surfaces[*i];
}

void ExpectCounts(const Mesh& mesh, const std::vector<Expected>& expected) {
  ASSERT_EQ(mesh.surfaces.size(), expected.size());
  size_t total = 0;
  for (const Expected& e : expected) {
    const MeshSurface& s = Side(mesh, e.name);
    EXPECT_EQ(s.nu, e.nu) << e.name;
    EXPECT_EQ(s.nv, e.nv) << e.name;
    EXPECT_EQ(s.elements.size(), static_cast<size_t>(e.nu) * e.nv) << e.name;
    total += static_cast<size_t>(e.nu) * e.nv;
  }
  EXPECT_EQ(mesh.element_count(), total);
}

TEST(GridMesh, PaperSceneAt16DivisionsHasTheExpectedGrids) {
  // Longest edge: the 4 m ground, so elements are 0.25 m: walls 2 m x 1 m -> 8 x 4, the 1 m light
  // 4 x 4 (also its max_divisions).
  const Mesh mesh = make_grid_mesh(paper_scene(), GridMeshOptions{16, 2});
  ExpectCounts(mesh, {{"ground", 16, 16},
                      {"light", 4, 4},
                      {"wall1/front", 8, 4},
                      {"wall1/back", 8, 4},
                      {"wall2/front", 8, 4},
                      {"wall2/back", 8, 4}});
}

TEST(GridMesh, PaperSceneAt400DivisionsCapsTheWallsAndLight) {
  // Elements of 1 cm would give 200 x 100 on a wall; max_divisions 64 scales that to 64 x 32.
  // The light would get 100 x 100 and is capped at 4 x 4.
  const Mesh mesh = make_grid_mesh(paper_scene(), GridMeshOptions{400, 2});
  ExpectCounts(mesh, {{"ground", 400, 400},
                      {"light", 4, 4},
                      {"wall1/front", 64, 32},
                      {"wall1/back", 64, 32},
                      {"wall2/front", 64, 32},
                      {"wall2/back", 64, 32}});
  const Scene scene = paper_scene();
  double sum = 0;
  for (const MeshElement& e : Side(mesh, "ground").elements) sum += e.area_m2;
  EXPECT_NEAR(sum, 16.0, 16.0 * kAreaSumRelative);
}

TEST(GridMesh, ElementGeometryMatchesTheSurfaceRectangles) {
  const Scene scene = paper_scene();
  const Mesh mesh = make_grid_mesh(scene, GridMeshOptions{16, 2});
  for (const MeshSurface& side : mesh.surfaces) {
    SCOPED_TRACE(side.name);
    ASSERT_LT(side.scene_surface, scene.surfaces.size());
    const Surface& s = scene.surfaces[side.scene_surface];
    // Every surface of the paper scene is a rectangle: corner 0 plus the two edge vectors.
    const Vec3 o = s.corners[0], eu = s.corners[1] - s.corners[0], ev = s.corners[3] - s.corners[0];
    const double surface_area = eu.cross(ev).norm();
    const Vec3 front_normal = eu.cross(ev).normalized();
    const Vec3 side_normal = side.back_side ? Vec3(-front_normal) : front_normal;
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(side.normal[k], side_normal[k], kGeometry);
    EXPECT_EQ(side.back_side, side.name.size() > 5 && side.name.substr(side.name.size() - 5) == "/back");

    double sum = 0;
    for (int j = 0; j < side.nv; ++j)
      for (int i = 0; i < side.nu; ++i) {
        const MeshElement& e = side.element(i, j);
        EXPECT_NEAR(e.u0, double(i) / side.nu, kGeometry);
        EXPECT_NEAR(e.u1, double(i + 1) / side.nu, kGeometry);
        EXPECT_NEAR(e.v0, double(j) / side.nv, kGeometry);
        EXPECT_NEAR(e.v1, double(j + 1) / side.nv, kGeometry);
        const double uc = (i + 0.5) / side.nu, vc = (j + 0.5) / side.nv;
        const Vec3 centre = o + uc * eu + vc * ev;
        EXPECT_LT((e.center - centre).norm(), kGeometry) << "element " << i << "," << j;
        EXPECT_NEAR(e.area_m2, surface_area / (side.nu * side.nv), kGeometry);
        // Corners counter-clockwise seen from this side's front: their normal is the side's.
        const Vec3 n = (e.corners[1] - e.corners[0]).cross(e.corners[3] - e.corners[0]);
        EXPECT_GT(n.dot(side_normal), 0.0) << "element " << i << "," << j;
        sum += e.area_m2;
      }
    EXPECT_NEAR(sum, surface_area, surface_area * kAreaSumRelative);
  }
}

TEST(GridMesh, BackSideIsTheFrontTurnedOver) {
  const Scene scene = paper_scene();
  const Mesh mesh = make_grid_mesh(scene, GridMeshOptions{16, 2});
  for (const std::string wall : {"wall1", "wall2"}) {
    SCOPED_TRACE(wall);
    const MeshSurface& front = Side(mesh, wall + "/front");
    const MeshSurface& back = Side(mesh, wall + "/back");
    EXPECT_FALSE(front.back_side);
    EXPECT_TRUE(back.back_side);
    EXPECT_EQ(front.scene_surface, back.scene_surface);
    EXPECT_NEAR((front.normal + back.normal).norm(), 0.0, kGeometry);
    EXPECT_NEAR(front.normal.norm(), 1.0, kGeometry);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(back.emission_w_m2[c], 0.0);  // only fronts emit
    ASSERT_EQ(front.elements.size(), back.elements.size());
    for (size_t k = 0; k < front.elements.size(); ++k) {
      EXPECT_LT((front.elements[k].center - back.elements[k].center).norm(), kGeometry);
      EXPECT_NEAR(front.elements[k].area_m2, back.elements[k].area_m2, kGeometry);
    }
  }
  // One-sided surfaces keep their plain names.
  EXPECT_TRUE(mesh.find("ground").has_value());
  EXPECT_FALSE(mesh.find("ground/front").has_value());
  EXPECT_FALSE(mesh.find("wall1").has_value());
}

}  // namespace grid_mesh_test
}  // namespace radrecon
