// Models written by the test, imported and solved, against the closed form the solver's own
// tests use for quads (tests/support/closed_forms.h): a 4 x 4 m floor of reflectance 0.5 under a
// 1 x 1 m light of 40 W/m^2 at 2.5 m, the design brief's scene. Both files give every quad as
// two triangles, which import merges back into quads; the glTF is Y-up and placed Z-up by a
// scene JSON's "rotate_x_deg": 90.

#include <gtest/gtest.h>

#include <string>

#include "io/scene_json.h"
#include "solver/solve.h"
#include "support/closed_forms.h"
#include "support/model_files.h"
#include "support/temp_dir.h"

namespace radrecon {
namespace mesh_solve_test {

using testing_support::TempDir;
using testing_support::write_file;

/// The solver tests' bound for direct radiosity against the closed form.
constexpr double kDirectRelative = 1e-3;

/// Solves the scene (grid:40, unshot power below 1e-6 of the emitted) and checks every floor
/// element's radiosity against 0.5 x 40 x F(element centre -> light) and the light's 40.
void expect_floor_under_light(const Scene& scene, const std::string& floor, const std::string& light) {
  ASSERT_EQ(scene.surfaces.size(), 2u);
  for (const Surface& s : scene.surfaces) EXPECT_EQ(s.corner_count, 4) << s.name;  // merged
  SolveSettings settings;
  settings.residual = 1e-6;
  const Solution sol = solve_scene(scene, "grid:40", settings, "test");
  const SurfaceSolution* f = sol.find(floor);
  ASSERT_NE(f, nullptr);
  ASSERT_EQ(f->elements.size(), 1600u);
  for (const SolutionElement& e : f->elements) {
    const double expected = 0.5 * 40.0 * testing_support::floor_to_rectangle(e.center.x(), e.center.y(), 1, 1, 2, 2, 2.5);
    ASSERT_NEAR(e.center.z(), 0.0, 1e-12);
    ASSERT_NEAR(e.radiosity_w_m2[0], expected, kDirectRelative * expected) << "at " << e.center.transpose();
  }
  const SurfaceSolution* l = sol.find(light);
  ASSERT_NE(l, nullptr);
  for (const SolutionElement& e : l->elements) EXPECT_EQ(e.radiosity_w_m2[0], 40.0);
}

TEST(MeshSolve, ObjOfTrianglesMatchesTheClosedForm) {
  TempDir dir("mesh_solve");
  write_file(dir / "room.mtl", "newmtl floor\nKd 0.5 0.5 0.5\nnewmtl light\nKd 0 0 0\nKe 40 40 40\n");
  write_file(dir / "room.obj",
             "mtllib room.mtl\n"
             "v 0 0 0\nv 4 0 0\nv 4 4 0\nv 0 4 0\n"
             "v 1 1 2.5\nv 1 2 2.5\nv 2 2 2.5\nv 2 1 2.5\n"
             "o floor\nusemtl floor\nf 1 2 3\nf 1 3 4\n"
             "o light\nusemtl light\nf 5 6 7\nf 5 7 8\n");
  expect_floor_under_light(load_scene((dir / "room.obj").string()), "floor:0", "light:0");
}

TEST(MeshSolve, YUpGltfPlacedZUpMatchesTheClosedForm) {
  TempDir dir("mesh_solve");
  // Y-up: the floor is y = 0 facing +y over x in [0, 4], z in [-4, 0]; the light at y = 2.5
  // facing -y. R_x(90 deg) takes (x, y, z) to (x, -z, y).
  std::string buffer;
  for (float f : {0.f, 0.f, 0.f, 4.f, 0.f, 0.f, 4.f, 0.f, -4.f, 0.f, 0.f, -4.f,                   //
                  1.f, 2.5f, -1.f, 1.f, 2.5f, -2.f, 2.f, 2.5f, -2.f, 2.f, 2.5f, -1.f})
    testing_support::append_le(buffer, f);
  for (uint16_t i : {0, 1, 2, 0, 2, 3, 0, 1, 2, 0, 2, 3}) testing_support::append_le(buffer, i);  // per primitive
  using json = nlohmann::json;
  const json g = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0, 1}}}}},
      {"nodes", {{{"mesh", 0}}, {{"mesh", 1}}}},
      {"meshes",
       {{{"name", "floor"}, {"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 2}, {"material", 0}}}}},
        {{"name", "light"}, {"primitives", {{{"attributes", {{"POSITION", 1}}}, {"indices", 3}, {"material", 1}}}}}}},
      {"materials",
       {{{"name", "floor"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.5, 0.5, 1}}}}},
        {{"name", "light"},
         {"pbrMetallicRoughness", {{"baseColorFactor", {0, 0, 0, 1}}}},
         {"emissiveFactor", {1, 1, 1}},
         {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 40}}}}}}}},
      {"buffers", {{{"byteLength", buffer.size()}}}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}}, {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 48}},
        {{"buffer", 0}, {"byteOffset", 96}, {"byteLength", 12}}, {{"buffer", 0}, {"byteOffset", 108}, {"byteLength", 12}}}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}, {"min", {0, 0, -4}}, {"max", {4, 0, 0}}},
        {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}, {"min", {1, 2.5, -2}}, {"max", {2, 2.5, -1}}},
        {{"bufferView", 2}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}},
        {{"bufferView", 3}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}}}};
  write_file(dir / "room.gltf", testing_support::gltf_text(g, buffer));
  const Scene scene = parse_scene_json(R"({"meshes": [{"file": "room.gltf", "rotate_x_deg": 90}]})",
                                       (dir / "scene.json").string());
  expect_floor_under_light(scene, "floor:0", "light:0");
}

}  // namespace mesh_solve_test
}  // namespace radrecon
