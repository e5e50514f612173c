#include "io/gltf_indices.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

#include "core/error.h"
#include "core/limits.h"

namespace radrecon {

namespace {

using json = nlohmann::json;

std::optional<std::string> base64_decode(const std::string& text) {
  std::string out;
  uint32_t bits = 0;
  int have = 0;
  for (char ch : text) {
    int v;
    if (ch >= 'A' && ch <= 'Z') v = ch - 'A';
    else if (ch >= 'a' && ch <= 'z') v = ch - 'a' + 26;
    else if (ch >= '0' && ch <= '9') v = ch - '0' + 52;
    else if (ch == '+') v = 62;
    else if (ch == '/') v = 63;
    else if (ch == '=') break;
    else return std::nullopt;
    bits = (bits << 6) | static_cast<uint32_t>(v);
    have += 6;
    if (have >= 8) {
      have -= 8;
      out += static_cast<char>((bits >> have) & 0xFF);
    }
  }
  return out;
}

/// A non-negative integer member, or nullopt.
std::optional<size_t> count_of(const json& obj, const char* key) {
  if (!obj.is_object() || !obj.contains(key) || !obj[key].is_number_unsigned()) return std::nullopt;
  return obj[key].get<size_t>();
}

const json* element(const json& doc, const char* array, std::optional<size_t> index) {
  if (!index || !doc.contains(array) || !doc[array].is_array() || *index >= doc[array].size()) return nullptr;
  return &doc[array][*index];
}

class Buffers {
 public:
  Buffers(const json& doc, const std::string& bin, std::string folder) : doc_(doc), bin_(bin), folder_(std::move(folder)) {}

  /// Buffer i's bytes, or nullptr if it cannot be resolved here.
  const std::string* get(size_t i) {
    if (auto it = cache_.find(i); it != cache_.end()) return it->second ? &*it->second : nullptr;
    std::optional<std::string>& slot = cache_[i];
    const json* buffer = element(doc_, "buffers", i);
    if (buffer == nullptr || !buffer->is_object()) return nullptr;
    if (!buffer->contains("uri")) {
      if (i == 0) slot = bin_;
    } else if ((*buffer)["uri"].is_string()) {
      const std::string uri = (*buffer)["uri"].get<std::string>();
      const size_t comma = uri.find(',');
      if (uri.rfind("data:", 0) == 0) {
        if (comma != std::string::npos && uri.substr(0, comma).find(";base64") != std::string::npos)
          slot = base64_decode(uri.substr(comma + 1));
      } else if (uri.find("://") == std::string::npos) {
        const std::string file = gltf_uri_file(folder_, uri);
        std::error_code ec;
        if (std::filesystem::is_regular_file(file, ec)) {  // not a pipe or a device
          check_input_file_size(file);
          std::ifstream in(file, std::ios::binary);
          if (in) {
            std::stringstream bytes;
            bytes << in.rdbuf();
            slot = bytes.str();
          }
        }
      }
    }
    return slot ? &*slot : nullptr;
  }

 private:
  const json& doc_;
  const std::string& bin_;
  std::string folder_;
  std::map<size_t, std::optional<std::string>> cache_;
};

size_t component_bytes(size_t type) {
  switch (type) {
    case 5120: case 5121: return 1;
    case 5122: case 5123: return 2;
    case 5125: case 5126: return 4;
    default: return 0;
  }
}

size_t components(const std::string& type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "VEC4" || type == "MAT2") return 4;
  if (type == "MAT3") return 9;
  if (type == "MAT4") return 16;
  return 0;
}

/// `value` (field `field`) as the glTF schema has an integer: a JSON integer (not 2.0) in [lo, hi]
/// and a multiple of `multiple`; refused naming the field otherwise.
void check_integer(const json& value, const std::string& field, const std::string& path, uint64_t lo,
                   uint64_t hi = std::numeric_limits<uint64_t>::max(), uint64_t multiple = 1) {
  if (value.is_number_unsigned()) {
    const uint64_t v = value.get<uint64_t>();
    if (v >= lo && v <= hi && v % multiple == 0) return;
  }
  const std::string range = multiple > 1 ? "a multiple of " + std::to_string(multiple) + " in [" + std::to_string(lo) + ", " +
                                               std::to_string(hi) + "]"
                            : hi == std::numeric_limits<uint64_t>::max() ? "an integer >= " + std::to_string(lo)
                                                                         : "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  throw UserError(path, field + ": must be " + range + " (the glTF schema), got " + value.dump());
}

/// obj[key] by check_integer() if present (or refused as missing if `required`).
void check_member(const json& obj, const char* key, const std::string& where, const std::string& path, uint64_t lo,
                  bool required = false, uint64_t hi = std::numeric_limits<uint64_t>::max(), uint64_t multiple = 1) {
  if (!obj.is_object()) return;
  const std::string field = where + "." + key;
  if (!obj.contains(key)) {
    if (required) throw UserError(path, field + ": missing (the glTF schema requires it)");
    return;
  }
  check_integer(obj[key], field, path, lo, hi, multiple);
}

/// Every element of the array obj[key] (if it is one) by check_integer(), as an index (>= 0).
void check_indices(const json& obj, const char* key, const std::string& where, const std::string& path) {
  if (!obj.is_object() || !obj.contains(key) || !obj[key].is_array()) return;
  for (size_t k = 0; k < obj[key].size(); ++k) check_integer(obj[key][k], where + "." + key + "[" + std::to_string(k) + "]", path, 0);
}

/// The array doc[name]'s objects, with their names ("accessors[3]").
template <typename F>
void each(const json& doc, const char* name, F f) {
  if (!doc.contains(name) || !doc[name].is_array()) return;
  for (size_t i = 0; i < doc[name].size(); ++i)
    if (doc[name][i].is_object()) f(doc[name][i], std::string(name) + "[" + std::to_string(i) + "]");
}

/// Every integer field radrecon or assimp reads, as the glTF 2.0 schema bounds it: offsets and
/// indices >= 0, counts and lengths >= 1, a byteStride a multiple of 4 in [4, 252], a mode in
/// [0, 6]. assimp 5.2 reads a negative or fractional one (or one written 2.0) as absent: an
/// accessor's byteOffset of -2 as 0 (other indices, a lamp 79 times too bright, exit 0), a
/// primitive's indices of -1 as none, a byteStride of -12 as tightly packed.
void check_gltf_integers(const json& doc, const std::string& path) {
  if (doc.contains("scene")) check_integer(doc["scene"], "scene", path, 0);
  each(doc, "scenes", [&](const json& scene, const std::string& where) { check_indices(scene, "nodes", where, path); });
  each(doc, "nodes", [&](const json& node, const std::string& where) {
    for (const char* key : {"mesh", "camera", "skin"}) check_member(node, key, where, path, 0);
    check_indices(node, "children", where, path);
  });
  each(doc, "meshes", [&](const json& mesh, const std::string& where) {
    if (!mesh.contains("primitives") || !mesh["primitives"].is_array()) return;
    for (size_t p = 0; p < mesh["primitives"].size(); ++p) {
      const json& primitive = mesh["primitives"][p];
      const std::string at = where + ".primitives[" + std::to_string(p) + "]";
      check_member(primitive, "indices", at, path, 0);
      check_member(primitive, "material", at, path, 0);
      check_member(primitive, "mode", at, path, 0, false, 6);
      if (primitive.is_object() && primitive.contains("attributes") && primitive["attributes"].is_object())
        for (const auto& [name, index] : primitive["attributes"].items()) check_integer(index, at + ".attributes." + name, path, 0);
    }
  });
  each(doc, "accessors", [&](const json& a, const std::string& where) {
    check_member(a, "bufferView", where, path, 0);
    check_member(a, "byteOffset", where, path, 0);
    check_member(a, "count", where, path, 1);
    if (!a.contains("sparse") || !a["sparse"].is_object()) return;
    const json& sparse = a["sparse"];
    check_member(sparse, "count", where + ".sparse", path, 1);
    for (const char* part : {"indices", "values"})
      if (sparse.contains(part)) {
        check_member(sparse[part], "bufferView", where + ".sparse." + part, path, 0);
        check_member(sparse[part], "byteOffset", where + ".sparse." + part, path, 0);
      }
  });
  each(doc, "bufferViews", [&](const json& view, const std::string& where) {
    check_member(view, "buffer", where, path, 0, true);
    check_member(view, "byteOffset", where, path, 0);
    check_member(view, "byteLength", where, path, 1, true);
    check_member(view, "byteStride", where, path, 4, false, 252, 4);
  });
  each(doc, "buffers", [&](const json& buffer, const std::string& where) { check_member(buffer, "byteLength", where, path, 1, true); });
}

/// Every accessor's elements fit its buffer view, and every view its buffer (byteLength): assimp
/// 5.2 refuses an accessor that does not, but leaks memory on the way (LeakSanitizer, found by
/// fuzzing), so radrecon refuses it first.
void check_gltf_accessors(const json& doc, const std::string& path) {
  if (!doc.contains("accessors") || !doc["accessors"].is_array()) return;
  for (size_t i = 0; i < doc["accessors"].size(); ++i) {
    const json& a = doc["accessors"][i];
    const std::string where = "accessors[" + std::to_string(i) + "]";
    if (!a.is_object()) continue;
    const std::optional<size_t> count = count_of(a, "count"), type = count_of(a, "componentType");
    const size_t bytes = type ? component_bytes(*type) : 0;
    const size_t n = a.contains("type") && a["type"].is_string() ? components(a["type"].get<std::string>()) : 0;
    if (!count || bytes == 0 || n == 0)
      throw UserError(path, where + ": needs a count, a componentType (5120-5126) and a type (SCALAR, VECn, MATn)");
    const json* view = element(doc, "bufferViews", count_of(a, "bufferView"));
    if (view == nullptr || *count == 0) continue;  // no view: zeros (or sparse), assimp's to read
    const size_t element_bytes = bytes * n;
    const size_t stride = count_of(*view, "byteStride").value_or(element_bytes);
    const size_t offset = count_of(a, "byteOffset").value_or(0);
    const std::optional<size_t> length = count_of(*view, "byteLength");
    if (!length || stride < element_bytes || offset > *length || *length - offset < element_bytes ||
        (*count - 1) > (*length - offset - element_bytes) / stride)
      throw UserError(path, where + ": its " + std::to_string(*count) + " elements of " + std::to_string(element_bytes) +
                                " bytes do not fit its buffer view");
    const json* buffer = element(doc, "buffers", count_of(*view, "buffer"));
    const size_t buffer_bytes = buffer ? count_of(*buffer, "byteLength").value_or(0) : 0;  // 0: none or no length
    const size_t view_offset = count_of(*view, "byteOffset").value_or(0);
    if (view_offset > buffer_bytes || *length > buffer_bytes - view_offset)
      throw UserError(path, where + ": its buffer view does not fit its buffer");
  }
}

/// A POSITION accessor is of VEC3 FLOAT, as the glTF 2.0 spec requires (assimp 5.2 read a VEC3
/// of UNSIGNED_SHORT as floats: a floor 5.6e-45 m long; a VEC2 or a NaN as faces of no area,
/// dropped with a warning), and its values are finite.
void check_positions(const json& doc, Buffers& buffers, size_t accessor, const std::string& path) {
  const json& a = doc["accessors"][accessor];
  const std::string where = "accessors[" + std::to_string(accessor) + "]";
  if (!a.is_object()) return;
  if (!(a.contains("type") && a["type"] == "VEC3" && count_of(a, "componentType") == size_t{5126}))
    throw UserError(path, where + ": a POSITION accessor must be of type VEC3 and componentType 5126 (FLOAT), got " +
                              (a.contains("type") ? a["type"].dump() : std::string("no type")) + " of " +
                              (a.contains("componentType") ? a["componentType"].dump() : std::string("no componentType")) +
                              " (quantized positions, KHR_mesh_quantization, are not read)");
  const json* view = element(doc, "bufferViews", count_of(a, "bufferView"));
  const std::optional<size_t> count = count_of(a, "count");
  if (view == nullptr || !count || a.contains("sparse")) return;
  const std::optional<size_t> buffer_index = count_of(*view, "buffer");
  const std::string* bytes = buffer_index ? buffers.get(*buffer_index) : nullptr;
  const size_t stride = count_of(*view, "byteStride").value_or(12);
  const size_t start = count_of(*view, "byteOffset").value_or(0) + count_of(a, "byteOffset").value_or(0);
  // Fits its view and buffer (check_gltf_accessors()), if the bytes are there as declared.
  if (bytes == nullptr || *count == 0 || start > bytes->size() || (*count - 1) * stride + 12 > bytes->size() - start) return;
  for (size_t k = 0; k < *count; ++k)
    for (size_t c = 0; c < 3; ++c) {
      float v;
      std::memcpy(&v, bytes->data() + start + k * stride + 4 * c, sizeof v);  // little-endian, as the spec's
      if (!std::isfinite(v))
        throw UserError(path, where + ": vertex " + std::to_string(k) + " has a coordinate that is not finite (" +
                                  std::to_string(v) + ")");
    }
}

}  // namespace

bool pad_strided_views(json& copy, std::string& bin, bool binary, const std::string& path) {
  if (!copy.contains("accessors") || !copy["accessors"].is_array()) return false;
  std::map<size_t, uint64_t> needed;  // view -> the bytes assimp needs of it
  for (size_t i = 0; i < copy["accessors"].size(); ++i) {
    const json& a = copy["accessors"][i];
    if (!a.is_object() || a.contains("sparse")) continue;
    const std::optional<size_t> v = count_of(a, "bufferView"), count = count_of(a, "count"), type = count_of(a, "componentType");
    const json* view = element(copy, "bufferViews", v);
    if (view == nullptr || !count || !type || !a.contains("type") || !a["type"].is_string()) continue;
    const uint64_t element_bytes = component_bytes(*type) * components(a["type"].get<std::string>());
    const uint64_t stride = count_of(*view, "byteStride").value_or(0), length = count_of(*view, "byteLength").value_or(0);
    // Checked to fit (check_gltf_accessors()): (count - 1) * stride + element_bytes <= length.
    if (stride <= element_bytes || *count * stride <= length) continue;
    needed[*v] = std::max(needed[*v], static_cast<uint64_t>(*count) * stride);
    const json* buffer = element(copy, "buffers", count_of(*view, "buffer"));
    const uint64_t view_offset = count_of(*view, "byteOffset").value_or(0);
    const uint64_t buffer_length = buffer ? count_of(*buffer, "byteLength").value_or(0) : 0;
    if (view_offset + needed[*v] <= buffer_length) continue;
    // At its buffer's end: a .glb's BIN chunk (buffer 0 without a uri) is padded with zeros here;
    // another buffer is not radrecon's to rewrite.
    const bool glb_bin = binary && buffer != nullptr && count_of(*view, "buffer") == size_t{0} && !buffer->contains("uri") &&
                         bin.size() >= buffer_length;
    if (!glb_bin)
      throw UserError(path, "accessors[" + std::to_string(i) + "]: its buffer view's last element is not padded to the byteStride " +
                                std::to_string(stride) + " (bufferViews[" + std::to_string(*v) + "].byteLength " + std::to_string(length) +
                                ", at the end of its buffer): valid glTF, but the model reader (assimp 5.2) needs count x byteStride = " +
                                std::to_string(*count) + " x " + std::to_string(stride) + " = " + std::to_string(*count * stride) +
                                " bytes in the view; pad the buffer and the view to that length, or write the model as .glb");
    copy["buffers"][0]["byteLength"] = view_offset + needed[*v];
    if (bin.size() < view_offset + needed[*v]) bin.resize(view_offset + needed[*v], '\0');
  }
  for (const auto& [v, bytes] : needed) copy["bufferViews"][v]["byteLength"] = bytes;
  return !needed.empty();
}

void check_gltf_indices(const json& doc, const std::string& bin, const std::string& folder, const std::string& path) {
  check_gltf_integers(doc, path);
  check_gltf_accessors(doc, path);
  if (!doc.contains("meshes") || !doc["meshes"].is_array()) return;
  Buffers buffers(doc, bin, folder);
  for (size_t m = 0; m < doc["meshes"].size(); ++m) {
    const json& mesh = doc["meshes"][m];
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    for (size_t p = 0; p < mesh["primitives"].size(); ++p) {
      const json& primitive = mesh["primitives"][p];
      if (!primitive.is_object() || !primitive.contains("attributes") || !primitive["attributes"].is_object()) continue;
      const json* positions = element(doc, "accessors", count_of(primitive["attributes"], "POSITION"));
      const json* indices = element(doc, "accessors", count_of(primitive, "indices"));
      // Triangles (mode 4, the default) take their corners three at a time: the glTF 2.0 spec
      // requires a count divisible by 3, and assimp 5.2 drops the rest without a word.
      const bool triangles = !primitive.contains("mode") || (primitive["mode"].is_number_unsigned() && primitive["mode"] == 4);
      const json* corners = primitive.contains("indices") ? indices : positions;
      if (triangles && corners != nullptr && corners->is_object())
        if (const std::optional<size_t> count = count_of(*corners, "count"); count && *count % 3 != 0)
          throw UserError(path, "meshes[" + std::to_string(m) + "].primitives[" + std::to_string(p) + "]: " + std::to_string(*count) +
                                    (indices != nullptr ? " indices" : " vertices without indices") +
                                    " for triangles (mode 4), not a multiple of 3");
      if (positions != nullptr) check_positions(doc, buffers, count_of(primitive["attributes"], "POSITION").value(), path);
      if (positions == nullptr || indices == nullptr || !indices->is_object() || indices->contains("sparse")) continue;
      const std::optional<size_t> vertices = count_of(*positions, "count"), count = count_of(*indices, "count");
      // A line loop of one index: assimp 5.2 reads a second one past its end (an assertion ends
      // the program; found by fuzzing).
      if (count && *count < 2 && primitive.contains("mode") && primitive["mode"] == 2)
        throw UserError(path, "meshes[" + std::to_string(m) + "].primitives[" + std::to_string(p) +
                                  "]: a line loop (mode 2) of " + std::to_string(*count) + " index (fewer than 2)");
      const json* view = element(doc, "bufferViews", count_of(*indices, "bufferView"));
      const std::optional<size_t> type = count_of(*indices, "componentType");
      if (!vertices || !count || view == nullptr || !type) continue;
      const size_t size = *type == 5121 ? 1 : *type == 5123 ? 2 : *type == 5125 ? 4 : 0;
      const std::optional<size_t> buffer_index = count_of(*view, "buffer"), view_length = count_of(*view, "byteLength");
      const size_t view_offset = count_of(*view, "byteOffset").value_or(0), offset = count_of(*indices, "byteOffset").value_or(0);
      if (size == 0 || !buffer_index || !view_length) continue;
      const std::string* bytes = buffers.get(*buffer_index);
      if (bytes == nullptr || view_offset > bytes->size() || *view_length > bytes->size() - view_offset ||
          offset > *view_length || *count > (*view_length - offset) / size)
        continue;
      const size_t start = view_offset + offset;
      for (size_t k = 0; k < *count; ++k) {
        uint32_t index = 0;
        for (size_t b = size; b-- > 0;) index = (index << 8) | static_cast<unsigned char>((*bytes)[start + k * size + b]);
        if (index >= *vertices)
          throw UserError(path, "meshes[" + std::to_string(m) + "].primitives[" + std::to_string(p) + "]: vertex index " +
                                    std::to_string(index) + " out of range (" + std::to_string(*vertices) + " vertices)");
      }
    }
  }
}

}  // namespace radrecon
