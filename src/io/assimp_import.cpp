#include "io/assimp_import.h"

#include <assimp/DefaultIOSystem.h>
#include <assimp/Importer.hpp>
#include <assimp/MemoryIOWrapper.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <set>
#include <sstream>

#include "core/check.h"
#include "core/error.h"
#include "core/limits.h"
#include "core/parse.h"
#include "core/tolerances.h"
#include "io/gltf_extras.h"
#include "io/gltf_indices.h"
#include "io/json_reader.h"
#include "io/mesh_polygons.h"
#include "io/obj_check.h"
#include "io/ply_check.h"

namespace radrecon {

namespace {

using Format = MeshFormat;

/// Reflectance 0.5 grey: what a face gets when its file gives it none (docs/formats.md).
const Rgb kDefaultReflectance = Rgb::Constant(0.5);
/// The largest reflectance a file's colour is clamped to (radrecon needs reflectance < 1).
constexpr double kMaxReflectance = 0.999;

struct Material {
  Rgb reflectance = kDefaultReflectance;
  Rgb emission_w_m2 = Rgb::Zero();
};

std::string rgb_text(const Rgb& c) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%g, %g, %g)", c[0], c[1], c[2]);
  return buf;
}

/// A file's colour as a reflectance: refused if not finite, clamped into [0, 0.999] with a warning.
Rgb reflectance_from(const Rgb& c, const std::string& path, const std::string& what, std::vector<std::string>& warnings) {
  if (!c.allFinite()) throw UserError(path, what + " is not finite " + rgb_text(c));
  const Rgb clamped = c.max(0.0).min(kMaxReflectance);
  if ((clamped != c).any())
    warnings.push_back(path + ": " + what + " " + rgb_text(c) + " clamped to " + rgb_text(clamped) +
                       " (a reflectance must lie in [0, 1))");
  return clamped;
}

Rgb emission_from(const Rgb& c, const std::string& path, const std::string& what) {
  if (!c.allFinite() || (c < 0).any() || (c > tol::kMaxEmission_w_m2).any())
    throw UserError(path, what + " must be finite, >= 0 and at most " + format_number(tol::kMaxEmission_w_m2) + " W/m^2, got " + rgb_text(c));
  return c;
}

std::vector<Material> read_materials(const aiScene& scene, Format format, const std::string& path,
                                     const std::vector<GltfMaterialFactors>& gltf, const ObjMaterials& obj,
                                     std::vector<std::string>& warnings) {
  std::vector<Material> out(scene.mNumMaterials);
  for (unsigned i = 0; i < scene.mNumMaterials; ++i) {
    const aiMaterial* m = scene.mMaterials[i];
    if (m == nullptr) throw UserError(path, "material " + std::to_string(i) + " is missing");
    aiString ai_name;
    m->Get(AI_MATKEY_NAME, ai_name);
    const std::string name = ai_name.C_Str();
    const std::string what = "material '" + name + "'";
    Material& mat = out[i];
    if (format == Format::kObj) {
      // assimp reads no MTL file (io/obj_check.h): its materials are the `usemtl` names.
      const auto found = obj.defined.find(name);
      if (found == obj.defined.end()) continue;  // faces before any usemtl, or of an undefined one: the default
      if (found->second.kd) mat.reflectance = reflectance_from(*found->second.kd, path, what + " Kd", warnings);
      if (found->second.ke) mat.emission_w_m2 = emission_from(*found->second.ke, path, what + " Ke");
    } else if (format == Format::kGltf) {
      // The copy assimp read names each material by its index in the file (io/gltf_extras.h);
      // another name is assimp's default material, for a primitive without one: 0.5 grey.
      const long long index = gltf_material_index(name);
      if (index < 0) continue;
      RR_CHECK(static_cast<size_t>(index) < gltf.size(), "a glTF material tag past the file's materials");
      const GltfMaterialFactors& f = gltf[static_cast<size_t>(index)];
      const std::string field = f.name.empty() ? "materials[" + std::to_string(index) + "]" : "material '" + f.name + "'";
      const std::string base = f.base_colour_field.substr(f.base_colour_field.find('.') + 1);
      mat.reflectance = reflectance_from(f.base_colour, path, field + " " + base, warnings);
      mat.emission_w_m2 = emission_from(f.emissive * f.emissive_strength, path, field + " emissiveFactor x emissiveStrength");
    }
    // PLY: no material; vertex colours per face (below), else the default.
  }
  return out;
}

void check_finite_vertex(const aiVector3D& v, const std::string& path, const std::string& mesh, unsigned index) {
  if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
    throw UserError(path, "mesh '" + mesh + "' vertex " + std::to_string(index) +
                              " has a coordinate that is not finite, or beyond single precision's range (3.4e38) in which the "
                              "model reader holds it (" +
                              std::to_string(v.x) + ", " + std::to_string(v.y) + ", " + std::to_string(v.z) + ")");
}

bool degenerate(std::span<const Vec3> c) {
  double longest_sq = 0;
  for (size_t i = 0; i < c.size(); ++i) longest_sq = std::max(longest_sq, (c[(i + 1) % c.size()] - c[i]).squaredNorm());
  Surface s;
  if (c.size() == 3) s.set_triangle(c[0], c[1], c[2]);
  else std::copy(c.begin(), c.end(), s.corners.begin());
  return longest_sq == 0 || !(s.area_m2() > tol::kDegenerateAreaRelative * longest_sq);
}

/// A name fit for the scene and its JSON files: '/' (reserved for sides), control characters and
/// bytes that are not valid UTF-8 replaced by '_'.
std::string clean_name(const std::string& raw) {
  std::string out;
  for (size_t i = 0; i < raw.size();) {
    const unsigned char c = static_cast<unsigned char>(raw[i]);
    size_t length = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 0;
    bool valid = length > 0 && i + length <= raw.size();
    for (size_t k = 1; valid && k < length; ++k) valid = (static_cast<unsigned char>(raw[i + k]) >> 6) == 0x2;
    if (!valid) {
      out += '_';
      ++i;
      continue;
    }
    out += (length == 1 && (c < 0x20 || c == 0x7F || c == '/')) ? std::string("_") : raw.substr(i, length);
    i += length;
  }
  return out;
}

/// assimp's file access for a glTF: the file itself from radrecon's copy (GltfExtras::assimp_copy,
/// which outlives it), the others from disk, a percent-encoded URI decoded (assimp 5.2 opens
/// "my%20model.bin" as written): a file that does not exist as named is looked for decoded.
class GltfIOSystem final : public Assimp::DefaultIOSystem {
 public:
  GltfIOSystem(std::string path, const std::string& copy)
      : path_(std::move(path)), folder_(std::filesystem::path(path_).parent_path().string()), copy_(copy) {}
  bool Exists(const char* file) const override { return is_copy(file) || DefaultIOSystem::Exists(resolve(file).c_str()); }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (is_copy(file)) return new Assimp::MemoryIOStream(reinterpret_cast<const uint8_t*>(copy_.data()), copy_.size());
    return DefaultIOSystem::Open(resolve(file).c_str(), mode);
  }

 private:
  bool is_copy(const char* file) const { return path_ == file; }
  /// A file in the glTF's folder by the URI after it, as radrecon's index check opens it
  /// (gltf_uri_file(): one rule for both); any other as named.
  std::string resolve(const char* file) const {
    const std::string name(file);
    const std::string prefix = folder_.empty() ? std::string() : folder_ + "/";
    if (name.compare(0, prefix.size(), prefix) != 0) return name;
    return gltf_uri_file(folder_, name.substr(prefix.size()));
  }
  std::string path_, folder_;
  const std::string& copy_;
};

class Builder {
 public:
  /// `file_offset_m`: added to every vertex assimp read, before the node transforms (an OBJ moved
  /// to the origin for assimp's floats, io/obj_check.h). `face_colours`: a PLY's, one per face of
  /// the scene's one mesh, or null.
  Builder(const aiScene& scene, Format format, std::string path, const std::vector<GltfMaterialFactors>& gltf,
          const ObjMaterials& obj, const MeshPlacement& placement, const Vec3& file_offset_m,
          const std::vector<Rgb>* face_colours, MeshImport& out)
      : scene_(scene), format_(format), path_(std::move(path)), placement_(placement), file_offset_m_(file_offset_m),
        face_colours_(face_colours), out_(out) {
    stem_ = std::filesystem::path(path_).stem().string();
    // A reflectance override uses no colour of the file: none is said to be clamped.
    std::vector<std::string> unused;
    materials_ = read_materials(scene, format, path_, gltf, obj, placement.reflectance ? unused : out.warnings);
    const double a = placement.rotate_x_deg * std::numbers::pi / 180.0;
    Eigen::Matrix3d rx;
    rx << 1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a);
    placement_linear_ = placement.scale * rx;
  }

  void node(const aiNode* n, const aiMatrix4x4& parent, int depth) {
    if (n == nullptr) return;
    if (depth > 1000) throw UserError(path_, "node tree deeper than 1000 levels");
    const aiMatrix4x4 m = parent * n->mTransformation;
    for (unsigned k = 0; k < n->mNumMeshes; ++k) {
      if (n->mMeshes[k] >= scene_.mNumMeshes || scene_.mMeshes[n->mMeshes[k]] == nullptr)
        throw UserError(path_, "node '" + std::string(n->mName.C_Str()) + "' refers to a missing mesh");
      mesh(*scene_.mMeshes[n->mMeshes[k]], m);
    }
    for (unsigned c = 0; c < n->mNumChildren; ++c) node(n->mChildren[c], m, depth + 1);
  }

  /// One warning for the faces whose mean vertex colour was clamped (a white PLY has them all;
  /// none under a reflectance override), and one for the polygons of 5 or more corners off their plane.
  void finish() {
    if (colours_clamped_ > 0 && !placement_.reflectance)
      out_.warnings.push_back(path_ + ": the " + (face_colours_ != nullptr ? "colour" : "mean vertex colour") + " of " +
                              std::to_string(colours_clamped_) + " face(s) clamped into [0, 0.999] (a reflectance must lie in [0, 1))");
    if (polygons_warped_ > 0)
      out_.warnings.push_back(path_ + ": " + std::to_string(polygons_warped_) + " polygon(s) of 5 or more corners not planar (up to " +
                              format_number(most_warped_) + " of their longest edge off their plane): cut into triangles through their corners");
  }

 private:
  void mesh(const aiMesh& mesh, const aiMatrix4x4& m) {
    std::string base = clean_name(mesh.mName.length > 0 ? std::string(mesh.mName.C_Str()) : stem_);
    const std::string first = base;
    for (int instance = 2; !bases_.insert(base).second; ++instance) base = first + "#" + std::to_string(instance);
    Eigen::Matrix3d node_linear;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) node_linear(r, c) = m[r][c];
    const Vec3 node_translate(m.a4, m.b4, m.c4);
    if (!node_linear.allFinite() || !node_translate.allFinite())
      throw UserError(path_, "mesh '" + base + "': its node transform is not finite");
    const Eigen::Matrix3d linear = placement_linear_ * node_linear;
    const Vec3 translate = placement_linear_ * (node_linear * file_offset_m_ + node_translate) + placement_.translate_m;
    const double det = linear.determinant();
    if (!(std::abs(det) > 0) || !std::isfinite(det)) throw UserError(path_, "mesh '" + base + "': its transform is singular");
    const bool mirrored = det < 0;  // a mirroring transform turns counter-clockwise corners clockwise

    if (mesh.mMaterialIndex >= materials_.size()) throw UserError(path_, "mesh '" + base + "' refers to a missing material");
    const Material& material = materials_[mesh.mMaterialIndex];
    const bool vertex_colours = format_ == Format::kPly && mesh.HasVertexColors(0);
    std::vector<Vec3> corners;
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      ++out_.faces_read;
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices < 3 || face.mIndices == nullptr) {
        ++out_.degenerate_skipped;
        continue;
      }
      corners.clear();
      Rgb colour_sum = Rgb::Zero();
      for (unsigned k = 0; k < face.mNumIndices; ++k) {
        const unsigned idx = face.mIndices[k];
        if (idx >= mesh.mNumVertices)
          throw UserError(path_, "mesh '" + base + "' face " + std::to_string(f) + ": vertex index " + std::to_string(idx) +
                                     " out of range (" + std::to_string(mesh.mNumVertices) + " vertices)");
        const aiVector3D& v = mesh.mVertices[idx];
        check_finite_vertex(v, path_, base, idx);
        const Vec3 p = linear * Vec3(v.x, v.y, v.z) + translate;
        if (!p.allFinite() || p.cwiseAbs().maxCoeff() > tol::kMaxCoordinate_m)
          throw UserError(path_, "mesh '" + base + "' vertex " + std::to_string(idx) + " (counted from 0, as in the mesh) lands at (" +
                                     format_number(p.x()) + ", " + format_number(p.y()) + ", " + format_number(p.z()) +
                                     ") m after placement, outside the +-" + format_number(tol::kMaxCoordinate_m) +
                                     " m of a scene");
        corners.push_back(p);
        if (vertex_colours && face_colours_ == nullptr) {
          const aiColor4D& c = mesh.mColors[0][idx];
          colour_sum += Rgb(c.r, c.g, c.b);
        }
      }
      if (mirrored) std::reverse(corners.begin(), corners.end());
      drop_repeated_corners(corners);
      if (corners.size() < 3) {
        ++out_.degenerate_skipped;
        continue;
      }
      Surface s;
      s.reflectance = material.reflectance;
      if (vertex_colours && face_colours_ == nullptr) {
        const Rgb mean = colour_sum / face.mNumIndices;
        if (!mean.allFinite()) throw UserError(path_, "mesh '" + base + "' face " + std::to_string(f) + ": vertex colours not finite");
        s.reflectance = mean.max(0.0).min(kMaxReflectance);
        colours_clamped_ += (s.reflectance != mean).any();
      }
      if (face_colours_ != nullptr) {  // a PLY face's own colour, before its vertices'
        const Rgb colour = (*face_colours_)[f];
        s.reflectance = colour.max(0.0).min(kMaxReflectance);
        colours_clamped_ += (s.reflectance != colour).any();
      }
      s.emission_w_m2 = material.emission_w_m2;
      if (placement_.reflectance) s.reflectance = *placement_.reflectance;
      if (placement_.emission_w_m2) s.emission_w_m2 = *placement_.emission_w_m2;
      s.two_sided = placement_.two_sided.value_or(false);
      s.max_divisions = placement_.max_divisions;
      const std::string name = base + ":" + std::to_string(f);
      if (corners.size() <= 4) {
        add(s, name, corners);
        continue;
      }
      const std::vector<std::array<int, 3>> triangles = triangulate_polygon(corners);
      if (triangles.empty()) {  // no area, or no ear to cut: a polygon that crosses itself
        ++(polygon_on_a_line(corners) ? out_.degenerate_skipped : out_.self_crossing_skipped);
        continue;
      }
      ++out_.polygons_triangulated;
      const double off_plane = polygon_off_plane(corners);
      if (off_plane > tol::kPlanarityRelative) {
        ++polygons_warped_;
        most_warped_ = std::max(most_warped_, off_plane);
      }
      for (size_t t = 0; t < triangles.size(); ++t) {
        const std::array<Vec3, 3> tri = {corners[triangles[t][0]], corners[triangles[t][1]], corners[triangles[t][2]]};
        add(s, name + ".t" + std::to_string(t), tri);
      }
    }
  }

  void add(Surface s, const std::string& name, std::span<const Vec3> corners) {
    if (degenerate(corners)) {
      ++out_.degenerate_skipped;
      return;
    }
    s.name = name;
    if (corners.size() == 3) {
      s.set_triangle(corners[0], corners[1], corners[2]);
    } else {
      s.corner_count = 4;
      std::copy(corners.begin(), corners.end(), s.corners.begin());
    }
    out_.surfaces.push_back(std::move(s));
  }

  const aiScene& scene_;
  Format format_;
  std::string path_, stem_;
  const MeshPlacement& placement_;
  Vec3 file_offset_m_;
  const std::vector<Rgb>* face_colours_ = nullptr;  ///< a PLY's, by face of its one mesh (CheckedPly)
  MeshImport& out_;
  std::vector<Material> materials_;
  Eigen::Matrix3d placement_linear_;
  std::set<std::string> bases_;  ///< the mesh names given so far
  size_t colours_clamped_ = 0;
  size_t polygons_warped_ = 0;  ///< polygons of 5+ corners off their plane
  double most_warped_ = 0;      ///< the largest distance off its plane, in units of its longest edge
};

}  // namespace

MeshImport import_mesh_assimp(const std::string& path, const MeshPlacement& placement) {
  const std::optional<Format> format = mesh_format(path);
  RR_CHECK(format.has_value(), "import_mesh() passes model files only");
  if (!(placement.scale > 0) || !std::isfinite(placement.scale)) throw UserError(path, "scale must be a finite number > 0");
  if (!std::isfinite(placement.rotate_x_deg) || !placement.translate_m.allFinite())
    throw UserError(path, "rotate_x_deg and translate must be finite");
  require_regular_file(path, "mesh file");
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw UserError(path, "cannot open mesh file: " + ec.message());
  if (size == 0) throw UserError(path, "empty mesh file");
  check_input_file_size(path);
  std::optional<CheckedPly> ply;  // assimp reads its canonical copy, not the file
  if (*format == Format::kPly) ply = check_ply(path);
  // glTF: its JSON first, for messages with a line or field, and for what assimp 5.2 drops.
  GltfExtras gltf;
  if (*format == Format::kGltf) gltf = read_gltf_extras(path);

  MeshImport out;
  ObjMaterials obj;
  ObjForAssimp obj_copy;  // what assimp reads of an OBJ
  if (*format == Format::kObj) {
    obj_copy = check_obj(path);
    obj = obj_materials(path);
    out.warnings = obj.warnings;
  }
  Assimp::Importer importer;
  if (*format == Format::kGltf) importer.SetIOHandler(new GltfIOSystem(path, gltf.assimp_copy));  // the importer owns it
  const aiScene* scene = nullptr;
  try {
    // No aiProcess_Triangulate: quads stay quads; larger polygons are cut here.
    const unsigned flags = aiProcess_JoinIdenticalVertices | aiProcess_ValidateDataStructure;
    if (ply) scene = importer.ReadFileFromMemory(ply->bytes.data(), ply->bytes.size(), flags, "ply");
    else if (*format == Format::kObj) scene = importer.ReadFileFromMemory(obj_copy.text.data(), obj_copy.text.size(), flags, "obj");
    else scene = importer.ReadFile(path, flags);
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    throw UserError(path, std::string("cannot be read: ") + e.what());
  } catch (...) {
    throw UserError(path, "cannot be read (the model library failed)");
  }
  if (scene == nullptr) throw UserError(path, std::string("cannot be read: ") + importer.GetErrorString());
  if (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) throw UserError(path, "incomplete model (no geometry was read)");
  if (scene->mRootNode == nullptr) throw UserError(path, "model has no node tree");
  size_t read = 0;
  for (unsigned i = 0; i < scene->mNumMeshes; ++i) read += scene->mMeshes[i] ? scene->mMeshes[i]->mNumFaces : 0;
  if (ply && read < ply->faces)
    throw UserError(path, "truncated: its header declares " + std::to_string(ply->faces) + " faces, " + std::to_string(read) + " were read");
  // assimp 5.2 drops a glTF face with a vertex index out of range, without a word.
  if (*format == Format::kGltf && read < gltf.faces)
    throw UserError(path, "vertex indices out of range: its primitives declare " + std::to_string(gltf.faces) + " faces, " +
                              std::to_string(gltf.faces - read) + " of them with an index past their vertices");
  // A PLY's face colours, by face: assimp makes one mesh of its faces, in order, unless a
  // material_index splits them.
  const std::vector<Rgb>* face_colours = nullptr;
  if (ply && !ply->face_colours.empty()) {
    if (scene->mNumMeshes == 1 && scene->mMeshes[0] != nullptr && scene->mMeshes[0]->mNumFaces == ply->face_colours.size())
      face_colours = &ply->face_colours;
    else if (!placement.reflectance)
      out.warnings.push_back(path + ": its face colours are not read: its faces are split among " + std::to_string(scene->mNumMeshes) +
                             " materials (their vertex colours, else 0.5 grey, are used)");
  }
  Builder builder(*scene, *format, path, gltf.materials, obj, placement, obj_copy.offset_m, face_colours, out);
  builder.node(scene->mRootNode, aiMatrix4x4(), 0);
  builder.finish();
  if (out.degenerate_skipped > 0)
    out.warnings.push_back(path + ": " + std::to_string(out.degenerate_skipped) +
                           " face(s) of fewer than 3 corners or of zero area skipped");
  if (out.self_crossing_skipped > 0)
    out.warnings.push_back(path + ": " + std::to_string(out.self_crossing_skipped) +
                           " polygon(s) of more than 4 corners that cross themselves skipped");
  if (out.surfaces.empty())
    throw UserError(path, "has no face of non-zero area that does not cross itself (" + std::to_string(out.faces_read) +
                              " faces read: " + std::to_string(out.degenerate_skipped) + " of zero area or fewer than 3 corners, " +
                              std::to_string(out.self_crossing_skipped) + " crossing themselves)");
  if (placement.merge_triangles) out.triangle_pairs_merged = merge_coplanar_triangle_pairs(out.surfaces);
  return out;
}

}  // namespace radrecon
