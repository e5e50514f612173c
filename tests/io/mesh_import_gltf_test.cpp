// Mesh import of glTF 2.0 (io/mesh_import.h), against what each test's own file holds: base
// colours, emissive strength, node transforms, .glb, buffers by URI, strips and fans, strided and
// unpadded views, materials by index, mirroring nodes.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "io/mesh_import.h"
#include "support/mesh_checks.h"
#include "support/model_files.h"
#include "support/temp_dir.h"

namespace radrecon {
namespace mesh_import_gltf_test {

using testing_support::expect_near;
using testing_support::kFloat;
using testing_support::named;
using testing_support::TempDir;
using testing_support::write_file;

void check_glow_quads(const MeshImport& m) {
  // Two instances of the two-triangle quad, each merged into one quad.
  EXPECT_EQ(m.faces_read, 4u);
  EXPECT_EQ(m.triangle_pairs_merged, 2u);
  ASSERT_EQ(m.surfaces.size(), 2u);
  for (const Surface& s : m.surfaces) {
    EXPECT_EQ(s.corner_count, 4);
    expect_near(s.reflectance, Rgb(0.4, 0.5, 0.6));
    expect_near(s.emission_w_m2, Rgb(8, 4, 2));  // emissiveFactor x emissiveStrength 8
    EXPECT_NEAR(s.area_m2(), 1.0, kFloat);
    expect_near(s.normal(), Vec3(0, 0, 1));
  }
  const Surface& lifted = named(m.surfaces, "quad#2:0");
  for (const Vec3& c : lifted.corners) EXPECT_NEAR(c.z(), 2.0, kFloat);  // node n1's translation
  for (const Vec3& c : named(m.surfaces, "quad:0").corners) EXPECT_NEAR(c.z(), 0.0, kFloat);
}

TEST(MeshImport, GltfBaseColourEmissiveStrengthAndNodeTransformsTheSameFromGlb) {
  TempDir dir("mesh_gltf");
  std::string buffer;
  const nlohmann::json g = testing_support::quad_gltf(buffer);
  write_file(dir / "glow.gltf", testing_support::gltf_text(g, buffer));
  write_file(dir / "glow.glb", testing_support::glb_bytes(g, buffer));
  for (const char* name : {"glow.gltf", "glow.glb"}) {
    SCOPED_TRACE(name);
    check_glow_quads(import_mesh((dir / name).string()));
  }
}

TEST(MeshImport, GltfBufferNamedByAPercentEncodedUri) {
  // Blender writes "my%20model.bin" for "my model.bin" (RFC 3986); assimp 5.2 opened it as written.
  TempDir dir("mesh_gltf");
  std::string buffer;
  nlohmann::json g = testing_support::quad_gltf(buffer);
  g["buffers"][0]["uri"] = "my%20model.bin";
  write_file(dir / "my model.bin", buffer);
  write_file(dir / "spaced.gltf", g.dump());
  check_glow_quads(import_mesh((dir / "spaced.gltf").string()));
  // A '%' that encodes nothing stays as written.
  g["buffers"][0]["uri"] = "100%25 %zz.bin";
  write_file(dir / "100% %zz.bin", buffer);
  write_file(dir / "percent.gltf", g.dump());
  check_glow_quads(import_mesh((dir / "percent.gltf").string()));
  // In a folder whose own name holds '%20': only the URI is decoded, by radrecon's check and by
  // assimp alike (assimp's file system decoded the whole path, folder included).
  std::filesystem::create_directories(dir / "dir%20x");
  g["buffers"][0]["uri"] = "c%20d.bin";
  write_file(dir / "dir%20x" / "c d.bin", buffer);
  write_file(dir / "dir%20x" / "in.gltf", g.dump());
  check_glow_quads(import_mesh((dir / "dir%20x" / "in.gltf").string()));
}

TEST(MeshImport, GltfStripsFansAndRepeatedIndicesAreFacesToo) {
  // The same four vertices as a strip (0 1 3 2: two triangles), a fan (0 1 2 3: two triangles)
  // and a list with a repeated index (0 1 2, 0 0 2: one degenerate triangle, skipped).
  TempDir dir("mesh_gltf");
  std::string buffer;
  nlohmann::json g = testing_support::quad_gltf(buffer);
  buffer.resize(48);
  for (uint16_t i : {0, 1, 3, 2, 0, 1, 2, 3, 0, 1, 2, 0, 0, 2}) testing_support::append_le(buffer, i);
  g["buffers"][0]["byteLength"] = buffer.size();
  g["bufferViews"][1]["byteLength"] = 28;
  g["accessors"][1]["count"] = 4;
  g["accessors"].push_back({{"bufferView", 1}, {"byteOffset", 8}, {"componentType", 5123}, {"count", 4}, {"type", "SCALAR"}});
  g["accessors"].push_back({{"bufferView", 1}, {"byteOffset", 16}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}});
  nlohmann::json& primitives = g["meshes"][0]["primitives"];
  primitives[0]["mode"] = 5;
  primitives.push_back({{"attributes", {{"POSITION", 0}}}, {"indices", 2}, {"material", 1}, {"mode", 6}});
  primitives.push_back({{"attributes", {{"POSITION", 0}}}, {"indices", 3}, {"material", 1}});
  g["scenes"][0]["nodes"] = {0};
  write_file(dir / "modes.gltf", testing_support::gltf_text(g, buffer));
  const MeshImport m = import_mesh((dir / "modes.gltf").string());
  EXPECT_EQ(m.faces_read, 6u);
  EXPECT_EQ(m.degenerate_skipped, 1u);
  double area = 0;
  for (const Surface& s : m.surfaces) area += s.area_m2();
  EXPECT_NEAR(area, 2.5, kFloat);  // strip 1 + fan 1 + the list's one triangle 0.5
  // A mesh of several primitives is one mesh each, named MESH-K (K the primitive's index) by
  // assimp 5.2; FACE counts in its primitive (docs/formats.md).
  std::vector<std::string> names;
  for (const Surface& s : m.surfaces) names.push_back(s.name);
  EXPECT_EQ(names, (std::vector<std::string>{"quad-0:0", "quad-1:0", "quad-2:0"}));
}

TEST(MeshImport, GltfStridedPositionsWhoseLastElementIsNotPadded) {
  // Valid glTF (the view's last element ends the view, as the spec allows), refused by assimp 5.2
  // ("count*stride 64 > maxSize 60"): its copy of the file gives the view its last stride.
  TempDir dir("mesh_gltf");
  const auto strided = [](bool positions_first, std::string& buffer) {
    std::string positions, indices;
    for (float f : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 1.f, 1.f, 0.f, 0.f, 1.f, 0.f}) {
      testing_support::append_le(positions, f);
      if (positions.size() % 16 == 12 && positions.size() < 60) testing_support::append_le(positions, -1.f);  // between vertices
    }
    for (uint16_t i : {0, 1, 2, 0, 2, 3}) testing_support::append_le(indices, i);
    buffer = positions_first ? positions + indices : indices + positions;
    nlohmann::json g = testing_support::quad_gltf(positions);  // its document; the buffer is this one
    g["buffers"][0]["byteLength"] = buffer.size();
    g["bufferViews"][0] = {{"buffer", 0}, {"byteOffset", positions_first ? 0 : 12}, {"byteLength", 60}, {"byteStride", 16}};
    g["bufferViews"][1] = {{"buffer", 0}, {"byteOffset", positions_first ? 60 : 0}, {"byteLength", 12}};
    return g;
  };
  std::string buffer;
  for (bool positions_first : {true, false}) {
    const nlohmann::json g = strided(positions_first, buffer);
    write_file(dir / "strided.glb", testing_support::glb_bytes(g, buffer));
    check_glow_quads(import_mesh((dir / "strided.glb").string()));
  }
  // In a .gltf the view is given the bytes after it in its buffer (the indices'); at the buffer's
  // end there are none: refused, saying how to mend the file.
  write_file(dir / "strided.gltf", testing_support::gltf_text(strided(true, buffer), buffer));
  check_glow_quads(import_mesh((dir / "strided.gltf").string()));
  write_file(dir / "end.gltf", testing_support::gltf_text(strided(false, buffer), buffer));
  const std::string message = testing_support::user_error_message([&] { import_mesh((dir / "end.gltf").string()); });
  EXPECT_NE(message.find("end.gltf: accessors[0]"), std::string::npos) << message;
  EXPECT_NE(message.find("bufferViews[0].byteLength 60"), std::string::npos) << message;
  EXPECT_NE(message.find("64"), std::string::npos) << message;
}

TEST(MeshImport, GltfPrimitiveWithoutMaterialIsHalfGreyBesideAnUnnamedMaterial) {
  // assimp 5.2 names both the unnamed "glow" and its default material '': the copy it reads
  // names every material by its index (io/gltf_extras.h).
  TempDir dir("mesh_gltf");
  std::string buffer;
  nlohmann::json g = testing_support::quad_gltf(buffer);
  g["materials"][1].erase("name");
  nlohmann::json plain = g["meshes"][0];
  plain["name"] = "plain";
  plain["primitives"][0].erase("material");
  g["meshes"].push_back(plain);
  g["nodes"][1]["mesh"] = 1;
  write_file(dir / "plain.gltf", testing_support::gltf_text(g, buffer));
  const MeshImport m = import_mesh((dir / "plain.gltf").string());
  ASSERT_EQ(m.surfaces.size(), 2u);
  expect_near(named(m.surfaces, "quad:0").reflectance, Rgb(0.4, 0.5, 0.6));
  expect_near(named(m.surfaces, "quad:0").emission_w_m2, Rgb(8, 4, 2));
  expect_near(named(m.surfaces, "plain:0").reflectance, Rgb::Constant(0.5));
  expect_near(named(m.surfaces, "plain:0").emission_w_m2, Rgb::Zero());
}

TEST(MeshImport, GltfMaterialsFoundByIndexWhateverTheirNamesAndSpecularGlossinessDiffuse) {
  // Two unnamed materials of the same factors and different strengths (refused before: assimp 5.2
  // drops the strength and names both ''), and a third of the archived
  // KHR_materials_pbrSpecularGlossiness, whose diffuseFactor is its colour (assimp gave its
  // default baseColorFactor, white).
  TempDir dir("mesh_gltf");
  std::string buffer;
  nlohmann::json g = testing_support::quad_gltf(buffer);
  g["materials"][1].erase("name");
  g["materials"][0] = g["materials"][1];
  g["materials"][0]["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"] = 2;
  g["materials"].push_back({{"extensions", {{"KHR_materials_pbrSpecularGlossiness", {{"diffuseFactor", {0.2, 0.3, 0.4, 1}}}}}}});
  for (const int k : {1, 2}) {
    nlohmann::json mesh = g["meshes"][0];
    mesh["name"] = "quad" + std::to_string(k);
    mesh["primitives"][0]["material"] = k == 1 ? 0 : 2;
    g["meshes"].push_back(mesh);
    g["nodes"].push_back({{"mesh", k}});
    g["scenes"][0]["nodes"].push_back(static_cast<int>(g["nodes"].size()) - 1);
  }
  write_file(dir / "strengths.gltf", testing_support::gltf_text(g, buffer));
  const MeshImport m = import_mesh((dir / "strengths.gltf").string());
  expect_near(named(m.surfaces, "quad:0").emission_w_m2, Rgb(8, 4, 2));   // materials[1], strength 8
  expect_near(named(m.surfaces, "quad1:0").emission_w_m2, Rgb(2, 1, 0.5)); // materials[0], strength 2
  expect_near(named(m.surfaces, "quad1:0").reflectance, Rgb(0.4, 0.5, 0.6));
  expect_near(named(m.surfaces, "quad2:0").reflectance, Rgb(0.2, 0.3, 0.4));
  expect_near(named(m.surfaces, "quad2:0").emission_w_m2, Rgb::Zero());
  // A material's name as the file has it in a warning (Kd of 1 and more clamped).
  g["materials"][2] = {{"name", "white"}};
  write_file(dir / "white.gltf", testing_support::gltf_text(g, buffer));
  const MeshImport white = import_mesh((dir / "white.gltf").string());
  ASSERT_FALSE(white.warnings.empty());
  EXPECT_NE(white.warnings.front().find("material 'white' pbrMetallicRoughness.baseColorFactor"), std::string::npos)
      << white.warnings.front();
}

TEST(MeshImport, MirroringNodeKeepsTheFrontInFront) {
  TempDir dir("mesh_gltf");
  std::string buffer;
  nlohmann::json g = testing_support::quad_gltf(buffer);
  g["nodes"][1]["scale"] = {-1, 1, 1};  // x -> -x: the quad's corners turn clockwise
  write_file(dir / "mirror.gltf", testing_support::gltf_text(g, buffer));
  const MeshImport m = import_mesh((dir / "mirror.gltf").string());
  ASSERT_EQ(m.surfaces.size(), 2u);
  const Surface& mirrored = named(m.surfaces, "quad#2:0");
  expect_near(mirrored.normal(), Vec3(0, 0, 1));
  EXPECT_NEAR(mirrored.area_m2(), 1.0, kFloat);
  for (const Vec3& c : mirrored.corners) {
    EXPECT_LE(c.x(), kFloat);
    EXPECT_NEAR(c.z(), 2.0, kFloat);
  }
}

}  // namespace mesh_import_gltf_test
}  // namespace radrecon
