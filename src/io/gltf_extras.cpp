#include "io/gltf_extras.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>

#include "core/error.h"
#include "core/parse.h"
#include "io/gltf_indices.h"
#include "io/json_reader.h"

namespace radrecon {

namespace {

using json = nlohmann::json;

uint32_t little_endian_u32(const std::string& bytes, size_t at) {
  uint32_t v = 0;
  for (int k = 3; k >= 0; --k) v = (v << 8) | static_cast<unsigned char>(bytes[at + k]);
  return v;
}

/// The JSON text of a .glb (its first chunk, which the format requires to be of type JSON) and
/// its BIN chunk ("" if none).
std::pair<std::string, std::string> glb_chunks(const std::string& bytes, const std::string& path) {
  if (bytes.size() < 20 || bytes.compare(0, 4, "glTF") != 0)
    throw UserError(path, "not a binary glTF file (no 'glTF' header)");
  const uint32_t length = little_endian_u32(bytes, 12), type = little_endian_u32(bytes, 16);
  if (type != 0x4E4F534Au) throw UserError(path, "binary glTF's first chunk is not JSON");
  if (length > bytes.size() - 20) throw UserError(path, "binary glTF is truncated (its JSON chunk runs past the end)");
  std::string bin;
  const size_t next = 20 + static_cast<size_t>(length);
  if (bytes.size() >= next + 8 && little_endian_u32(bytes, next + 4) == 0x004E4942u) {
    const uint32_t bin_length = little_endian_u32(bytes, next);
    if (bin_length > bytes.size() - next - 8) throw UserError(path, "binary glTF is truncated (its BIN chunk runs past the end)");
    bin = bytes.substr(next + 8, bin_length);
  }
  return {bytes.substr(20, length), bin};
}

Rgb factor(const JsonReader& r, const json& j, const std::string& path, size_t needed, Rgb fallback) {
  if (!j.is_array() || j.size() < needed) r.fail(path, "must be an array of " + std::to_string(needed) + " numbers");
  Rgb out = fallback;
  for (int c = 0; c < 3; ++c) {
    const double x = r.number(j[c], JsonReader::at(path, c));
    if (!(x >= 0)) r.fail(JsonReader::at(path, c), "must be a number >= 0");
    out[c] = x;
  }
  return out;
}

/// The faces a primitive declares, as assimp 5.2 makes them of its mode (0 points, 1 lines,
/// 2 line loop, 3 line strip, 4 triangles (default), 5 triangle strip, 6 triangle fan); 0 where
/// the JSON is not as the schema says (assimp refuses that itself).
size_t primitive_faces(const json& doc, const json& primitive) {
  if (!primitive.is_object()) return 0;
  const json* accessor_index = nullptr;
  if (primitive.contains("indices")) accessor_index = &primitive["indices"];
  else if (primitive.contains("attributes") && primitive["attributes"].is_object() && primitive["attributes"].contains("POSITION"))
    accessor_index = &primitive["attributes"]["POSITION"];
  if (!accessor_index || !accessor_index->is_number_unsigned() || !doc.contains("accessors") || !doc["accessors"].is_array()) return 0;
  const size_t a = accessor_index->get<size_t>();
  if (a >= doc["accessors"].size() || !doc["accessors"][a].is_object() || !doc["accessors"][a].contains("count") ||
      !doc["accessors"][a]["count"].is_number_unsigned())
    return 0;
  const size_t count = doc["accessors"][a]["count"].get<size_t>();
  const long long mode = primitive.contains("mode") && primitive["mode"].is_number_integer() ? primitive["mode"].get<long long>() : 4;
  switch (mode) {
    case 0: return count;
    case 1: return count / 2;
    case 2: return count;
    case 3: return count >= 2 ? count - 1 : 0;
    case 4: return count / 3;
    case 5: case 6: return count >= 3 ? count - 2 : 0;
    default: return 0;
  }
}

}  // namespace

GltfExtras read_gltf_extras(const std::string& path) {
  std::string text = read_text_file(path, "mesh file");
  const bool binary = lower_extension(path) == ".glb";
  std::string bin;
  if (binary) std::tie(text, bin) = glb_chunks(text, path);
  const JsonReader r(path);
  // A modelling tool's file: a key it repeats where radrecon reads nothing (extras, extensions)
  // is no reason to refuse it; the last value counts, as in every glTF reader.
  const json doc = r.parse(text, "glTF file", JsonReader::Keys::as_parsed);
  if (!doc.is_object()) r.fail("(top level)", "must be a JSON object");
  const json& asset = r.member(doc, "asset", "");
  const std::string version = r.string(r.member(asset, "version", "asset"), "asset.version");
  if (version.rfind("2.", 0) != 0) r.fail("asset.version", "must be \"2.0\" (glTF 2.0), got \"" + version + "\"");
  check_gltf_indices(doc, bin, std::filesystem::path(path).parent_path().string(), path);
  GltfExtras extras;
  if (doc.contains("meshes") && doc["meshes"].is_array())
    for (const json& mesh : doc["meshes"])
      if (mesh.is_object() && mesh.contains("primitives") && mesh["primitives"].is_array())
        for (const json& primitive : mesh["primitives"]) extras.faces += primitive_faces(doc, primitive);
  std::vector<GltfMaterialFactors>& out = extras.materials;
  if (!doc.contains("materials")) return extras;
  const json& materials = doc["materials"];
  if (!materials.is_array()) r.fail("materials", "must be an array");
  for (size_t i = 0; i < materials.size(); ++i) {
    const std::string where = JsonReader::at("materials", i);
    const json& m = materials[i];
    if (!m.is_object()) r.fail(where, "must be an object");
    GltfMaterialFactors f;
    if (m.contains("name")) f.name = r.string(m["name"], where + ".name");
    if (m.contains("pbrMetallicRoughness") && m["pbrMetallicRoughness"].is_object() &&
        m["pbrMetallicRoughness"].contains("baseColorFactor"))
      f.base_colour = factor(r, m["pbrMetallicRoughness"]["baseColorFactor"], where + ".pbrMetallicRoughness.baseColorFactor", 4, f.base_colour);
    if (m.contains("emissiveFactor")) f.emissive = factor(r, m["emissiveFactor"], where + ".emissiveFactor", 3, f.emissive);
    if (m.contains("extensions") && m["extensions"].is_object() && m["extensions"].contains("KHR_materials_emissive_strength")) {
      const std::string ext = where + ".extensions.KHR_materials_emissive_strength";
      const json& e = m["extensions"]["KHR_materials_emissive_strength"];
      if (!e.is_object()) r.fail(ext, "must be an object");
      if (e.contains("emissiveStrength")) {
        f.emissive_strength = r.number(e["emissiveStrength"], ext + ".emissiveStrength");
        if (!(f.emissive_strength >= 0)) r.fail(ext + ".emissiveStrength", "must be a number >= 0");
      }
    }
    out.push_back(f);
  }
  return extras;
}

}  // namespace radrecon
