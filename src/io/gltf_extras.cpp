#include "io/gltf_extras.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string_view>

#include "core/error.h"
#include "core/parse.h"
#include "core/tolerances.h"
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
  if (bytes.size() < 4 || bytes.compare(0, 4, "glTF") != 0) throw UserError(path, "not a binary glTF file (no 'glTF' header)");
  if (bytes.size() < 12)
    throw UserError(path, "binary glTF is truncated: " + std::to_string(bytes.size()) + " bytes, shorter than its 12-byte header");
  // The header: magic, version, length (of the whole file); assimp 5.2 read on past a wrong one.
  const uint32_t version = little_endian_u32(bytes, 4), declared = little_endian_u32(bytes, 8);
  if (version != 2) throw UserError(path, "binary glTF: its header's version must be 2 (glTF 2.0), got " + std::to_string(version));
  if (declared != bytes.size())
    throw UserError(path, std::string(declared > bytes.size() ? "binary glTF is truncated: " : "binary glTF: ") +
                              "its header's length is " + std::to_string(declared) + " bytes, the file has " +
                              std::to_string(bytes.size()) + (declared < bytes.size() ? " (data after its end)" : ""));
  if (bytes.size() < 20)
    throw UserError(path, "binary glTF is truncated: its header's length is " + std::to_string(declared) +
                              " bytes: no JSON chunk after the 12-byte header");
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

void append_u32(std::string& bytes, uint32_t v) {
  for (int k = 0; k < 4; ++k) bytes += static_cast<char>((v >> (8 * k)) & 0xFFu);
}

/// A binary glTF of the JSON text and BIN chunk (none if empty), each padded to 4 bytes as the
/// format asks (the JSON with spaces, the BIN with zeros).
std::string glb_with_json(std::string json_text, std::string bin) {
  while (json_text.size() % 4) json_text += ' ';
  while (bin.size() % 4) bin += '\0';
  std::string out = "glTF";
  append_u32(out, 2);
  append_u32(out, static_cast<uint32_t>(12 + 8 + json_text.size() + (bin.empty() ? 0 : 8 + bin.size())));
  append_u32(out, static_cast<uint32_t>(json_text.size()));
  append_u32(out, 0x4E4F534Au);
  out += json_text;
  if (!bin.empty()) {
    append_u32(out, static_cast<uint32_t>(bin.size()));
    append_u32(out, 0x004E4942u);
    out += bin;
  }
  return out;
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

/// Required extensions radrecon reads, or may pass over because they touch only what it does not
/// read (textures, how a viewer shades): the geometry and the two factors it takes are as the
/// core specification says. Any other in extensionsRequired changes what the file means.
constexpr std::array<std::string_view, 6> kRequiredExtensionsRead = {
    "KHR_materials_emissive_strength", "KHR_materials_pbrSpecularGlossiness", "KHR_texture_transform",
    "KHR_texture_basisu", "EXT_texture_webp", "KHR_materials_unlit"};

/// Refuses a required extension radrecon does not read (KHR_mesh_quantization's integer
/// positions, read by assimp 5.2 as floats, gave a floor of 3e-89 m^2 with exit 0).
void check_required_extensions(const JsonReader& r, const json& doc) {
  if (!doc.contains("extensionsRequired")) return;
  const json& required = doc["extensionsRequired"];
  if (!required.is_array()) r.fail("extensionsRequired", "must be an array of strings");
  for (size_t i = 0; i < required.size(); ++i) {
    const std::string name = r.string(required[i], JsonReader::at("extensionsRequired", i));
    if (std::find(kRequiredExtensionsRead.begin(), kRequiredExtensionsRead.end(), name) == kRequiredExtensionsRead.end())
      r.fail(JsonReader::at("extensionsRequired", i),
             "requires " + in_quotes(name) + ", which radrecon does not read (it reads the core glTF 2.0 geometry, "
             "baseColorFactor, emissiveFactor, KHR_materials_emissive_strength and the diffuseFactor of "
             "KHR_materials_pbrSpecularGlossiness): export without it (e.g. no quantization or compression)");
  }
}

/// The length of `field`'s array of numbers in node `where`, each finite, or refused.
void check_numbers(const JsonReader& r, const json& node, const std::string& where, const char* field, size_t count) {
  if (!node.contains(field)) return;
  const json& a = node[field];
  const std::string at = where + "." + field;
  if (!a.is_array() || a.size() != count) r.fail(at, "must be an array of " + std::to_string(count) + " numbers");
  for (size_t k = 0; k < count; ++k) r.number(a[k], JsonReader::at(at, k));
}

/// Refuses node transforms the schema forbids, which assimp 5.2 reads as something else without
/// a word (a translation of strings as 0, a short scale or matrix as none, a rotation of any length
/// as it stands): translation and scale of 3 numbers, rotation of 4 of unit length
/// (tol::kGltfUnitQuaternion), matrix of 16 with (0, 0, 0, 1) as its bottom row, not both a matrix
/// and any of the others; and morph
/// targets given weight (by the mesh or the node), which assimp does not apply.
void check_nodes(const JsonReader& r, const json& doc) {
  if (!doc.contains("nodes")) return;
  const json& nodes = doc["nodes"];
  if (!nodes.is_array()) r.fail("nodes", "must be an array");
  const json* meshes = doc.contains("meshes") && doc["meshes"].is_array() ? &doc["meshes"] : nullptr;
  const auto weighted = [&](const json& weights) {
    if (!weights.is_array()) return false;
    for (const json& w : weights)
      if (!w.is_number() || w.get<double>() != 0) return true;
    return false;
  };
  for (size_t i = 0; i < nodes.size(); ++i) {
    const std::string where = JsonReader::at("nodes", i);
    const json& node = nodes[i];
    if (!node.is_object()) r.fail(where, "must be an object");
    check_numbers(r, node, where, "translation", 3);
    check_numbers(r, node, where, "rotation", 4);
    check_numbers(r, node, where, "scale", 3);
    check_numbers(r, node, where, "matrix", 16);
    if (node.contains("matrix") && (node.contains("translation") || node.contains("rotation") || node.contains("scale")))
      r.fail(where, "has both a matrix and translation, rotation or scale (the glTF schema allows one or the other)");
    // Column-major: elements 3, 7, 11 and 15 are the bottom row, (0, 0, 0, 1) in any transform the
    // spec allows (one of translation, rotation and scale); assimp ignored another (a w of 2).
    if (node.contains("matrix")) {
      const json& m = node["matrix"];
      if (m[3].get<double>() != 0 || m[7].get<double>() != 0 || m[11].get<double>() != 0 || m[15].get<double>() != 1)
        r.fail(where + ".matrix", "its bottom row must be (0, 0, 0, 1) (elements 3, 7, 11, 15, column-major), got (" +
                                      format_number(m[3].get<double>()) + ", " + format_number(m[7].get<double>()) + ", " +
                                      format_number(m[11].get<double>()) + ", " + format_number(m[15].get<double>()) +
                                      "): a projection is no placement");
    }
    if (node.contains("rotation")) {
      double norm_sq = 0;
      for (const json& q : node["rotation"]) norm_sq += q.get<double>() * q.get<double>();
      if (!(std::abs(std::sqrt(norm_sq) - 1) <= tol::kGltfUnitQuaternion))
        r.fail(where + ".rotation", "must be a unit quaternion, its length is " + format_number(std::sqrt(norm_sq)));
    }
    if (!node.contains("mesh") || !node["mesh"].is_number_unsigned() || meshes == nullptr) continue;
    const size_t m = node["mesh"].get<size_t>();
    if (m >= meshes->size() || !(*meshes)[m].is_object()) continue;  // assimp refuses it
    const json& mesh = (*meshes)[m];
    bool targets = false;
    if (mesh.contains("primitives") && mesh["primitives"].is_array())
      for (const json& primitive : mesh["primitives"]) targets = targets || (primitive.is_object() && primitive.contains("targets"));
    if (targets && ((node.contains("weights") && weighted(node["weights"])) ||
                    (!node.contains("weights") && mesh.contains("weights") && weighted(mesh["weights"]))))
      r.fail(where, "shows mesh " + std::to_string(m) + " with morph targets of non-zero weight, which radrecon does not "
                    "apply (it reads the base shape): apply the shape keys before export");
  }
}

/// Refuses what the glTF schema forbids in the node tree and assimp 5.2 reads without a word: a
/// node that is a child of two parents, or listed twice by one, is shown once under each (a lamp
/// of 20.25 W shown three times, 60.75 W); a scene's root that is a child of another node is shown
/// twice. A `scene` past the scenes is refused naming it (assimp 5.2 said "GLTF: No scene").
/// Indices not integers >= 0 are check_gltf_indices()'s to refuse, those past their arrays assimp's.
void check_node_tree(const JsonReader& r, const json& doc) {
  const size_t scenes = doc.contains("scenes") && doc["scenes"].is_array() ? doc["scenes"].size() : 0;
  if (doc.contains("scene") && doc["scene"].is_number_unsigned() && doc["scene"].get<size_t>() >= scenes)
    r.fail("scene", std::to_string(doc["scene"].get<size_t>()) + " is out of range: the file has " +
                        (scenes == 0 ? std::string("no scenes") : std::to_string(scenes) + (scenes == 1 ? " scene" : " scenes")));
  if (!doc.contains("nodes") || !doc["nodes"].is_array()) return;
  const json& nodes = doc["nodes"];
  std::map<size_t, size_t> parent;  // child -> its parent
  for (size_t i = 0; i < nodes.size(); ++i) {
    if (!nodes[i].is_object() || !nodes[i].contains("children") || !nodes[i]["children"].is_array()) continue;
    for (const json& c : nodes[i]["children"]) {
      if (!c.is_number_unsigned()) continue;
      const size_t child = c.get<size_t>();
      if (const auto [it, first] = parent.emplace(child, i); !first && it->second == i)
        r.fail(JsonReader::at("nodes", i) + ".children", "lists nodes[" + std::to_string(child) + "] twice (the glTF schema lists each once)");
      else if (!first)
        r.fail(JsonReader::at("nodes", child), "is a child of nodes[" + std::to_string(it->second) + "] and of nodes[" +
                                                   std::to_string(i) + "]: a node has one parent at most (the glTF schema); give "
                                                   "each place a node of its own (they may share the mesh)");
    }
  }
  for (size_t s = 0; s < scenes; ++s) {
    const json& scene = doc["scenes"][s];
    if (!scene.is_object() || !scene.contains("nodes") || !scene["nodes"].is_array()) continue;
    std::set<size_t> roots;
    for (const json& n : scene["nodes"]) {
      if (!n.is_number_unsigned()) continue;
      const size_t node = n.get<size_t>();
      const std::string field = JsonReader::at("scenes", s) + ".nodes";
      if (const auto it = parent.find(node); it != parent.end())
        r.fail(field, "lists nodes[" + std::to_string(node) + "], a child of nodes[" + std::to_string(it->second) +
                          "]: a scene lists root nodes only (the glTF schema)");
      if (!roots.insert(node).second) r.fail(field, "lists nodes[" + std::to_string(node) + "] twice (the glTF schema lists each once)");
    }
  }
}

/// Refuses a mesh of no primitives (the schema requires one at least; assimp 5.2 dropped the mesh
/// without a word).
void check_meshes(const JsonReader& r, const json& doc) {
  if (!doc.contains("meshes") || !doc["meshes"].is_array()) return;
  for (size_t m = 0; m < doc["meshes"].size(); ++m) {
    const json& mesh = doc["meshes"][m];
    if (mesh.is_object() && mesh.contains("primitives") && mesh["primitives"].is_array() && mesh["primitives"].empty())
      r.fail(JsonReader::at("meshes", m) + ".primitives", "must hold at least one primitive (the glTF schema); it is empty");
  }
}

/// The meshes the default scene shows: those of the nodes reachable from it ("scene", else scene
/// 0), each once however many nodes show it. assimp 5.2 reads these and no others (its objects
/// load as the scene refers to them). Empty optional where the file has no scene (assimp refuses it).
std::optional<std::set<size_t>> default_scene_meshes(const json& doc) {
  if (!doc.contains("scenes") || !doc["scenes"].is_array() || doc["scenes"].empty()) return std::nullopt;
  const size_t index = doc.contains("scene") && doc["scene"].is_number_unsigned() ? doc["scene"].get<size_t>() : 0;
  if (index >= doc["scenes"].size() || !doc["scenes"][index].is_object()) return std::nullopt;
  const json& scene = doc["scenes"][index];
  const json* nodes = doc.contains("nodes") && doc["nodes"].is_array() ? &doc["nodes"] : nullptr;
  std::set<size_t> meshes, seen;
  std::vector<size_t> stack;
  const auto push_all = [&](const json& list) {
    if (!list.is_array()) return;
    for (const json& n : list)
      if (n.is_number_unsigned()) stack.push_back(n.get<size_t>());
  };
  if (scene.contains("nodes")) push_all(scene["nodes"]);
  while (!stack.empty() && nodes != nullptr) {
    const size_t n = stack.back();
    stack.pop_back();
    if (n >= nodes->size() || !seen.insert(n).second || !(*nodes)[n].is_object()) continue;
    const json& node = (*nodes)[n];
    if (node.contains("mesh") && node["mesh"].is_number_unsigned()) meshes.insert(node["mesh"].get<size_t>());
    if (node.contains("children")) push_all(node["children"]);
  }
  return meshes;
}

/// Refuses a binary glTF with a buffer in a file of its own (a "uri"): assimp 5.2 reads its
/// buffer views from the BIN chunk whatever the buffer ("Buffer view ... is out of range").
void check_glb_buffers(const JsonReader& r, const json& doc) {
  if (!doc.contains("buffers") || !doc["buffers"].is_array()) return;
  for (size_t i = 0; i < doc["buffers"].size(); ++i)
    if (doc["buffers"][i].is_object() && doc["buffers"][i].contains("uri"))
      r.fail(JsonReader::at("buffers", i) + ".uri",
             "a binary glTF (.glb) with a buffer in another file is not read: embed the buffer, or write a .gltf");
}

}  // namespace

GltfExtras read_gltf_extras(const std::string& path) {
  const std::string file = read_text_file(path, "mesh file");
  const bool binary = lower_extension(path) == ".glb";
  std::string text = file, bin;
  if (binary) std::tie(text, bin) = glb_chunks(file, path);
  const JsonReader r(path);
  // A modelling tool's file: a key it repeats where radrecon reads nothing (extras, extensions)
  // is no reason to refuse it; the last value counts, as in every glTF reader.
  const json doc = r.parse(text, "glTF file", JsonReader::Keys::as_parsed);
  if (!doc.is_object()) r.fail("(top level)", "must be a JSON object");
  const json& asset = r.member(doc, "asset", "");
  const std::string version = r.string(r.member(asset, "version", "asset"), "asset.version");
  if (version.rfind("2.", 0) != 0) r.fail("asset.version", "must be \"2.0\" (glTF 2.0), got \"" + version + "\"");
  check_required_extensions(r, doc);
  if (binary) check_glb_buffers(r, doc);
  check_nodes(r, doc);
  check_node_tree(r, doc);
  check_meshes(r, doc);
  check_gltf_indices(doc, bin, std::filesystem::path(path).parent_path().string(), path);
  GltfExtras extras;
  if (doc.contains("meshes") && doc["meshes"].is_array()) {
    const std::optional<std::set<size_t>> shown = default_scene_meshes(doc);
    for (size_t m = 0; m < doc["meshes"].size(); ++m) {
      const json& mesh = doc["meshes"][m];
      if (shown && !shown->count(m)) continue;
      if (mesh.is_object() && mesh.contains("primitives") && mesh["primitives"].is_array())
        for (const json& primitive : mesh["primitives"]) extras.faces += primitive_faces(doc, primitive);
    }
  }
  std::vector<GltfMaterialFactors>& out = extras.materials;
  json copy = doc;  // as assimp is to read it
  const bool padded = pad_strided_views(copy, bin, binary, path);
  if (!doc.contains("materials")) {
    extras.assimp_copy = !padded ? file : binary ? glb_with_json(copy.dump(), bin) : copy.dump();
    return extras;
  }
  const json& materials = doc["materials"];
  if (!materials.is_array()) r.fail("materials", "must be an array");
  for (size_t i = 0; i < materials.size(); ++i)
    if (copy["materials"][i].is_object()) copy["materials"][i]["name"] = gltf_material_tag(i);
  extras.assimp_copy = binary ? glb_with_json(copy.dump(), bin) : copy.dump();
  for (size_t i = 0; i < materials.size(); ++i) {
    const std::string where = JsonReader::at("materials", i);
    const json& m = materials[i];
    if (!m.is_object()) r.fail(where, "must be an object");
    GltfMaterialFactors f;
    if (m.contains("name")) f.name = r.string(m["name"], where + ".name");
    f.base_colour_field = where + ".pbrMetallicRoughness.baseColorFactor";
    if (m.contains("pbrMetallicRoughness") && m["pbrMetallicRoughness"].is_object() &&
        m["pbrMetallicRoughness"].contains("baseColorFactor"))
      f.base_colour = factor(r, m["pbrMetallicRoughness"]["baseColorFactor"], f.base_colour_field, 4, f.base_colour);
    if (m.contains("extensions") && m["extensions"].is_object() && m["extensions"].contains("KHR_materials_pbrSpecularGlossiness")) {
      const json& e = m["extensions"]["KHR_materials_pbrSpecularGlossiness"];
      f.base_colour_field = where + ".extensions.KHR_materials_pbrSpecularGlossiness.diffuseFactor";
      if (!e.is_object()) r.fail(where + ".extensions.KHR_materials_pbrSpecularGlossiness", "must be an object");
      f.base_colour = e.contains("diffuseFactor") ? factor(r, e["diffuseFactor"], f.base_colour_field, 4, Rgb::Ones()) : Rgb::Ones();
    }
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

std::string gltf_material_tag(size_t index) { return "radrecon#material#" + std::to_string(index); }

long long gltf_material_index(const std::string& name) {
  constexpr std::string_view kPrefix = "radrecon#material#";
  if (!name.starts_with(kPrefix) || name.size() == kPrefix.size() || name.size() > kPrefix.size() + 18) return -1;
  long long index = 0;
  for (size_t k = kPrefix.size(); k < name.size(); ++k) {
    if (name[k] < '0' || name[k] > '9') return -1;
    index = 10 * index + (name[k] - '0');
  }
  return index;
}

}  // namespace radrecon
