// Mesh import (io/mesh_import.h) refusing what it cannot read whole: every malformed, truncated
// or inconsistent model file is a UserError naming the file and what is wrong, never a crash.

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstring>
#include <limits>

#include <initializer_list>
#include <string>

#include "core/limits.h"
#include "io/mesh_import.h"
#include "io/scene_json.h"
#include "support/model_files.h"
#include "support/refused_import.h"
#include "support/temp_dir.h"

namespace radrecon {
namespace mesh_import_errors_test {

using testing_support::Refused;
using testing_support::TempDir;
using testing_support::write_file;

const char* const kTriangle = "v 0 0 0\nv 1 0 0\nv 1 1 0\n";

TEST(MeshImportErrors, UnknownExtensionEmptyAndMissingFiles) {
  TempDir dir("mesh_bad");
  EXPECT_TRUE(Refused(dir, "model.stl", "solid x\nendsolid x\n", {"unknown mesh format", ".obj"}));
  EXPECT_TRUE(Refused(dir, "empty.obj", "", {"empty"}));
  EXPECT_TRUE(Refused(dir, "empty.gltf", "", {"empty"}));
  const std::string message = testing_support::user_error_message([&] { import_mesh((dir / "absent.ply").string()); });
  EXPECT_NE(message.find("absent.ply"), std::string::npos) << message;
  EXPECT_NE(message.find("cannot open"), std::string::npos) << message;
  EXPECT_NE(message.find("No such file or directory"), std::string::npos) << message;  // the system's reason
  // A folder, a pipe and a device say what they are; none is read (a FIFO hung the scene's list of
  // input files, /dev/zero read 2 GB), and the list holds the model alone.
  std::filesystem::create_directory(dir / "folder.obj");
  EXPECT_NE(testing_support::user_error_message([&] { import_mesh((dir / "folder.obj").string()); }).find("is a folder"),
            std::string::npos);
  ASSERT_EQ(::mkfifo((dir / "pipe.obj").c_str(), 0600), 0);
  EXPECT_EQ(scene_input_files((dir / "pipe.obj").string()), std::vector<std::string>{(dir / "pipe.obj").string()});
  EXPECT_NE(testing_support::user_error_message([&] { import_mesh((dir / "pipe.obj").string()); }).find("a pipe or a device"),
            std::string::npos);
  std::filesystem::create_symlink("/dev/zero", dir / "zero.gltf");
  EXPECT_EQ(scene_input_files((dir / "zero.gltf").string()).size(), 1u);
  EXPECT_NE(testing_support::user_error_message([&] { import_mesh((dir / "zero.gltf").string()); }).find("a pipe or a device"),
            std::string::npos);
}

TEST(MeshImportErrors, MtlFileOverTheInputSizeLimit) {
  TempDir dir("mesh_bad");
  write_file(dir / "big.mtl", "newmtl m\nKd 0.5 0.5 0.5\n" + std::string(4096, '#') + "\n");
  write_file(dir / "small.obj", std::string("mtllib big.mtl\n") + kTriangle + "usemtl m\nf 1 2 3\n");
  const long long saved = limit_value(Limit::file_bytes);
  set_limit(Limit::file_bytes, 1000);  // the OBJ is within it, its MTL is not
  const std::string message = testing_support::user_error_message([&] { import_mesh((dir / "small.obj").string()); });
  set_limit(Limit::file_bytes, saved);
  EXPECT_NE(message.find("big.mtl"), std::string::npos) << message;
  EXPECT_NE(message.find("--max-file-bytes"), std::string::npos) << message;
}

TEST(MeshImportErrors, GltfRequiredExtensionsNodeTransformsMorphWeightsAndExternalGlbBuffers) {
  // Each valid by the schema or not, each read by assimp 5.2 as something else with exit 0.
  TempDir dir("mesh_bad");
  std::string buffer;
  const nlohmann::json g = testing_support::quad_gltf(buffer);
  nlohmann::json quantized = g;  // int16 positions, which assimp read as floats (a floor of 3e-89 m^2)
  quantized["extensionsRequired"] = {"KHR_mesh_quantization"};
  EXPECT_TRUE(Refused(dir, "quant.gltf", testing_support::gltf_text(quantized, buffer),
                      {"extensionsRequired[0]", "KHR_mesh_quantization", "does not read"}));
  nlohmann::json strength = g;  // one it reads
  strength["extensionsRequired"] = {"KHR_materials_emissive_strength"};
  write_file((dir / "strength.gltf").string(), testing_support::gltf_text(strength, buffer));
  EXPECT_NO_THROW(import_mesh((dir / "strength.gltf").string()));

  const auto node_with = [&](const char* field, const nlohmann::json& value) {
    nlohmann::json h = g;
    h["nodes"][1][field] = value;
    return testing_support::gltf_text(h, buffer);
  };
  EXPECT_TRUE(Refused(dir, "t.gltf", node_with("translation", {0, "x", 0}), {"nodes[1].translation[1]", "number"}));
  EXPECT_TRUE(Refused(dir, "s.gltf", node_with("scale", {2}), {"nodes[1].scale", "array of 3 numbers"}));
  EXPECT_TRUE(Refused(dir, "r.gltf", node_with("rotation", {0.7071, 0, 0}), {"nodes[1].rotation", "array of 4 numbers"}));
  EXPECT_TRUE(Refused(dir, "q.gltf", node_with("rotation", {2, 0, 0, 2}), {"nodes[1].rotation", "unit quaternion", "2.828"}));
  EXPECT_TRUE(Refused(dir, "m.gltf", node_with("matrix", nlohmann::json::array({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0})),
                      {"nodes[1].matrix", "16 numbers"}));
  nlohmann::json both = g;  // node 1 has a translation already
  both["nodes"][1]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  EXPECT_TRUE(Refused(dir, "both.gltf", testing_support::gltf_text(both, buffer), {"nodes[1]", "both a matrix"}));
  // A projective bottom row (a w of 2), which assimp ignored; node 1's translation as a matrix.
  const auto node_matrix = [&](const nlohmann::json& m) {
    nlohmann::json h = g;
    h["nodes"][1].erase("translation");
    h["nodes"][1]["matrix"] = m;
    return testing_support::gltf_text(h, buffer);
  };
  EXPECT_TRUE(Refused(dir, "w.gltf", node_matrix({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 2, 2}),
                      {"nodes[1].matrix", "bottom row must be (0, 0, 0, 1)", "got (0, 0, 0, 2)"}));
  write_file((dir / "affine.gltf").string(), node_matrix({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 2, 1}));
  EXPECT_NO_THROW(import_mesh((dir / "affine.gltf").string()));
  // A unit quaternion written in single precision is read.
  write_file((dir / "unit.gltf").string(), node_with("rotation", {0.70710677, 0, 0, 0.70710677}));
  EXPECT_NO_THROW(import_mesh((dir / "unit.gltf").string()));

  nlohmann::json morph = g;  // a shape key at full weight: viewers move the quad, assimp does not
  morph["meshes"][0]["primitives"][0]["targets"] = {{{"POSITION", 0}}};
  morph["meshes"][0]["weights"] = {1.0};
  EXPECT_TRUE(Refused(dir, "morph.gltf", testing_support::gltf_text(morph, buffer), {"nodes[0]", "morph targets", "shape keys"}));
  morph["meshes"][0]["weights"] = {0.0};  // at rest: the base shape is what viewers show
  write_file((dir / "rest.gltf").string(), testing_support::gltf_text(morph, buffer));
  EXPECT_NO_THROW(import_mesh((dir / "rest.gltf").string()));

  nlohmann::json external = g;  // assimp read the views from the BIN chunk whatever their buffer
  external["buffers"][0]["uri"] = "quad.bin";
  write_file((dir / "quad.bin").string(), buffer);
  EXPECT_TRUE(Refused(dir, "external.glb", testing_support::glb_bytes(external, buffer), {"buffers[0].uri", "embed the buffer"}));
}

TEST(MeshImportErrors, GltfPositionsOfAnotherFormatOrNotFiniteAreRefused) {
  // Each read by assimp 5.2 with exit 0 (an outside-in trial): VEC3 of UNSIGNED_SHORT without the
  // quantization extension read as floats (a floor 5.6e-45 m long); a VEC2 and a NaN vertex made
  // faces of no area, dropped with a warning.
  TempDir dir("mesh_bad");
  std::string buffer;
  const nlohmann::json g = testing_support::quad_gltf(buffer);
  nlohmann::json u16 = g;
  u16["accessors"][0]["componentType"] = 5123;
  EXPECT_TRUE(Refused(dir, "u16.gltf", testing_support::gltf_text(u16, buffer),
                      {"accessors[0]", "VEC3", "5126 (FLOAT)", "5123"}));
  nlohmann::json vec2 = g;
  vec2["accessors"][0]["type"] = "VEC2";
  EXPECT_TRUE(Refused(dir, "vec2.gltf", testing_support::gltf_text(vec2, buffer), {"accessors[0]", "\"VEC2\""}));
  std::string nan_buffer = buffer;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(nan_buffer.data() + 2 * 12 + 4, &nan, sizeof nan);  // vertex 2's y
  EXPECT_TRUE(Refused(dir, "nan.gltf", testing_support::gltf_text(g, nan_buffer), {"accessors[0]", "vertex 2", "not finite"}));
  EXPECT_TRUE(Refused(dir, "nan.glb", testing_support::glb_bytes(g, nan_buffer), {"accessors[0]", "vertex 2", "not finite"}));
  write_file((dir / "fine.gltf").string(), testing_support::gltf_text(g, buffer));
  EXPECT_NO_THROW(import_mesh((dir / "fine.gltf").string()));
}

TEST(MeshImportErrors, GltfMeshesOutsideTheDefaultSceneAreNotCountedAgainstIt) {
  // assimp 5.2 reads the default scene's meshes only: a mesh of another scene, of no node, or of
  // a node in no scene was counted among the faces it should have read, and the file refused as
  // "vertex indices out of range".
  TempDir dir("mesh_scenes");
  std::string buffer;
  nlohmann::json g = testing_support::quad_gltf(buffer);
  g["meshes"].push_back(g["meshes"][0]);
  g["meshes"][1]["name"] = "elsewhere";
  g["nodes"].push_back({{"mesh", 1}});
  g["scenes"].push_back({{"nodes", {2}}});  // scene 1 shows mesh 1; the default, scene 0, does not
  write_file((dir / "two.gltf").string(), testing_support::gltf_text(g, buffer));
  const MeshImport m = import_mesh((dir / "two.gltf").string());
  EXPECT_EQ(m.faces_read, 4u) << "the default scene's two nodes, two triangles each";
  for (const Surface& s : m.surfaces) EXPECT_EQ(s.name.rfind("elsewhere", 0), std::string::npos) << s.name;
  g["scenes"].erase(1);  // node 2 in no scene
  write_file((dir / "orphan.gltf").string(), testing_support::gltf_text(g, buffer));
  EXPECT_EQ(import_mesh((dir / "orphan.gltf").string()).faces_read, 4u);
  g["scenes"].push_back({{"nodes", {2}}});
  g["scene"] = 1;  // the default now: its one node shows mesh 1
  write_file((dir / "one.gltf").string(), testing_support::gltf_text(g, buffer));
  const MeshImport shown = import_mesh((dir / "one.gltf").string());
  EXPECT_EQ(shown.faces_read, 2u) << "scene 1 shows mesh 1 once";
}

TEST(MeshImportErrors, PlacementBeyondTheSceneOrNotFinite) {
  TempDir dir("mesh_bad");
  write_file(dir / "tri.obj", std::string(kTriangle) + "f 1 2 3\n");
  MeshPlacement far;
  far.scale = 1e7;  // corner (1, 1, 0) lands 1e7 m out
  std::string message = testing_support::user_error_message([&] { import_mesh((dir / "tri.obj").string(), far); });
  EXPECT_NE(message.find("tri.obj"), std::string::npos) << message;
  EXPECT_NE(message.find("outside"), std::string::npos) << message;
  MeshPlacement nan;
  nan.translate_m = Vec3(0, std::nan(""), 0);
  message = testing_support::user_error_message([&] { import_mesh((dir / "tri.obj").string(), nan); });
  EXPECT_NE(message.find("finite"), std::string::npos) << message;
}

TEST(MeshImportErrors, GltfMissingBufferBadAccessorSchemaAndTruncation) {
  TempDir dir("mesh_bad");
  std::string buffer;
  const nlohmann::json g = testing_support::quad_gltf(buffer);
  const std::string good = testing_support::gltf_text(g, buffer);

  nlohmann::json missing = g;
  missing["buffers"][0]["uri"] = "absent.bin";
  EXPECT_TRUE(Refused(dir, "missing.gltf", missing.dump(), {"absent.bin"}));

  nlohmann::json too_long = nlohmann::json::parse(good);
  too_long["accessors"][1]["count"] = 600;  // past the end of its buffer view
  EXPECT_TRUE(Refused(dir, "accessor.gltf", too_long.dump(), {"accessors[1]", "600 elements of 2 bytes do not fit"}));
  nlohmann::json wrong_type = nlohmann::json::parse(good);
  wrong_type["accessors"][1]["type"] = "MAT4";  // 6 x 32 bytes in a view of 12 (assimp leaked on it)
  EXPECT_TRUE(Refused(dir, "type.gltf", wrong_type.dump(), {"accessors[1]", "do not fit"}));
  nlohmann::json bad_component = nlohmann::json::parse(good);
  bad_component["accessors"][0]["componentType"] = 9999;
  EXPECT_TRUE(Refused(dir, "component.gltf", bad_component.dump(), {"accessors[0]", "componentType"}));

  // Nesting: 200,000 levels in an unused member overflowed assimp's recursive reader's stack.
  const std::string deep = good.substr(0, good.rfind('}')) + ", \"extras\": " + std::string(200000, '[') +
                           std::string(200000, ']') + "}";
  EXPECT_TRUE(Refused(dir, "deep.gltf", deep, {"deep.gltf:1", "nested deeper than 256 levels"}));
  const std::string shallow = good.substr(0, good.rfind('}')) + ", \"extras\": " + std::string(200, '[') +
                              std::string(200, ']') + "}";
  write_file((dir / "shallow.gltf").string(), shallow);
  EXPECT_NO_THROW(import_mesh((dir / "shallow.gltf").string())) << "200 levels are read";

  nlohmann::json bad_index = nlohmann::json::parse(good);
  bad_index["meshes"][0]["primitives"][0]["indices"] = 7;  // no accessor 7
  EXPECT_TRUE(Refused(dir, "index.gltf", bad_index.dump(), {"accessors"}));

  // An index past the vertices inside the buffer: assimp 5.2 drops the face without a word.
  std::string wild = buffer;
  const uint16_t nine = 9;
  std::memcpy(wild.data() + 48 + 10, &nine, 2);  // the second triangle's third index
  EXPECT_TRUE(Refused(dir, "wild.gltf", testing_support::gltf_text(g, wild), {"meshes[0].primitives[0]", "vertex index 9 out of range (4 vertices)"}));
  EXPECT_TRUE(Refused(dir, "wild.glb", testing_support::glb_bytes(g, wild), {"vertex index 9 out of range"}));
  // A line loop of such indices made assimp 5.2 read past the vertices (a crash, found by fuzzing).
  nlohmann::json loop = g;
  loop["meshes"][0]["primitives"][0]["mode"] = 2;
  loop["accessors"][0]["count"] = 1;
  EXPECT_TRUE(Refused(dir, "loop.gltf", testing_support::gltf_text(loop, buffer), {"vertex index 1 out of range (1 vertices)"}));
  nlohmann::json short_loop = g;  // assimp 5.2 failed an assertion on this one (found by fuzzing)
  short_loop["meshes"][0]["primitives"][0]["mode"] = 2;
  short_loop["accessors"][1]["count"] = 1;
  EXPECT_TRUE(Refused(dir, "short_loop.gltf", testing_support::gltf_text(short_loop, buffer), {"line loop", "fewer than 2"}));

  nlohmann::json no_asset = nlohmann::json::parse(good);
  no_asset.erase("asset");  // required by the schema
  EXPECT_TRUE(Refused(dir, "schema.gltf", no_asset.dump(), {"asset", "missing"}));
  nlohmann::json version1 = nlohmann::json::parse(good);
  version1["asset"]["version"] = "1.0";
  EXPECT_TRUE(Refused(dir, "version.gltf", version1.dump(), {"asset.version", "2.0"}));

  EXPECT_TRUE(Refused(dir, "truncated.gltf", good.substr(0, good.size() / 2), {"not valid JSON"}));
  const std::string glb = testing_support::glb_bytes(g, buffer);
  EXPECT_TRUE(Refused(dir, "truncated.glb", glb.substr(0, glb.size() - 20), {"truncated", "header's length"}));
  EXPECT_TRUE(Refused(dir, "cut.glb", glb.substr(0, 40), {"truncated"}));

  nlohmann::json negative = nlohmann::json::parse(good);
  negative["materials"][1]["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"] = -2;
  EXPECT_TRUE(Refused(dir, "strength.gltf", negative.dump(), {"materials[1]", "emissiveStrength", ">= 0"}));

  nlohmann::json huge = nlohmann::json::parse(good);  // the message once printed 309 digits
  huge["materials"][1]["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"] = 1e308;
  EXPECT_TRUE(Refused(dir, "huge.gltf", huge.dump(), {"emissiveFactor x emissiveStrength", "at most 1e+12", "e+308"}));

  // Triangles take their corners three at a time (glTF 2.0, 3.7.2.1); assimp 5.2 dropped the rest.
  nlohmann::json unindexed = g;
  unindexed["meshes"][0]["primitives"][0].erase("indices");  // 4 vertices
  EXPECT_TRUE(Refused(dir, "unindexed.gltf", testing_support::gltf_text(unindexed, buffer),
                      {"meshes[0].primitives[0]", "4 vertices without indices", "not a multiple of 3"}));
  nlohmann::json five = g;
  five["accessors"][1]["count"] = 5;
  EXPECT_TRUE(Refused(dir, "five.gltf", testing_support::gltf_text(five, buffer), {"5 indices", "not a multiple of 3"}));

  nlohmann::json nan_buffer = nlohmann::json::parse(good);
  std::string nan_bytes = buffer;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(nan_bytes.data() + 4, &nan, 4);  // vertex 0's y
  EXPECT_TRUE(Refused(dir, "nan.gltf", testing_support::gltf_text(g, nan_bytes), {"not finite"}));
}

TEST(MeshImportErrors, GltfIntegerFieldsOutsideTheSchemaAreRefusedNamingTheField) {
  // assimp 5.2 reads a negative or fractional integer field as its default: an indices accessor
  // at byteOffset -2 was read from offset 0 (other indices, a lamp 79 times too bright, exit 0).
  TempDir dir("mesh_bad");
  std::string buffer;
  const nlohmann::json g = testing_support::quad_gltf(buffer);
  const auto with = [&](const nlohmann::json::json_pointer& field, const nlohmann::json& value) {
    nlohmann::json h = g;
    h[field] = value;
    return testing_support::glb_bytes(h, buffer);
  };
  using P = nlohmann::json::json_pointer;
  EXPECT_TRUE(Refused(dir, "offset.glb", with(P("/accessors/1/byteOffset"), -2),
                      {"accessors[1].byteOffset", "an integer >= 0", "got -2"}));
  EXPECT_TRUE(Refused(dir, "view_offset.glb", with(P("/bufferViews/1/byteOffset"), -2), {"bufferViews[1].byteOffset", "got -2"}));
  EXPECT_TRUE(Refused(dir, "half.glb", with(P("/accessors/1/byteOffset"), 1.5), {"accessors[1].byteOffset", "got 1.5"}));
  EXPECT_TRUE(Refused(dir, "real.glb", with(P("/accessors/0/count"), 4.0), {"accessors[0].count", "an integer >= 1", "got 4.0"}));
  EXPECT_TRUE(Refused(dir, "count0.glb", with(P("/accessors/1/count"), 0), {"accessors[1].count", "an integer >= 1", "got 0"}));
  EXPECT_TRUE(Refused(dir, "length0.glb", with(P("/bufferViews/0/byteLength"), 0), {"bufferViews[0].byteLength", "got 0"}));
  EXPECT_TRUE(Refused(dir, "buffer.glb", with(P("/buffers/0/byteLength"), -60), {"buffers[0].byteLength", "got -60"}));
  EXPECT_TRUE(Refused(dir, "view.glb", with(P("/accessors/0/bufferView"), "0"), {"accessors[0].bufferView", "got \"0\""}));
  for (const nlohmann::json& stride : {nlohmann::json(-12), nlohmann::json(2), nlohmann::json(14), nlohmann::json(256)})
    EXPECT_TRUE(Refused(dir, "stride.glb", with(P("/bufferViews/0/byteStride"), stride),
                        {"bufferViews[0].byteStride", "a multiple of 4 in [4, 252]", "got " + stride.dump()}));
  // A primitive's indices of -1 were no indices (4 vertices, one triangle of the quad), a mode
  // of 7 no faces; a node's mesh of -1 no mesh.
  EXPECT_TRUE(Refused(dir, "indices.glb", with(P("/meshes/0/primitives/0/indices"), -1), {"meshes[0].primitives[0].indices", "got -1"}));
  EXPECT_TRUE(Refused(dir, "mode.glb", with(P("/meshes/0/primitives/0/mode"), 7), {"meshes[0].primitives[0].mode", "in [0, 6]", "got 7"}));
  EXPECT_TRUE(Refused(dir, "position.glb", with(P("/meshes/0/primitives/0/attributes/POSITION"), -1),
                      {"meshes[0].primitives[0].attributes.POSITION", "got -1"}));
  EXPECT_TRUE(Refused(dir, "material.glb", with(P("/meshes/0/primitives/0/material"), 0.5), {"meshes[0].primitives[0].material"}));
  EXPECT_TRUE(Refused(dir, "mesh.glb", with(P("/nodes/1/mesh"), -1), {"nodes[1].mesh", "got -1"}));
  EXPECT_TRUE(Refused(dir, "child.glb", with(P("/nodes/0/children"), nlohmann::json::array({-1})), {"nodes[0].children[0]", "got -1"}));
  EXPECT_TRUE(Refused(dir, "root.glb", with(P("/scenes/0/nodes"), nlohmann::json::array({0, 1.0})), {"scenes[0].nodes[1]", "got 1.0"}));
  EXPECT_TRUE(Refused(dir, "scene.glb", with(P("/scene"), -1), {"scene:", "got -1"}));
  // As the schema has them, they are read: a stride of 12 (the positions' own) and mode 4.
  nlohmann::json fine = g;
  fine["bufferViews"][0]["byteStride"] = 12;
  fine["meshes"][0]["primitives"][0]["mode"] = 4;
  write_file((dir / "fine.glb").string(), testing_support::glb_bytes(fine, buffer));
  EXPECT_EQ(import_mesh((dir / "fine.glb").string()).faces_read, 4u);
}

TEST(MeshImportErrors, GltfEmptyMeshSharedNodeAndSceneOutOfRange) {
  // The schema forbids each; assimp 5.2 dropped the mesh without a word, read a node that is a
  // child of two parents once under each (a lamp of 20.25 W shown three times, 60.75 W), and
  // said only "GLTF: No scene" for a scene index past the scenes.
  TempDir dir("mesh_bad");
  std::string buffer;
  const nlohmann::json g = testing_support::quad_gltf(buffer);
  nlohmann::json empty = g;
  empty["meshes"].push_back({{"name", "nothing"}, {"primitives", nlohmann::json::array()}});
  EXPECT_TRUE(Refused(dir, "empty.glb", testing_support::glb_bytes(empty, buffer), {"meshes[1].primitives", "at least one primitive"}));
  nlohmann::json shared = g;  // node 2 (the quad) under both node 0 and node 1
  shared["nodes"].push_back({{"mesh", 0}, {"name", "lamp"}});
  shared["nodes"][0]["children"] = {2};
  shared["nodes"][1]["children"] = {2};
  EXPECT_TRUE(Refused(dir, "shared.glb", testing_support::glb_bytes(shared, buffer),
                      {"nodes[2]", "a child of nodes[0] and of nodes[1]", "one parent"}));
  nlohmann::json twice = g;  // listed twice by one parent
  twice["nodes"].push_back({{"mesh", 0}});
  twice["nodes"][0]["children"] = {2, 2};
  EXPECT_TRUE(Refused(dir, "twice.glb", testing_support::glb_bytes(twice, buffer), {"nodes[0].children", "lists nodes[2] twice"}));
  nlohmann::json root_child = g;  // a root of the scene that is also a child
  root_child["nodes"][0]["children"] = {1};
  EXPECT_TRUE(Refused(dir, "root.glb", testing_support::glb_bytes(root_child, buffer), {"scenes[0].nodes", "nodes[1]", "a child of nodes[0]"}));
  nlohmann::json scene = g;
  scene["scene"] = 3;
  EXPECT_TRUE(Refused(dir, "scene.glb", testing_support::glb_bytes(scene, buffer), {"scene:", "3", "1 scene"}));
  nlohmann::json no_scenes = g;
  no_scenes.erase("scenes");
  EXPECT_TRUE(Refused(dir, "no_scenes.glb", testing_support::glb_bytes(no_scenes, buffer), {"scene:", "0", "no scenes"}));
}

TEST(MeshImportErrors, GlbHeaderLengthAndVersion) {
  TempDir dir("mesh_bad");
  std::string buffer;
  const std::string glb = testing_support::glb_bytes(testing_support::quad_gltf(buffer), buffer);
  // The 12-byte header alone: "no 'glTF' header" before.
  EXPECT_TRUE(Refused(dir, "header.glb", glb.substr(0, 8) + std::string("\x0C\0\0\0", 4),
                      {"truncated", "its header's length is 12 bytes", "no JSON chunk"}));
  EXPECT_TRUE(Refused(dir, "header_only.glb", glb.substr(0, 12), {"truncated", "header's length is " + std::to_string(glb.size()), "has 12"}));
  EXPECT_TRUE(Refused(dir, "short.glb", glb.substr(0, 10), {"truncated", "10 bytes", "12-byte header"}));
  EXPECT_TRUE(Refused(dir, "longer.glb", glb + std::string(8, '\0'),
                      {"header's length is " + std::to_string(glb.size()), "the file has " + std::to_string(glb.size() + 8)}));
  std::string version1 = glb;
  version1[4] = 1;
  EXPECT_TRUE(Refused(dir, "version1.glb", version1, {"header's version", "must be 2", "got 1"}));
  EXPECT_TRUE(Refused(dir, "magic.glb", "glTx" + glb.substr(4), {"no 'glTF' header"}));
}

TEST(MeshImportErrors, SceneJsonNamesTheEntryAndTheModelFile) {
  TempDir dir("mesh_bad");
  write_file(dir / "broken.obj", std::string(kTriangle) + "f 1 2 7\n");
  const std::string scene = (dir / "scene.json").string();
  const std::string message = testing_support::user_error_message(
      [&] { parse_scene_json(R"({"meshes": [{"file": "broken.obj"}]})", scene); });
  EXPECT_NE(message.find("scene.json: meshes[0].file"), std::string::npos) << message;
  EXPECT_NE(message.find("broken.obj"), std::string::npos) << message;
  const std::string scale = testing_support::user_error_message(
      [&] { parse_scene_json(R"({"meshes": [{"file": "broken.obj", "scale": -1}]})", scene); });
  EXPECT_NE(scale.find("meshes[0].scale"), std::string::npos) << scale;
  const std::string unknown = testing_support::user_error_message(
      [&] { parse_scene_json(R"({"meshes": [{"file": "broken.obj", "rotate": 1}]})", scene); });
  EXPECT_NE(unknown.find("meshes[0]"), std::string::npos) << unknown;
  // Overrides out of range are the entry's, not a surface's of the scene it makes.
  write_file(dir / "tri.obj", std::string(kTriangle) + "f 1 2 3\n");
  const std::string bright = testing_support::user_error_message(
      [&] { parse_scene_json(R"({"meshes": [{"file": "tri.obj", "reflectance": [1.5, 0.2, 0.2]}]})", scene); });
  EXPECT_NE(bright.find("meshes[0].reflectance: must be in [0,1), got 1.5"), std::string::npos) << bright;
  const std::string dark = testing_support::user_error_message(
      [&] { parse_scene_json(R"({"meshes": [{"file": "tri.obj", "emission": [0, -1, 0]}]})", scene); });
  EXPECT_NE(dark.find("meshes[0].emission: must be in [0, 1e+12] W/m^2, got -1"), std::string::npos) << dark;
}

}  // namespace mesh_import_errors_test
}  // namespace radrecon
