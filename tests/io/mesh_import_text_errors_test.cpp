// Mesh import (io/mesh_import.h) refusing malformed OBJ and PLY files: each a UserError naming the
// file and the line or record at fault, never a crash, never a model read out of step.

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <string>

#include "io/mesh_import.h"
#include "support/model_files.h"
#include "support/refused_import.h"
#include "support/temp_dir.h"

namespace radrecon {
namespace mesh_import_text_errors_test {

using testing_support::Refused;
using testing_support::TempDir;
using testing_support::write_file;

const char* const kTriangle = "v 0 0 0\nv 1 0 0\nv 1 1 0\n";

TEST(MeshImportErrors, ObjIndicesOutOfRangeAndNonFiniteCoordinates) {
  TempDir dir("mesh_bad");
  EXPECT_TRUE(Refused(dir, "index.obj", std::string(kTriangle) + "f 1 2 7\n", {"index.obj:4", "vertex index 7 out of range (3 vertices)"}));
  EXPECT_TRUE(Refused(dir, "negative.obj", std::string(kTriangle) + "f 1 2 -9\n", {"negative.obj:4", "vertex index -9 out of range"}));
  EXPECT_TRUE(Refused(dir, "zero.obj", std::string(kTriangle) + "f 0/1/1 2/1/1 3/1/1\n", {"zero.obj:4", "vertex index 0"}));
  // A face of 1 or 2 corners: assimp 5.2 failed its own validation on it, naming no line.
  EXPECT_TRUE(Refused(dir, "two.obj", std::string(kTriangle) + "f 1 2 3\nf 1 2\n", {"two.obj:5", "a face of 2 corners"}));
  EXPECT_TRUE(Refused(dir, "one.obj", std::string(kTriangle) + "f 1/1\nf 1 2 3\n", {"one.obj:4", "a face of 1 corner;"}));
  // A face continued on the next line ('\\' at the end, as assimp reads it) is no such face.
  write_file((dir / "continued.obj").string(), std::string(kTriangle) + "f 1 2 \\\n3\n");
  EXPECT_EQ(import_mesh((dir / "continued.obj").string()).surfaces.size(), 1u);
  // Relative indices count back from the vertices before the face: -1 -2 -3 is the triangle.
  write_file(dir / "relative.obj", std::string(kTriangle) + "f -3 -2 -1\n");
  EXPECT_EQ(import_mesh((dir / "relative.obj").string()).surfaces.size(), 1u);
  EXPECT_TRUE(Refused(dir, "nan.obj", "v 0 0 0\nv nan 0 0\nv 1 1 0\nf 1 2 3\n", {"not finite"}));
  EXPECT_TRUE(Refused(dir, "inf.obj", "v 0 0 0\nv 1 0 0\nv 1 inf 0\nf 1 2 3\n", {"not finite"}));
  EXPECT_TRUE(Refused(dir, "junk.obj", "hello\n", {"cannot be read"}));
  // assimp 5.2 reads a word it cannot parse as the end of the vertex, which a face then misses.
  EXPECT_TRUE(Refused(dir, "word.obj", "v 0 0 0\nv 2 abc 0\nv 1 1 0\nf 1 2 3\n", {"word.obj:2", "'abc' is not a number"}));
  EXPECT_TRUE(Refused(dir, "short.obj", "v 0 0 0\nv 2 0\nv 1 1 0\nf 1 2 3\n", {"short.obj:2", "needs 3 coordinates"}));
  EXPECT_TRUE(Refused(dir, "big.obj", "v 0 0 0\nv 1e999 0 0\nv 1 1 0\nf 1 2 3\n", {"big.obj:2", "out of a double's range"}));
  // Beyond a float's range the reader's single precision made it infinite ("not finite", no line).
  EXPECT_TRUE(Refused(dir, "float.obj", "v 0 0 0\nv 3.5e38 0 0\nv 1 1 0\nf 1 2 3\n", {"float.obj:2", "beyond single precision"}));
  // A bare 'f' was accepted, a corner that is no index refused by assimp without a line, and a
  // statement that only begins with f ("foo") read as a face: refused, and skipped.
  EXPECT_TRUE(Refused(dir, "bare.obj", std::string(kTriangle) + "f\nf 1 2 3\n", {"bare.obj:4", "a face of 0 corners"}));
  EXPECT_TRUE(Refused(dir, "bare_v.obj", std::string(kTriangle) + "v\nf 1 2 3\n", {"bare_v.obj:4", "needs 3 coordinates, it has 0"}));
  EXPECT_TRUE(Refused(dir, "x.obj", std::string(kTriangle) + "f 1 2 3 x\n", {"x.obj:4", "corner 'x' is no vertex index"}));
  // A NUL ends a line for assimp, not for the check: "l 0" after NULs crashed assimp (fuzzing).
  EXPECT_TRUE(Refused(dir, "nul.obj", std::string(kTriangle) + "f 1 2 3\n" + std::string("x\0l 0 ", 6) + "\n",
                      {"nul.obj:5", "a NUL byte within the line (byte 2)"}));
  EXPECT_TRUE(Refused(dir, "ff.obj", std::string(kTriangle) + "f 1 2\f3\n", {"ff.obj:4", "form feed"}));
  write_file(dir / "crlf.obj", "v 0 0 0\r\nv 1 0 0\r\nv 1 1 0\r\nf 1 2 3\r\n");  // a closing CR is fine
  EXPECT_EQ(import_mesh((dir / "crlf.obj").string()).surfaces.size(), 1u);
  write_file(dir / "foo.obj", std::string(kTriangle) + "foo bar\nf 1 2 3\n");
  EXPECT_EQ(import_mesh((dir / "foo.obj").string()).surfaces.size(), 1u);
  // A coordinate too small for a double is 0, as any reader takes it.
  write_file(dir / "tiny.obj", "v 0 0 1e-999\nv 1 0 0\nv 1 1 0\nf 1 2 3\n");
  EXPECT_EQ(import_mesh((dir / "tiny.obj").string()).surfaces.size(), 1u);
  EXPECT_TRUE(Refused(dir, "nofaces.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 2 2 2\n", {}));
}

TEST(MeshImportErrors, ObjNegativeEmissionOrNonFiniteColourIsRefused) {
  TempDir dir("mesh_bad");
  write_file(dir / "neg.mtl", "newmtl m\nKd 0.5 0.5 0.5\nKe -1 0 0\n");
  EXPECT_TRUE(Refused(dir, "neg.obj", std::string("mtllib neg.mtl\n") + kTriangle + "usemtl m\nf 1 2 3\n", {"'m' Ke", ">= 0"}));
  write_file(dir / "nan.mtl", "newmtl m\nKd nan 0.5 0.5\n");
  EXPECT_TRUE(Refused(dir, "nankd.obj", std::string("mtllib nan.mtl\n") + kTriangle + "usemtl m\nf 1 2 3\n",
                      {"nan.mtl:2", "Kd value 'nan'", "not a finite number"}));
  // Named with its MTL file and line (assimp 5.2 named the OBJ alone, and refused Blender's aniso).
  write_file(dir / "two.mtl", "newmtl m\naniso 0.0\nanisor 0.0\nKd 0.2 0.4\n");
  EXPECT_TRUE(Refused(dir, "two.obj", std::string("mtllib two.mtl\n") + kTriangle + "usemtl m\nf 1 2 3\n",
                      {"two.mtl:4", "Kd must be one number (grey) or three (r g b), got 2"}));
  write_file(dir / "spectral.mtl", "newmtl m\nKd spectral x.rfl\n");
  EXPECT_TRUE(Refused(dir, "spectral.obj", std::string("mtllib spectral.mtl\n") + kTriangle + "usemtl m\nf 1 2 3\n",
                      {"spectral.mtl:2", "spectral colours are not read"}));
  write_file(dir / "hot.mtl", "newmtl m\nKe 1e300\n");  // one value: grey, and beyond 1e12 W/m^2
  EXPECT_TRUE(Refused(dir, "hot.obj", std::string("mtllib hot.mtl\n") + kTriangle + "usemtl m\nf 1 2 3\n", {"'m' Ke", "at most 1e+12"}));
}

TEST(MeshImportErrors, ObjVertexWeightOtherThanOneAndVerticesOfFiveOrSevenNumbers) {
  // assimp 5.2 divides x y z by w (a model of w = 2 came out half its size, exit 0), and reads
  // no vertex of 5 or 7 numbers ("vertex index out of range", no line).
  TempDir dir("mesh_bad");
  EXPECT_TRUE(Refused(dir, "w2.obj", "v 0 0 0 2\nv 1 0 0 2\nv 1 1 0 2\nf 1 2 3\n", {"w2.obj:1", "vertex weight w = 2", "only 1"}));
  EXPECT_TRUE(Refused(dir, "w0.obj", "v 0 0 0\nv 1 0 0 0\nv 1 1 0\nf 1 2 3\n", {"w0.obj:2", "vertex weight w = 0"}));
  EXPECT_TRUE(Refused(dir, "wx.obj", "v 0 0 0 x\nv 1 0 0\nv 1 1 0\nf 1 2 3\n", {"wx.obj:1", "'x' is not a number"}));
  EXPECT_TRUE(Refused(dir, "five.obj", "v 0 0 0\nv 1 0 0 1 1\nv 1 1 0\nf 1 2 3\n", {"five.obj:2", "5 numbers"}));
  EXPECT_TRUE(Refused(dir, "seven.obj", "v 0 0 0 1 1 1 1\nv 1 0 0\nv 1 1 0\nf 1 2 3\n", {"seven.obj:1", "7 numbers"}));
  EXPECT_TRUE(Refused(dir, "colour.obj", "v 0 0 0 1 nan 1\nv 1 0 0\nv 1 1 0\nf 1 2 3\n", {"colour.obj:1", "'nan'", "not finite"}));
  // w = 1 and an r g b colour after x y z (written by some exporters, ignored) are read as they are.
  for (const char* first : {"v 0 0 0 1", "v 0 0 0 1.0", "v 0 0 0 0.5 0.25 1", "v 0 0 0 # 4 5 6"}) {
    write_file(dir / "fine.obj", std::string(first) + "\nv 2 0 0\nv 2 2 0\nf 1 2 3\n");
    const MeshImport m = import_mesh((dir / "fine.obj").string());
    ASSERT_EQ(m.surfaces.size(), 1u) << first;
    EXPECT_NEAR(m.surfaces[0].area_m2(), 2.0, 1e-9) << first;
  }
}

TEST(MeshImportErrors, ObjStatementsContinuedOnTheNextLine) {
  // A line ending in '\' goes on in the next, as assimp 5.2 reads it (a vertex so continued was
  // refused as "'\' is not a number"); the statement is named by its first line.
  TempDir dir("mesh_bad");
  write_file(dir / "continued.obj", "v 0 0 \\\n0\nv 2 \\\n 0 0\nv 2 2 0\nf 1 \\\n2 \\\n3\n");
  const MeshImport m = import_mesh((dir / "continued.obj").string());
  ASSERT_EQ(m.surfaces.size(), 1u);
  EXPECT_NEAR(m.surfaces[0].area_m2(), 2.0, 1e-9);
  // Joined as assimp joins them, with nothing between: "f 1 2 3\\\n1" ends in the corner 31.
  EXPECT_TRUE(Refused(dir, "joined.obj", std::string(kTriangle) + "f 1 2 3\\\n1\n", {"joined.obj:4", "vertex index 31 out of range"}));
  EXPECT_TRUE(Refused(dir, "crlf.obj", "v 0 0 0\r\nv 1 0 0 \\\r\n2\r\nv 1 1 0\r\nf 1 2 3\r\n", {"crlf.obj:2", "vertex weight w = 2"}));
  EXPECT_TRUE(Refused(dir, "spaced.obj", "v 0 0 \\ \n0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n",
                      {"spaced.obj:1", "'\\' is not a number", "only as the last character of a line"}));
}

TEST(MeshImportErrors, PlyTruncatedOrWithIndicesOutOfRange) {
  TempDir dir("mesh_bad");
  const std::string ply = testing_support::coloured_square_ply();
  EXPECT_TRUE(Refused(dir, "short.ply", ply.substr(0, ply.find("1 1 0 0 0 51")), {"truncated", "vertex 2"}));
  EXPECT_TRUE(Refused(dir, "noface.ply", ply.substr(0, ply.size() - 4), {"truncated", "face 0"}));
  std::string bad_index = ply;
  bad_index.replace(bad_index.find("4 0 1 2 3"), 9, "4 0 1 2 9");
  EXPECT_TRUE(Refused(dir, "index.ply", bad_index, {"out of range"}));
  EXPECT_TRUE(Refused(dir, "header.ply", "ply\nformat ascii 1.0\nelement vertex 3\n", {"end_header"}));
  std::string binary = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                       "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  for (float f : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 1.f, 1.f, 0.f}) testing_support::append_le(binary, f);
  binary += char(3);
  for (int32_t i : {0, 1}) testing_support::append_le(binary, i);  // the third index is missing
  EXPECT_TRUE(Refused(dir, "binary.ply", binary, {"truncated", "face 0"}));
}

TEST(MeshImportErrors, PlyRecordsPastThoseItsHeaderDeclares) {
  // assimp 5.2 reads the declared records and drops the rest without a word.
  TempDir dir("mesh_bad");
  const std::string ply = testing_support::coloured_square_ply();
  EXPECT_TRUE(Refused(dir, "extra.ply", ply + "3 0 1 2\n", {"line 18", "data after the last record", "1 face"}));
  write_file(dir / "blank.ply", ply + "\n  \n");  // blank lines at the end are no data
  EXPECT_EQ(import_mesh((dir / "blank.ply").string()).surfaces.size(), 1u);
  std::string binary = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                       "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  for (float f : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 1.f, 1.f, 0.f}) testing_support::append_le(binary, f);
  binary += char(3);
  for (int32_t i : {0, 1, 2}) testing_support::append_le(binary, i);
  write_file(dir / "binary.ply", binary);
  EXPECT_EQ(import_mesh((dir / "binary.ply").string()).surfaces.size(), 1u);
  binary += char(3);
  for (int32_t i : {2, 1, 0}) testing_support::append_le(binary, i);  // a second face the header does not declare
  EXPECT_TRUE(Refused(dir, "binary_extra.ply", binary, {"13 bytes after the last record", "3 vertex, 1 face"}));
}

TEST(MeshImportErrors, PlyDataThatAssimpWouldReadOutOfStep) {
  // Each of these once made assimp allocate for billions of list items or loop for minutes.
  TempDir dir("mesh_bad");
  const std::string ply = testing_support::coloured_square_ply();
  const auto with = testing_support::coloured_square_ply_with;
  // A NUL ends a line for assimp but not for a reader of words: the next value became a count.
  std::string nul = ply;
  nul.insert(nul.find("0 1 0 0 0 0") + 11, std::string(1, '\0') + "4444444444");
  EXPECT_TRUE(Refused(dir, "nul.ply", nul,
                      {"line 16", "byte 0x0 is not text"}));
  EXPECT_TRUE(Refused(dir, "split.ply", with("4 0 1 2 3", "4 0 1\n2 3"), {"line 17 (face 0)", "fewer values"}));
  EXPECT_TRUE(Refused(dir, "joined.ply", with("0 0 0 204 0 0\n", "0 0 0 204 0 0 "), {"line 13 (vertex 0)", "more values"}));
  EXPECT_TRUE(Refused(dir, "count.ply", with("4 0 1 2 3", "300 0 1 2 3"), {"list count '300'"}));
  EXPECT_TRUE(Refused(dir, "colour.ply", with("0 0 0 204 0 0", "0 0 0 256 0 0"), {"(vertex 0)", "'256' is not an integer"}));
  EXPECT_TRUE(Refused(dir, "plus_minus.ply", with("4 0 1 2 3", "4 +-0 1 2 3"), {"(face 0)", "'+-0' is not an integer"}));
  EXPECT_TRUE(Refused(dir, "minus_zero.ply", with("0 0 0 204 0 0", "0 0 0 -0 0 0"), {"'-0' is not an integer"}));
  EXPECT_TRUE(Refused(dir, "huge.ply", with("1 0 0 0 102 0", "1e99999999999999999999 0 0 0 102 0"),
                      {"(vertex 1)", "is not a finite number"}));
  EXPECT_TRUE(Refused(dir, "inf.ply", with("1 0 0 0 102 0", "inf 0 0 0 102 0"), {"'inf' is not a finite number"}));
  EXPECT_TRUE(Refused(dir, "plus.ply", with("0 0 0 204 0 0", "0 0 0 +204 0 0"), {"'+204' is not an integer"}));
  EXPECT_TRUE(Refused(dir, "word.ply", with("1 0 0 0 102 0", "1 0 x 0 102 0"), {"(vertex 1)", "'x' is not a finite number"}));
  EXPECT_TRUE(Refused(dir, "realcount.ply", with("list uchar int", "list float int"), {"count type must be an integer"}));
  // Records of no properties take no bytes: a count of 10^11 of them is refused, not walked.
  EXPECT_TRUE(Refused(dir, "empty_records.ply", with("element face 1", "element junk 99999999999\nelement face 1"),
                      {"element 'junk' declares 99999999999 records but no properties"}));
  // A binary count of a signed type that is negative: assimp reads char -1 as 2^32 - 1 items.
  std::string binary = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                       "property float z\nelement face 1\nproperty list char int vertex_indices\nend_header\n";
  for (float f : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 1.f, 1.f, 0.f}) testing_support::append_le(binary, f);
  binary += char(-1);
  for (int32_t i = 0; i < 255; ++i) testing_support::append_le(binary, i % 3);
  EXPECT_TRUE(Refused(dir, "negative.ply", binary, {"face 0 has a negative list count"}));
}

}  // namespace mesh_import_text_errors_test
}  // namespace radrecon
