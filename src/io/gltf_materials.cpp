#include "io/gltf_materials.h"

#include <cmath>
#include <cstdint>
#include <cstring>

#include "core/error.h"
#include "io/json_reader.h"

namespace radrecon {

namespace {

using json = nlohmann::json;

uint32_t little_endian_u32(const std::string& bytes, size_t at) {
  uint32_t v = 0;
  for (int k = 3; k >= 0; --k) v = (v << 8) | static_cast<unsigned char>(bytes[at + k]);
  return v;
}

/// The JSON text of a .glb: its first chunk, which the format requires to be of type JSON.
std::string glb_json_chunk(const std::string& bytes, const std::string& path) {
  if (bytes.size() < 20 || bytes.compare(0, 4, "glTF") != 0)
    throw UserError(path, "not a binary glTF file (no 'glTF' header)");
  const uint32_t length = little_endian_u32(bytes, 12), type = little_endian_u32(bytes, 16);
  if (type != 0x4E4F534Au) throw UserError(path, "binary glTF's first chunk is not JSON");
  if (length > bytes.size() - 20) throw UserError(path, "binary glTF is truncated (its JSON chunk runs past the end)");
  return bytes.substr(20, length);
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

}  // namespace

std::vector<GltfMaterialFactors> read_gltf_material_factors(const std::string& path) {
  std::string text = read_text_file(path, "mesh file");
  const bool binary = path.size() >= 4 && (path.compare(path.size() - 4, 4, ".glb") == 0 || path.compare(path.size() - 4, 4, ".GLB") == 0);
  if (binary) text = glb_json_chunk(text, path);
  const JsonReader r(path);
  const json doc = r.parse(text, "glTF file");
  if (!doc.is_object()) r.fail("(top level)", "must be a JSON object");
  const json& asset = r.member(doc, "asset", "");
  const std::string version = r.string(r.member(asset, "version", "asset"), "asset.version");
  if (version.rfind("2.", 0) != 0) r.fail("asset.version", "must be \"2.0\" (glTF 2.0), got \"" + version + "\"");
  std::vector<GltfMaterialFactors> out;
  if (!doc.contains("materials")) return out;
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
  return out;
}

}  // namespace radrecon
