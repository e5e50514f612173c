#pragma once
// Model files written by the tests themselves (tests/io/mesh_import*_test.cpp): an OBJ with its
// MTL, a glTF 2.0 (JSON with the buffer as a base64 data URI, or a .glb), a PLY; all tiny.

#include <array>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace radrecon::testing_support {

inline void write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

inline std::string base64(const std::string& bytes) {
  static const char* const kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const uint32_t v = (uint8_t(bytes[i]) << 16) | (uint8_t(bytes[i + 1]) << 8) | uint8_t(bytes[i + 2]);
    for (int k = 18; k >= 0; k -= 6) out += kDigits[(v >> k) & 63];
  }
  if (i + 1 == bytes.size()) {
    const uint32_t v = uint8_t(bytes[i]) << 16;
    out += std::string{kDigits[(v >> 18) & 63], kDigits[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == bytes.size()) {
    const uint32_t v = (uint8_t(bytes[i]) << 16) | (uint8_t(bytes[i + 1]) << 8);
    out += std::string{kDigits[(v >> 18) & 63], kDigits[(v >> 12) & 63], kDigits[(v >> 6) & 63], '='};
  }
  return out;
}

template <typename T>
void append_le(std::string& bytes, T value) {  // the machines the tests run on are little-endian
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  bytes.append(raw, sizeof(T));
}

/// A glTF 2.0 document of one mesh "quad" (the unit square in z = 0 as two triangles, indices
/// 0 1 2 and 0 2 3) placed by two nodes, the second translated by (0, 0, 2), with material
/// "glow" (baseColorFactor (0.4, 0.5, 0.6), emissiveFactor (1, 0.5, 0.25), emissiveStrength 8)
/// and an unused material "unused". Its buffer: `buffer_bytes` (set by the function) to be given
/// as a data URI or a .glb chunk.
inline nlohmann::json quad_gltf(std::string& buffer_bytes) {
  buffer_bytes.clear();
  for (float f : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 1.f, 1.f, 0.f, 0.f, 1.f, 0.f}) append_le(buffer_bytes, f);
  for (uint16_t i : {0, 1, 2, 0, 2, 3}) append_le(buffer_bytes, i);
  using json = nlohmann::json;
  json g = {
      {"asset", {{"version", "2.0"}}},
      {"extensionsUsed", {"KHR_materials_emissive_strength"}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0, 1}}}}},
      {"nodes", {{{"mesh", 0}, {"name", "n0"}}, {{"mesh", 0}, {"name", "n1"}, {"translation", {0, 0, 2}}}}},
      {"meshes", {{{"name", "quad"}, {"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}, {"material", 1}}}}}}},
      {"materials",
       {{{"name", "unused"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.1, 0.2, 0.3, 1}}}}},
        {{"name", "glow"},
         {"pbrMetallicRoughness", {{"baseColorFactor", {0.4, 0.5, 0.6, 1}}}},
         {"emissiveFactor", {1, 0.5, 0.25}},
         {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 8}}}}}}}},
      {"buffers", {{{"byteLength", buffer_bytes.size()}}}},
      {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}}, {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 12}}}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}, {"min", {0, 0, 0}}, {"max", {1, 1, 0}}},
        {{"bufferView", 1}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}}}};
  return g;
}

/// The document with its buffer as a base64 data URI, as .gltf text.
inline std::string gltf_text(nlohmann::json g, const std::string& buffer_bytes) {
  g["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64(buffer_bytes);
  return g.dump();
}

/// The document and its buffer as a binary glTF (.glb): header, JSON chunk, BIN chunk.
inline std::string glb_bytes(const nlohmann::json& g, std::string buffer_bytes) {
  std::string json_text = g.dump();
  while (json_text.size() % 4) json_text += ' ';
  while (buffer_bytes.size() % 4) buffer_bytes += '\0';
  std::string out = "glTF";
  append_le<uint32_t>(out, 2);
  append_le<uint32_t>(out, uint32_t(12 + 8 + json_text.size() + 8 + buffer_bytes.size()));
  append_le<uint32_t>(out, uint32_t(json_text.size()));
  append_le<uint32_t>(out, 0x4E4F534Au);
  out += json_text;
  append_le<uint32_t>(out, uint32_t(buffer_bytes.size()));
  append_le<uint32_t>(out, 0x004E4942u);
  out += buffer_bytes;
  return out;
}

/// An ASCII PLY of the unit square in z = 0 as one quad face (vertices counter-clockwise from
/// the origin), its vertices coloured (204, 0, 0), (0, 102, 0), (0, 0, 51), (0, 0, 0): the face's
/// mean colour is (0.2, 0.1, 0.05).
inline std::string coloured_square_ply() {
  return "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
         "property uchar red\nproperty uchar green\nproperty uchar blue\nelement face 1\n"
         "property list uchar int vertex_indices\nend_header\n"
         "0 0 0 204 0 0\n1 0 0 0 102 0\n1 1 0 0 0 51\n0 1 0 0 0 0\n4 0 1 2 3\n";
}

/// coloured_square_ply() with the first `from` in it replaced by `to` (std::logic_error if it
/// holds none: a test's typo).
inline std::string coloured_square_ply_with(const std::string& from, const std::string& to) {
  std::string out = coloured_square_ply();
  const size_t at = out.find(from);
  if (at == std::string::npos) throw std::logic_error("the coloured square PLY has no '" + from + "'");
  return out.replace(at, from.size(), to);
}

}  // namespace radrecon::testing_support
