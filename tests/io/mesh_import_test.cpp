// Mesh import (io/mesh_import.h) of model files the test writes itself: OBJ with MTL, glTF 2.0
// (.gltf with a data URI, .glb) and PLY (whose reading mesh_import_ply_test.cpp tests); faces,
// materials, emission, placement, the "meshes" of a scene JSON and `--scene model.obj`
// (load_scene). Expected values are the numbers written into the files, combined by hand.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numeric>
#include <string>
#include <vector>

#include "io/mesh_import.h"
#include "io/scene_json.h"
#include "support/mesh_checks.h"
#include "support/model_files.h"
#include "support/temp_dir.h"

namespace radrecon {
namespace mesh_import_test {

using testing_support::expect_near;
using testing_support::kFloat;
using testing_support::named;
using testing_support::TempDir;
using testing_support::total_area;
using testing_support::write_file;

/// A 2 x 1 m floor quad (white, Kd 0.7 0.6 0.5), a lamp quad facing down (Kd 0.2, Ke 10 20 30),
/// and a convex pentagon "roof" of Kd 1.2 0.5 0.5 (clamped) whose area is 2.5 m^2 by the
/// shoelace formula: (0,0) (2,0) (2,1) (1,1.5) (0,1) in z = 2.
void write_obj(const TempDir& dir) {
  write_file(dir / "room.mtl",
             "newmtl white\nKd 0.7 0.6 0.5\n"
             "newmtl lamp\nKd 0.2 0.2 0.2\nKe 10 20 30\n"
             "newmtl hot\nKd 1.2 0.5 0.5\n");
  write_file(dir / "room.obj",
             "mtllib room.mtl\n"
             "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\n"
             "v 0.5 0.25 1\nv 0.5 0.75 1\nv 1.5 0.75 1\nv 1.5 0.25 1\n"
             "v 0 0 2\nv 2 0 2\nv 2 1 2\nv 1 1.5 2\nv 0 1 2\n"
             "o floor\nusemtl white\nf 1 2 3 4\n"
             "o lamp\nusemtl lamp\nf 5 6 7 8\n"
             "o roof\nusemtl hot\nf 9 10 11 12 13\n");
}

TEST(MeshImport, ObjQuadsKeepTheirCornersMaterialsAndEmission) {
  TempDir dir("mesh_obj");
  write_obj(dir);
  const MeshImport m = import_mesh((dir / "room.obj").string());
  EXPECT_EQ(m.faces_read, 3u);
  EXPECT_EQ(m.polygons_triangulated, 1u);
  const Surface& floor = named(m.surfaces, "floor:0");
  ASSERT_EQ(floor.corner_count, 4);
  const Vec3 want[4] = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}};
  for (int i = 0; i < 4; ++i) expect_near(floor.corners[i], want[i]);
  expect_near(floor.reflectance, Rgb(0.7, 0.6, 0.5));
  expect_near(floor.emission_w_m2, Rgb::Zero());
  const Surface& lamp = named(m.surfaces, "lamp:0");
  expect_near(lamp.emission_w_m2, Rgb(10, 20, 30));
  expect_near(lamp.reflectance, Rgb::Constant(0.2));
  expect_near(lamp.normal(), Vec3(0, 0, -1));
  EXPECT_FALSE(lamp.two_sided);
}

TEST(MeshImport, ObjPentagonIsCutIntoTrianglesOfItsAreaAndKdAboveOneIsClamped) {
  TempDir dir("mesh_obj");
  write_obj(dir);
  const MeshImport m = import_mesh((dir / "room.obj").string());
  std::vector<Surface> roof;
  for (const Surface& s : m.surfaces)
    if (s.name.rfind("roof:0.t", 0) == 0) roof.push_back(s);
  // Three fan triangles, two of which make a convex quad again: 2 surfaces.
  ASSERT_EQ(roof.size(), 2u);
  EXPECT_NEAR(total_area(roof), 2.5, kFloat);
  for (const Surface& s : roof) {
    expect_near(s.normal(), Vec3(0, 0, 1));
    expect_near(s.reflectance, Rgb(0.999, 0.5, 0.5));
  }
  EXPECT_EQ(m.surfaces.size(), 4u);
  const bool warned = std::any_of(m.warnings.begin(), m.warnings.end(), [](const std::string& w) {
    return w.find("'hot' Kd") != std::string::npos && w.find("clamped") != std::string::npos;
  });
  EXPECT_TRUE(warned);
  // With a reflectance override no Kd is used: none is said to be clamped.
  MeshPlacement grey;
  grey.reflectance = Rgb::Constant(0.3);
  const MeshImport o = import_mesh((dir / "room.obj").string(), grey);
  for (const Surface& s : o.surfaces) expect_near(s.reflectance, Rgb::Constant(0.3));
  for (const std::string& w : o.warnings) EXPECT_EQ(w.find("clamped"), std::string::npos) << w;
}

TEST(MeshImport, ObjWithoutItsMtlIsHalfGreyWithAWarning) {
  TempDir dir("mesh_obj");
  write_obj(dir);
  std::filesystem::remove(dir / "room.mtl");
  const MeshImport m = import_mesh((dir / "room.obj").string());
  for (const Surface& s : m.surfaces) {
    expect_near(s.reflectance, Rgb::Constant(0.5));
    expect_near(s.emission_w_m2, Rgb::Zero());
  }
  ASSERT_FALSE(m.warnings.empty());
  EXPECT_NE(m.warnings[0].find("mtllib 'room.mtl' not found"), std::string::npos) << m.warnings[0];
}

TEST(MeshImport, ObjFacesBeforeAnyMaterialAreHalfGreyAndDegenerateFacesAreCountedOnce) {
  TempDir dir("mesh_obj");
  write_file(dir / "plain.obj",
             "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 2 2 0\nv 3 3 0\n"
             "f 1 2 3\nf 1 4 5\nf 1 3 4\n");  // the last two: collinear corners
  const MeshImport m = import_mesh((dir / "plain.obj").string());
  ASSERT_EQ(m.surfaces.size(), 1u);
  expect_near(m.surfaces[0].reflectance, Rgb::Constant(0.5));
  EXPECT_EQ(m.degenerate_skipped, 2u);
  EXPECT_EQ(std::count_if(m.warnings.begin(), m.warnings.end(),
                          [](const std::string& w) { return w.find("2 face(s)") != std::string::npos; }),
            1);
}

TEST(MeshImport, APolygonThatCrossesItselfIsSkippedAndNamedSo) {
  // A pentagon whose edges cross (area 6 by the shoelace, yet no ear to cut), a collinear
  // pentagon (no area) and a triangle: each counted for what it is.
  TempDir dir("mesh_obj");
  write_file(dir / "crossing.obj",
             "v 0 0 0\nv 4 0 0\nv 0 4 0\nv 4 4 0\nv 2 5 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\n"
             "f 1 2 3 4 5\nf 1 6 7 8 2\nf 1 2 4\n");
  const MeshImport m = import_mesh((dir / "crossing.obj").string());
  EXPECT_EQ(m.surfaces.size(), 1u);
  EXPECT_EQ(m.self_crossing_skipped, 1u);
  EXPECT_EQ(m.degenerate_skipped, 1u);
  EXPECT_EQ(std::count_if(m.warnings.begin(), m.warnings.end(),
                          [](const std::string& w) { return w.find("1 polygon(s) of more than 4 corners that cross themselves skipped") != std::string::npos; }),
            1);
  write_file(dir / "only.obj", "v 0 0 0\nv 4 0 0\nv 0 4 0\nv 4 4 0\nv 2 5 0\nf 1 2 3 4 5\n");
  try {
    import_mesh((dir / "only.obj").string());
    ADD_FAILURE() << "accepted";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("1 crossing themselves"), std::string::npos) << e.what();
  }
}

TEST(MeshImport, ObjFaceClosedOnItsFirstCornerKeepsItsAreaAndOneValueColoursAreGrey) {
  // The pentagon of write_obj() closed on its first corner (`f 1 2 3 4 5 1`, as some exporters
  // write), a quad with a corner twice (a triangle), and MTL colours of one value (grey).
  TempDir dir("mesh_obj");
  write_file(dir / "grey.mtl", "newmtl wall\nKd 0.25\nnewmtl lamp\nKd 0\nKe 40\n");
  write_file(dir / "closed.obj",
             "mtllib grey.mtl\n"
             "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1.5 0\nv 0 1 0\n"
             "v 0 0 2\nv 0 1 2\nv 1 1 2\n"
             "o roof\nusemtl wall\nf 1 2 3 4 5 1\n"
             "o lamp\nusemtl lamp\nf 6 7 8 8\n");
  const MeshImport m = import_mesh((dir / "closed.obj").string());
  EXPECT_EQ(m.degenerate_skipped, 0u);
  std::vector<Surface> roof;
  for (const Surface& s : m.surfaces)
    if (s.name.rfind("roof:0", 0) == 0) roof.push_back(s);
  EXPECT_NEAR(total_area(roof), 2.5, kFloat);  // the shoelace area of the pentagon
  for (const Surface& s : roof) expect_near(s.reflectance, Rgb::Constant(0.25));
  const Surface& lamp = named(m.surfaces, "lamp:0");
  EXPECT_TRUE(lamp.is_triangle());
  EXPECT_NEAR(lamp.area_m2(), 0.5, kFloat);
  expect_near(lamp.emission_w_m2, Rgb::Constant(40));
  expect_near(lamp.reflectance, Rgb::Zero());
}

TEST(MeshImport, ObjMaterialsFromEveryMtllibWithSpacesByteOrderMarksAndBlendersStatements) {
  // assimp 5.2 read none of these as written (found by an outside-in trial): the second file of
  // `mtllib a.mtl b.mtl`, a file named with a space (Blender's `mtllib my mats.mtl`), an OBJ or
  // MTL starting with a UTF-8 byte-order mark, and Blender's PBR statements (`aniso`, `Pr`).
  TempDir dir("mesh_obj");
  const std::string bom = "\xEF\xBB\xBF";
  write_file(dir / "a.mtl", bom + "newmtl g\nKd 0.2 0.4 0.6\naniso 0.0\nanisor 0.0\nPr 0.5\nPm 0\n");
  write_file(dir / "b.mtl", "newmtl lamp\nKd 0\nKe 10 10 10\n");
  write_file(dir / "my mats.mtl", "newmtl s\nKd 0.1 0.2 0.3\n");
  const std::string faces = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 0 1 1\nv 1 1 1\nv 1 0 1\n"
                            "o floor\nusemtl g\nf 1 2 3 4\no lamp\nusemtl lamp\nf 5 6 7 8\n";
  write_file(dir / "two.obj", bom + "mtllib a.mtl b.mtl\r\n" + faces);
  const MeshImport two = import_mesh((dir / "two.obj").string());
  EXPECT_TRUE(two.warnings.empty()) << two.warnings.front();
  expect_near(named(two.surfaces, "floor:0").reflectance, Rgb(0.2, 0.4, 0.6));
  expect_near(named(two.surfaces, "lamp:0").emission_w_m2, Rgb::Constant(10));
  write_file(dir / "spaced.obj", "mtllib my mats.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl s\nf 1 2 3\n");
  const MeshImport spaced = import_mesh((dir / "spaced.obj").string());
  EXPECT_TRUE(spaced.warnings.empty()) << spaced.warnings.front();
  expect_near(spaced.surfaces.at(0).reflectance, Rgb(0.1, 0.2, 0.3));
}

TEST(MeshImport, ASceneKeepsAsInputsTheCompanionFilesTheReaderOpens) {
  // No output may overwrite them (found by an outside-in trial: `--out "my model.bin"` replaced
  // the buffer of a glTF naming it "my%20model.bin", and `--out bom.mtl` the MTL of an OBJ whose
  // `mtllib` line follows a byte-order mark).
  TempDir dir("mesh_inputs");
  write_file(dir / "bom.obj", "\xEF\xBB\xBFmtllib bom.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n");
  write_file(dir / "pct.gltf", R"({"asset": {"version": "2.0"}, "buffers": [{"uri": "my%20model.bin", "byteLength": 4},
                                   {"uri": "data:application/octet-stream;base64,AAAA", "byteLength": 3}]})");
  write_file(dir / "my model.bin", "abcd");
  const auto has = [](const std::vector<std::string>& files, const std::filesystem::path& f) {
    return std::any_of(files.begin(), files.end(), [&](const std::string& g) { return std::filesystem::path(g) == f; });
  };
  const std::vector<std::string> obj = scene_input_files((dir / "bom.obj").string());
  EXPECT_TRUE(has(obj, dir / "bom.mtl"));
  const std::vector<std::string> gltf = scene_input_files((dir / "pct.gltf").string());
  EXPECT_TRUE(has(gltf, dir / "my model.bin"));
  EXPECT_EQ(std::count_if(gltf.begin(), gltf.end(), [](const std::string& g) { return g.find("data:") != std::string::npos; }), 0);
}

TEST(MeshImport, ObjFarFromTheOriginKeepsItsDetailInDouble) {
  // A lamp 5 cm wide at x = 300000 m (a georeferenced model): assimp's single-precision floats
  // rounded its corners to 3.1 cm apart (37.5% of its power lost). The copy assimp reads is moved
  // to the origin and moved back in double: the corners as written, within single precision's
  // rounding of their distance to the model's centre (some 1e-8 m here).
  TempDir dir("mesh_obj");
  write_file(dir / "site.mtl", "newmtl lamp\nKe 100\n");
  write_file(dir / "site.obj",
             "mtllib site.mtl\nv 300000.02 0.02 3 # a corner\nv 300000.07 0.02 3\nv 300000.07 0.07 3\nv 300000.02 0.07 3\n"
             "v 299990 -10 0\nv 300010 -10 0\nv 300010 10 1e-400\nv 299990 10 0\n"
             "usemtl lamp\nf 4 3 2 1\nusemtl none\nf 5 6 7 8\n");
  MeshPlacement back;
  back.translate_m = Vec3(-300000, 0, 0);
  const MeshImport m = import_mesh((dir / "site.obj").string(), back);
  ASSERT_EQ(m.surfaces.size(), 2u);
  const Surface& lamp = m.surfaces[0];
  EXPECT_NEAR(lamp.area_m2(), 0.05 * 0.05, kFloat * 0.05 * 0.05);
  EXPECT_NEAR(lamp.corners[3].x(), 0.02, 1e-8);
  EXPECT_NEAR(lamp.corners[1].y(), 0.07, 1e-8);
  EXPECT_NEAR(m.surfaces[1].area_m2(), 400, kFloat * 400);
  // A coordinate that underflows (1e-400, read as 0) is moved with the others: it stayed at 0 in
  // assimp's copy and landed 1.5 m off.
  for (const Vec3& c : m.surfaces[1].corners) EXPECT_NEAR(c.z(), 0, 1e-8);
}

TEST(MeshImport, ObjPolygonOffItsPlaneIsCutThroughItsCornersWithAWarning) {
  // A hexagon whose corners rise and fall by 0.01 m in turn (1% of its 1 m sides off its plane):
  // its triangles run through its corners, and one warning says so.
  TempDir dir("mesh_obj");
  std::string obj;
  for (int k = 0; k < 6; ++k)
    obj += "v " + std::to_string(std::cos(k * M_PI / 3)) + " " + std::to_string(std::sin(k * M_PI / 3)) + " " +
           (k % 2 == 0 ? "0.01" : "-0.01") + "\n";
  write_file(dir / "crown.obj", obj + "f 1 2 3 4 5 6\n");
  const MeshImport m = import_mesh((dir / "crown.obj").string());
  EXPECT_EQ(m.polygons_triangulated, 1u);
  for (const Surface& s : m.surfaces)
    for (int i = 0; i < s.corner_count; ++i) EXPECT_NEAR(std::abs(s.corners[i].z()), 0.01, kFloat);
  const auto warned = std::count_if(m.warnings.begin(), m.warnings.end(),
                                    [](const std::string& w) { return w.find("1 polygon(s) of 5 or more corners not planar") != std::string::npos; });
  EXPECT_EQ(warned, 1);
}

TEST(MeshImport, NamesLoseSlashesControlCharactersAndInvalidUtf8AndStayUnique) {
  TempDir dir("mesh_obj");
  write_file(dir / "names.obj",
             "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
             "o a/b\x01\xff\xc3\xa9\nf 1 2 3\n"      // '/', a control byte, a stray byte, then a valid 'é'
             "o x\nf 1 3 4\no x\nf 1 2 4\n");  // assimp joins the two objects 'x' into one mesh
  MeshPlacement keep_triangles;
  keep_triangles.merge_triangles = false;
  const MeshImport m = import_mesh((dir / "names.obj").string(), keep_triangles);
  std::vector<std::string> names;
  for (const Surface& s : m.surfaces) names.push_back(s.name);
  EXPECT_EQ(names, (std::vector<std::string>{"a_b__\xc3\xa9:0", "x:0", "x:1"}));

  // glTF: mesh "quad" placed twice ("quad", "quad#2"), then a mesh that is called "quad#2".
  std::string buffer;
  nlohmann::json g = testing_support::quad_gltf(buffer);
  nlohmann::json other = g["meshes"][0];
  other["name"] = "quad#2";
  g["meshes"].push_back(other);
  g["nodes"].push_back({{"mesh", 1}, {"translation", {0, 0, 4}}});
  g["scenes"][0]["nodes"].push_back(2);
  write_file(dir / "names.gltf", testing_support::gltf_text(g, buffer));
  names.clear();
  for (const Surface& s : import_mesh((dir / "names.gltf").string()).surfaces) names.push_back(s.name);
  EXPECT_EQ(names, (std::vector<std::string>{"quad:0", "quad#2:0", "quad#2#2:0"}));
}

TEST(MeshImport, PlacementScalesRotatesAndTranslates) {
  TempDir dir("mesh_place");
  write_file(dir / "square.ply", testing_support::coloured_square_ply());
  MeshPlacement p;
  p.scale = 2;
  p.rotate_x_deg = 90;  // (x, y, z) -> (x, -z, y)
  p.translate_m = Vec3(1, 2, 3);
  p.reflectance = Rgb(0.3, 0.3, 0.3);
  p.two_sided = true;
  const MeshImport m = import_mesh((dir / "square.ply").string(), p);
  ASSERT_EQ(m.surfaces.size(), 1u);
  const Surface& s = m.surfaces[0];
  // (1, 1, 0) -> scaled (2, 2, 0) -> rotated (2, 0, 2) -> moved (3, 2, 5).
  expect_near(s.corners[2], Vec3(3, 2, 5));
  expect_near(s.corners[0], Vec3(1, 2, 3));
  expect_near(s.normal(), Vec3(0, -1, 0));  // +z turned about +x by 90 degrees
  EXPECT_NEAR(s.area_m2(), 4.0, kFloat);
  expect_near(s.reflectance, Rgb::Constant(0.3));
  EXPECT_TRUE(s.two_sided);
}

TEST(MeshImport, SceneJsonMeshesBesideHandWrittenSurfaces) {
  TempDir dir("mesh_json");
  write_file(dir / "square.ply", testing_support::coloured_square_ply());
  const std::string text = R"({"name": "with meshes",
    "surfaces": [{"name": "light", "corners": [[0,0,3],[0,1,3],[1,1,3],[1,0,3]], "reflectance": 0, "emission": 5}],
    "meshes": [{"file": "square.ply", "scale": 3, "translate": [10, 0, 0]},
               {"file": "square.ply", "emission": [1, 2, 3]}]})";
  const Scene scene = parse_scene_json(text, (dir / "scene.json").string());
  ASSERT_EQ(scene.surfaces.size(), 3u);
  const Surface& big = named(scene.surfaces, "square:0");
  expect_near(big.corners[2], Vec3(13, 3, 0));
  EXPECT_NEAR(big.area_m2(), 9.0, kFloat);
  const Surface& second = named(scene.surfaces, "square:0@1");  // the same file again
  expect_near(second.corners[2], Vec3(1, 1, 0));
  expect_near(second.emission_w_m2, Rgb(1, 2, 3));
  expect_near(second.reflectance, Rgb(0.2, 0.1, 0.05));
}

TEST(MeshImport, SceneJsonOfMeshesOnly) {
  TempDir dir("mesh_json");
  write_obj(dir);
  const Scene scene = parse_scene_json(R"({"meshes": [{"file": "room.obj"}]})", (dir / "scene.json").string());
  EXPECT_EQ(scene.surfaces.size(), 4u);
  ASSERT_EQ(scene.cameras.size(), 1u);  // none in the scene: default_camera()
  EXPECT_EQ(scene.cameras[0].name, "default");
}

TEST(MeshImport, LoadSceneTakesAModelWithAnEmitterAndRefusesOneWithout) {
  TempDir dir("mesh_load");
  write_obj(dir);
  const Scene scene = load_scene((dir / "room.obj").string());
  EXPECT_EQ(scene.name, "room");
  EXPECT_EQ(scene.surfaces.size(), 4u);
  ASSERT_EQ(scene.cameras.size(), 1u);
  EXPECT_EQ(scene.cameras[0].name, "default");
  write_file(dir / "square.ply", testing_support::coloured_square_ply());
  const std::string message = testing_support::user_error_message([&] { load_scene((dir / "square.ply").string()); });
  EXPECT_NE(message.find("square.ply"), std::string::npos) << message;
  // A PLY holds no emission at all: said so, not pointed at OBJ's Ke or glTF's emissiveFactor.
  EXPECT_NE(message.find("a PLY model has no emission"), std::string::npos) << message;
  EXPECT_EQ(message.find("emissiveFactor"), std::string::npos) << message;
  EXPECT_NE(message.find("\"meshes\""), std::string::npos) << message;
}

}  // namespace mesh_import_test
}  // namespace radrecon
