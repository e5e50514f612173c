#include "export/gltf.h"

#include <bit>
#include <cstdint>
#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "core/check.h"
#include "core/error.h"
#include "core/tolerances.h"
#include "io/atomic_file.h"
#include "io/image_io.h"
#include "scene/side.h"
#include "solver/covered.h"

namespace radrecon {

namespace {

// glTF 2.0 constants (the specification's enumerations).
constexpr int kFloat = 5126, kUnsignedShort = 5123, kArrayBuffer = 34962, kElementArrayBuffer = 34963;
constexpr int kLinear = 9729, kClampToEdge = 33071;
constexpr std::uint32_t kGlbMagic = 0x46546C67, kJsonChunk = 0x4E4F534A, kBinChunk = 0x004E4942;

// glTF's binary data is little endian; the floats and integers are copied as the machine holds them.
static_assert(std::endian::native == std::endian::little, "the glTF writer assumes a little-endian machine");

/// The binary chunk being assembled: every piece 4-byte aligned, as glTF requires of accessors.
struct Binary {
  std::vector<std::uint8_t> bytes;
  nlohmann::json views = nlohmann::json::array();

  /// Appends `data` as a new buffer view; returns its index.
  int add(const void* data, size_t size, int target) {
    while (bytes.size() % 4 != 0) bytes.push_back(0);
    nlohmann::json view = {{"buffer", 0}, {"byteOffset", bytes.size()}, {"byteLength", size}};
    if (target != 0) view["target"] = target;
    const auto* p = static_cast<const std::uint8_t*>(data);
    bytes.insert(bytes.end(), p, p + size);
    views.push_back(view);
    return static_cast<int>(views.size()) - 1;
  }
};

void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) out.push_back(static_cast<std::uint8_t>(v >> (8 * k)));  // little endian
}

}  // namespace

Vec3 export_origin(const Scene& scene) {
  Vec3 lo = Vec3::Constant(INFINITY), hi = -lo;
  for (const Surface& s : scene.surfaces)
    for (const Vec3& c : s.polygon()) lo = lo.cwiseMin(c), hi = hi.cwiseMax(c);
  const Vec3 centre = 0.5 * (lo + hi);
  const double extent = (hi - lo).maxCoeff();
  if (!(centre.cwiseAbs().maxCoeff() > tol::kExportOriginFreeExtents * extent)) return Vec3::Zero();
  // The centre rounded to a multiple of a power of two at least the extent and at least a float's
  // spacing at the centre's magnitude: a float exactly, so that a reader holding the translation
  // as a float (most do) holds it exactly. (The extent's alone left 6378137.25 for a 0.1 m model
  // at x = 6,378,137.3 m, which a float reader took as 6378137: the model moved by 0.25 m.)
  const int float_spacing_exponent = std::ilogb(centre.cwiseAbs().maxCoeff()) - (std::numeric_limits<float>::digits - 1);
  const double step = std::exp2(std::max<double>(std::ceil(std::log2(extent)), float_spacing_exponent));
  return (centre / step).array().round().matrix() * step;
}

std::vector<double> export_raise_m(const Scene& scene) {
  const size_t n = scene.surfaces.size();
  // By cover, the bases it overlaps (a coplanar neighbour touching a base's edge is none).
  std::vector<std::vector<size_t>> bases(n);
  const std::vector<std::vector<size_t>> covering = covering_surfaces(scene);
  for (size_t base = 0; base < n; ++base) {
    const Surface& b = scene.surfaces[base];
    for (const size_t cover : covering[base]) {
      ConvexPolygon p;
      for (const Vec3& c : scene.surfaces[cover].polygon()) p.push(c);
      if (exposed_fraction(b.polygon(), b.normal(), std::span(&p, 1)) < 1) bases[cover].push_back(base);
    }
  }
  // A cover's own step (its size's share) over the highest of its bases' raises: a canvas on a
  // frame on a wall stands above both. Covers are smaller than their bases, so the chains end.
  std::vector<double> raise(n, -1);
  const auto raise_of = [&](const auto& self, size_t k) -> double {
    if (raise[k] >= 0) return raise[k];
    double below = 0;
    for (const size_t base : bases[k]) below = std::max(below, self(self, base));
    const Surface& s = scene.surfaces[k];
    raise[k] = bases[k].empty() ? 0 : below + tol::kExportRaisedRelative * std::max(s.length_u_m(), s.length_v_m());
    return raise[k];
  };
  for (size_t k = 0; k < n; ++k) raise_of(raise_of, k);
  return raise;
}

void write_lightmapped_glb(const std::filesystem::path& path, const Scene& scene, const Solution& solution,
                           const LightmapAtlas& atlas, double white_w_m2, const nlohmann::json& extras) {
  RR_CHECK(white_w_m2 > 0, "the white point must be positive");
  Binary bin;
  const Vec3 origin = export_origin(scene);
  const std::vector<double> raise_m = export_raise_m(scene);
  nlohmann::json accessors = nlohmann::json::array(), meshes = nlohmann::json::array(), nodes = nlohmann::json::array();
  for (const LightmapTile& tile : atlas.tiles) {
    const Surface& surface = scene.surfaces[tile.side.surface];
    const bool back = tile.side.back_side;
    // Corners in (u, v), counter-clockwise seen from the side's front.
    std::vector<Vec2> uv = surface.is_triangle() ? std::vector<Vec2>{{0, 0}, {1, 0}, {0, 1}}
                                                 : std::vector<Vec2>{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    if (back) std::reverse(uv.begin() + 1, uv.end());
    const Vec3 n = side_normal(surface, back);
    std::vector<float> position, normal, texcoord;
    Vec3 lo = Vec3::Constant(INFINITY), hi = -lo;
    for (const Vec2& c : uv) {
      // Exact: the origin is near the model. A surface lying on another is raised off it.
      const Vec3 p = surface.point(c.x(), c.y()) - origin + raise_m[tile.side.surface] * n;
      const Vec2 t = atlas.texture_coordinate(tile, c.x(), c.y());
      for (int k = 0; k < 3; ++k) {
        position.push_back(static_cast<float>(p[k]));
        normal.push_back(static_cast<float>(n[k]));
      }
      texcoord.push_back(static_cast<float>(t.x()));
      texcoord.push_back(static_cast<float>(t.y()));
      lo = lo.cwiseMin(p.cast<float>().cast<double>());
      hi = hi.cwiseMax(p.cast<float>().cast<double>());
    }
    std::vector<std::uint16_t> index = {0, 1, 2};
    if (uv.size() == 4) index.insert(index.end(), {0, 2, 3});
    const auto count = uv.size();
    const int a = static_cast<int>(accessors.size());
    accessors.push_back({{"bufferView", bin.add(position.data(), position.size() * 4, kArrayBuffer)}, {"componentType", kFloat},
                         {"count", count}, {"type", "VEC3"}, {"min", {lo.x(), lo.y(), lo.z()}}, {"max", {hi.x(), hi.y(), hi.z()}}});
    accessors.push_back({{"bufferView", bin.add(normal.data(), normal.size() * 4, kArrayBuffer)}, {"componentType", kFloat},
                         {"count", count}, {"type", "VEC3"}});
    accessors.push_back({{"bufferView", bin.add(texcoord.data(), texcoord.size() * 4, kArrayBuffer)}, {"componentType", kFloat},
                         {"count", count}, {"type", "VEC2"}});
    accessors.push_back({{"bufferView", bin.add(index.data(), index.size() * 2, kElementArrayBuffer)},
                         {"componentType", kUnsignedShort}, {"count", index.size()}, {"type", "SCALAR"}});
    const std::string& name = solution.surfaces[tile.solution_side].name;
    meshes.push_back({{"name", name},
                      {"primitives", {{{"attributes", {{"POSITION", a}, {"NORMAL", a + 1}, {"TEXCOORD_0", a + 2}}},
                                       {"indices", a + 3}, {"material", 0}}}}});
    nodes.push_back({{"name", name}, {"mesh", meshes.size() - 1}});
    if (origin != Vec3::Zero()) nodes.back()["translation"] = {origin.x(), origin.y(), origin.z()};
  }
  const int image_view = [&] {
    const std::vector<std::uint8_t> png = encode_png_tone_mapped(atlas.radiosity_w_m2, white_w_m2);
    return bin.add(png.data(), png.size(), 0);
  }();
  while (bin.bytes.size() % 4 != 0) bin.bytes.push_back(0);

  nlohmann::json asset_extras = extras;
  asset_extras["white_w_m2"] = white_w_m2;
  asset_extras["texels_per_metre"] = atlas.texels_per_metre;
  asset_extras["lightmap"] = "emissive texture: sRGB of clamp(radiosity / white_w_m2, 0, 1) per channel";
  nlohmann::json scene_nodes = nlohmann::json::array();
  for (size_t k = 0; k < nodes.size(); ++k) scene_nodes.push_back(k);
  const nlohmann::json doc = {
      {"asset", {{"version", "2.0"}, {"generator", "radrecon export"}, {"extras", asset_extras}}},
      {"scene", 0},
      {"scenes", {{{"name", solution.scene}, {"nodes", scene_nodes}}}},
      {"nodes", nodes},
      {"meshes", meshes},
      {"materials", {{{"name", "lightmap"},
                      {"pbrMetallicRoughness", {{"baseColorFactor", {0, 0, 0, 1}}, {"metallicFactor", 0}, {"roughnessFactor", 1}}},
                      {"emissiveTexture", {{"index", 0}}},
                      {"emissiveFactor", {1, 1, 1}}}}},
      {"textures", {{{"sampler", 0}, {"source", 0}}}},
      {"samplers", {{{"magFilter", kLinear}, {"minFilter", kLinear}, {"wrapS", kClampToEdge}, {"wrapT", kClampToEdge}}}},
      {"images", {{{"bufferView", image_view}, {"mimeType", "image/png"}, {"name", "lightmap"}}}},
      {"accessors", accessors},
      {"bufferViews", bin.views},
      {"buffers", {{{"byteLength", bin.bytes.size()}}}},
  };
  std::string json = doc.dump();
  while (json.size() % 4 != 0) json.push_back(' ');  // the JSON chunk is padded with spaces

  std::vector<std::uint8_t> glb;
  put_u32(glb, kGlbMagic);
  put_u32(glb, 2);
  put_u32(glb, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.bytes.size()));
  put_u32(glb, static_cast<std::uint32_t>(json.size()));
  put_u32(glb, kJsonChunk);
  glb.insert(glb.end(), json.begin(), json.end());
  put_u32(glb, static_cast<std::uint32_t>(bin.bytes.size()));
  put_u32(glb, kBinChunk);
  glb.insert(glb.end(), bin.bytes.begin(), bin.bytes.end());
  write_binary_file(path, glb);
}

}  // namespace radrecon
