// Mesh import (io/mesh_import.h) of PLY files the test writes itself, ASCII and binary: vertex
// colours averaged per face, numbers in every written form, and the files assimp 5.2 misread
// when it read them itself (radrecon gives it a canonical copy: io/ply_check.h). Expected
// values are the numbers written into the files.

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "io/mesh_import.h"
#include "support/mesh_checks.h"
#include "support/model_files.h"
#include "support/temp_dir.h"

namespace radrecon {
namespace mesh_import_ply_test {

using testing_support::expect_near;
using testing_support::kFloat;
using testing_support::TempDir;
using testing_support::write_file;

TEST(MeshImport, PlyVertexColoursAreAveragedPerFace) {
  TempDir dir("mesh_ply");
  write_file(dir / "square.ply", testing_support::coloured_square_ply());
  const MeshImport m = import_mesh((dir / "square.ply").string());
  ASSERT_EQ(m.surfaces.size(), 1u);
  const Surface& s = m.surfaces[0];
  EXPECT_EQ(s.name, "square:0");  // a PLY mesh has no name: the file's stem
  EXPECT_EQ(s.corner_count, 4);
  expect_near(s.reflectance, Rgb(0.2, 0.1, 0.05));
  expect_near(s.corners[2], Vec3(1, 1, 0));
  EXPECT_TRUE(m.warnings.empty());
}

TEST(MeshImport, AsciiPlyNumbersInEveryWrittenForm) {
  // The coloured square with CRLF line ends, tabs, signs, exponents and a bare fraction: the
  // same face, read value for value.
  TempDir dir("mesh_ply");
  std::string ply = testing_support::coloured_square_ply();
  ply.replace(ply.find("0 0 0 204 0 0"), 13, "+0.0\t-0e5 .0 204 0 0");
  ply.replace(ply.find("1 1 0 0 0 51"), 12, "1.E0 10e-1 0. 0 0 51");
  ply.replace(ply.find("4 0 1 2 3"), 9, "4 +0 1 2\t3");  // a signed index may carry a sign
  std::string crlf;
  for (const char c : ply) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  write_file(dir / "forms.ply", crlf);
  const MeshImport m = import_mesh((dir / "forms.ply").string());
  ASSERT_EQ(m.surfaces.size(), 1u);
  expect_near(m.surfaces[0].reflectance, Rgb(0.2, 0.1, 0.05));
  expect_near(m.surfaces[0].corners[0], Vec3(0, 0, 0));
  expect_near(m.surfaces[0].corners[2], Vec3(1, 1, 0));
}

TEST(MeshImport, PlyIsReadAsWrittenWhereAssimpAloneMisreadsIt) {
  // Each of these files made assimp 5.2, reading the file itself, take the wrong values, read
  // out of step or allocate for billions of list items; radrecon gives it a canonical copy
  // (io/ply_check.h), and each reads as the coloured square.
  TempDir dir("mesh_ply");
  const std::string ply = testing_support::coloured_square_ply();
  const auto with = testing_support::coloured_square_ply_with;
  // `content` with `line` as the first line of its data.
  const auto data_first = [](std::string content, const std::string& line) {
    return content.insert(content.find("end_header\n") + 11, line + "\n");
  };
  const std::string digits = with("1 1 0 0 0 51", "10000000000000000000e-19 1 0 0 0 51");
  const std::vector<std::pair<std::string, std::string>> variants = {
      // an element assimp does not know (it takes the name's digits for the count: 0 records)
      {"unknown.ply", data_first(with("element vertex 4", "element foo 1\nproperty uint a\nelement vertex 4"), "4000000000")},
      {"texture.ply", data_first(with("element vertex 4", "element TextureFile 1\nproperty uint a\nelement vertex 4"), "7")},
      // a comment and a blank line among an element's properties (assimp ended the list there)
      {"comment.ply", with("property float y\n", "property float y\ncomment between\n\n")},
      // header words inside an obj_info line, which assimp read back as header lines
      {"obj_info.ply", with("format ascii 1.0\n", "format ascii 1.0\nobj_info Aelement vertex 99999999999\ncomment x\n")},
      // a twenty-digit mantissa (assimp's integer part overflows), and no line end at the end
      {"digits.ply", digits.substr(0, digits.size() - 1)},
  };
  for (const auto& [name, content] : variants) {
    write_file(dir / name, content);
    const MeshImport m = import_mesh((dir / name).string());
    ASSERT_EQ(m.surfaces.size(), 1u) << name;
    const Surface& s = m.surfaces[0];
    EXPECT_EQ(s.corner_count, 4) << name;
    expect_near(s.reflectance, Rgb(0.2, 0.1, 0.05));
    expect_near(s.corners[0], Vec3(0, 0, 0));
    expect_near(s.corners[2], Vec3(1, 1, 0));
  }
}

TEST(MeshImport, WhiteVertexColoursAreClampedWithOneWarning) {
  TempDir dir("mesh_ply");
  std::string ply = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                    "property uchar red\nproperty uchar green\nproperty uchar blue\nelement face 2\n"
                    "property list uchar int vertex_indices\nend_header\n"
                    "0 0 0 255 255 255\n1 0 0 255 255 255\n1 1 0 255 255 255\n0 1 0 255 255 255\n3 0 1 2\n3 0 2 3\n";
  write_file(dir / "white.ply", ply);
  const MeshImport m = import_mesh((dir / "white.ply").string());
  ASSERT_EQ(m.surfaces.size(), 1u);  // the two triangles merged
  expect_near(m.surfaces[0].reflectance, Rgb::Constant(0.999));
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_NE(m.warnings[0].find("2 face(s) clamped"), std::string::npos) << m.warnings[0];
  // A reflectance override (a scene's meshes[].reflectance) uses no colour of the file: no warning.
  MeshPlacement grey;
  grey.reflectance = Rgb::Constant(0.3);
  const MeshImport o = import_mesh((dir / "white.ply").string(), grey);
  ASSERT_EQ(o.surfaces.size(), 1u);
  expect_near(o.surfaces[0].reflectance, Rgb::Constant(0.3));
  EXPECT_TRUE(o.warnings.empty()) << o.warnings[0];
}

/// A binary PLY of the unit square as one quad, in either byte order.
std::string binary_square_ply(bool big_endian) {
  std::string out = std::string("ply\nformat binary_") + (big_endian ? "big" : "little") +
                    "_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                    "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const auto put = [&](auto value) {
    std::string raw;
    testing_support::append_le(raw, value);
    if (big_endian) std::reverse(raw.begin(), raw.end());
    out += raw;
  };
  for (float f : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 1.f, 1.f, 0.f, 0.f, 1.f, 0.f}) put(f);
  out += char(4);
  for (int32_t i : {0, 1, 2, 3}) put(i);
  return out;
}

TEST(MeshImport, BinaryPlyInEitherByteOrder) {
  TempDir dir("mesh_ply");
  for (bool big : {false, true}) {
    write_file(dir / "bin.ply", binary_square_ply(big));
    const MeshImport m = import_mesh((dir / "bin.ply").string());
    ASSERT_EQ(m.surfaces.size(), 1u);
    EXPECT_EQ(m.surfaces[0].corner_count, 4);
    expect_near(m.surfaces[0].corners[2], Vec3(1, 1, 0));
    expect_near(m.surfaces[0].reflectance, Rgb::Constant(0.5));  // no colours: the default
  }
}

TEST(MeshImport, PlyFaceColoursAreTheFacesOwnAndWinOverVertexColours) {
  // Two faces, their colours as the face element's properties (assimp 5.2 reads none: a face of
  // red 200 came out 0.5 grey): uchar over 255, a second file with float diffuse_* and binary
  // ushort over 65535, in either byte order.
  TempDir dir("mesh_ply");
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                             "property uchar red\nproperty uchar green\nproperty uchar blue\nelement face 2\n"
                             "property list uchar int vertex_indices\n";
  // White vertex colours (clamped, were they read): the faces' own win, and only a face's own
  // colour out of range counts as clamped.
  const std::string vertices = "0 0 0 255 255 255\n1 0 0 255 255 255\n1 1 0 255 255 255\n0 1 0 255 255 255\n";
  write_file(dir / "uchar.ply", header + "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n" + vertices +
                                    "3 0 1 2 200 20 20\n3 0 2 3 51 102 255\n");
  const MeshImport m = import_mesh((dir / "uchar.ply").string());
  ASSERT_EQ(m.surfaces.size(), 2u);
  expect_near(m.surfaces[0].reflectance, Rgb(200, 20, 20) / 255.0);
  expect_near(m.surfaces[1].reflectance, Rgb(0.2, 0.4, 0.999));  // 255 is 1: clamped, with a warning
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_NE(m.warnings[0].find("the colour of 1 face(s) clamped"), std::string::npos) << m.warnings[0];
  write_file(dir / "float.ply", header + "property float diffuse_red\nproperty float diffuse_green\nproperty float diffuse_blue\n"
                                    "end_header\n" + vertices + "3 0 1 2 0.25 0.5 0.75\n3 0 2 3 0.1 0.2 0.3\n");
  const MeshImport f = import_mesh((dir / "float.ply").string());
  ASSERT_EQ(f.surfaces.size(), 2u);
  expect_near(f.surfaces[0].reflectance, Rgb(0.25, 0.5, 0.75));
  expect_near(f.surfaces[1].reflectance, Rgb(0.1, 0.2, 0.3));
  for (bool big : {false, true}) {
    std::string bin = std::string("ply\nformat binary_") + (big ? "big" : "little") +
                      "_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                      "element face 1\nproperty ushort red\nproperty list uchar int vertex_indices\nproperty ushort green\n"
                      "property ushort blue\nend_header\n";
    const auto put = [&](auto value) {
      std::string raw;
      testing_support::append_le(raw, value);
      if (big) std::reverse(raw.begin(), raw.end());
      bin += raw;
    };
    for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 1.f, 1.f, 0.f}) put(v);
    put(uint16_t{13107});  // 0.2
    bin += char(3);
    for (int32_t i : {0, 1, 2}) put(i);
    put(uint16_t{26214});  // 0.4
    put(uint16_t{39321});  // 0.6
    write_file(dir / "bin.ply", bin);
    const MeshImport b = import_mesh((dir / "bin.ply").string());
    ASSERT_EQ(b.surfaces.size(), 1u);
    expect_near(b.surfaces[0].reflectance, Rgb(0.2, 0.4, 0.6));
  }
}

TEST(MeshImport, BinaryPlyWhoseDataBeginsWithALineFeedByte) {
  // assimp 5.2, reading the file itself, dropped a first data byte of 0x0A after "end_header\n"
  // and read every value one byte late. x = 1.0000012f is stored as 0A 00 80 3F.
  TempDir dir("mesh_ply");
  const float x = std::bit_cast<float>(std::uint32_t{0x3F80000A});
  std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  for (float f : {x, 0.f, 0.f, x, 1.f, 0.f, 0.f, 1.f, 0.f}) testing_support::append_le(ply, f);
  ply += char(3);
  for (int32_t i : {0, 1, 2}) testing_support::append_le(ply, i);
  ASSERT_EQ(ply[ply.find("end_header\n") + 11], '\n');
  write_file(dir / "line_feed.ply", ply);
  const MeshImport m = import_mesh((dir / "line_feed.ply").string());
  ASSERT_EQ(m.surfaces.size(), 1u);
  EXPECT_EQ(m.surfaces[0].corner_count, 3);
  EXPECT_NEAR(m.surfaces[0].area_m2(), 0.5 * x, kFloat);
  for (const Vec3& c : m.surfaces[0].polygon()) EXPECT_TRUE(c.x() == 0 || c.x() == double(x)) << c.transpose();
}

}  // namespace mesh_import_ply_test
}  // namespace radrecon
