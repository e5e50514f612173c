#include "io/scene_json.h"

#include <cstdio>
#include <filesystem>
#include <optional>
#include <set>
#include <sstream>

#include "core/error.h"
#include "io/gltf_uri.h"
#include "io/json_reader.h"
#include "io/mesh_import.h"
#include "scene/default_camera.h"

namespace radrecon {

namespace {

using json = nlohmann::json;

/// A surface's or a mesh file's "mesh" settings: {"max_divisions": int in [1, 100000]}.
std::optional<int> read_mesh_settings(const JsonReader& r, const json& m, const std::string& path) {
  if (!m.is_object()) r.fail(path, "must be an object");
  r.no_unknown_keys(m, {"max_divisions"}, path);
  if (!m.contains("max_divisions")) return std::nullopt;
  const json& d = m["max_divisions"];
  if (!d.is_number_integer() || d.get<long long>() < 1 || d.get<long long>() > 100000)
    r.fail(path + ".max_divisions", "must be an integer in [1, 100000]");
  return d.get<int>();
}

Surface read_surface(const JsonReader& r, const json& j, const std::string& path) {
  if (!j.is_object()) r.fail(path, "must be an object");
  r.no_unknown_keys(j, {"name", "corners", "reflectance", "emission", "two_sided", "mesh"}, path);
  Surface s;
  s.name = r.string(r.member(j, "name", path), path + ".name");
  const json& corners = r.member(j, "corners", path);
  if (!corners.is_array() || (corners.size() != 3 && corners.size() != 4))
    r.fail(path + ".corners", "must be an array of 3 or 4 points [x, y, z] (a triangle or a quad)");
  for (size_t i = 0; i < corners.size(); ++i) s.corners[i] = r.vec3(corners[i], JsonReader::at(path + ".corners", i));
  if (corners.size() == 3) s.set_triangle(s.corners[0], s.corners[1], s.corners[2]);
  s.reflectance = r.colour(r.member(j, "reflectance", path), path + ".reflectance");
  if (j.contains("emission")) s.emission_w_m2 = r.colour(j["emission"], path + ".emission");
  if (j.contains("two_sided")) s.two_sided = r.boolean(j["two_sided"], path + ".two_sided");
  if (j.contains("mesh")) s.max_divisions = read_mesh_settings(r, j["mesh"], path + ".mesh");
  return s;
}

Camera read_camera(const JsonReader& r, const json& j, const std::string& path) {
  if (!j.is_object()) r.fail(path, "must be an object");
  r.no_unknown_keys(j, {"name", "eye", "target", "up", "fov_deg"}, path);
  Camera c;
  c.name = r.string(r.member(j, "name", path), path + ".name");
  c.eye = r.vec3(r.member(j, "eye", path), path + ".eye");
  c.target = r.vec3(r.member(j, "target", path), path + ".target");
  c.up = j.contains("up") ? r.vec3(j["up"], path + ".up") : Vec3(0, 0, 1);
  if (j.contains("fov_deg")) c.fov_deg = r.number(j["fov_deg"], path + ".fov_deg");
  return c;
}

/// One entry of "meshes": the model file's surfaces, placed and overridden as the entry says.
/// `base_dir`: the folder the file's path is relative to (the scene file's).
MeshImport read_mesh_entry(const JsonReader& r, const json& j, const std::string& path, const std::filesystem::path& base_dir) {
  if (!j.is_object()) r.fail(path, "must be an object");
  r.no_unknown_keys(j, {"file", "scale", "translate", "rotate_x_deg", "reflectance", "emission", "two_sided", "merge_triangles", "mesh"}, path);
  const std::string file = r.string(r.member(j, "file", path), path + ".file");
  if (file.empty()) r.fail(path + ".file", "must not be empty");
  MeshPlacement placement;
  if (j.contains("scale")) {
    placement.scale = r.number(j["scale"], path + ".scale");
    if (!(placement.scale > 0)) r.fail(path + ".scale", "must be a number > 0");
  }
  if (j.contains("translate")) placement.translate_m = r.vec3(j["translate"], path + ".translate");
  if (j.contains("rotate_x_deg")) placement.rotate_x_deg = r.number(j["rotate_x_deg"], path + ".rotate_x_deg");
  if (j.contains("reflectance")) {
    placement.reflectance = r.colour(j["reflectance"], path + ".reflectance");
    if (const std::string problem = reflectance_problem(*placement.reflectance); !problem.empty()) r.fail(path + ".reflectance", problem);
  }
  if (j.contains("emission")) {
    placement.emission_w_m2 = r.colour(j["emission"], path + ".emission");
    if (const std::string problem = emission_problem(*placement.emission_w_m2); !problem.empty()) r.fail(path + ".emission", problem);
  }
  if (j.contains("two_sided")) placement.two_sided = r.boolean(j["two_sided"], path + ".two_sided");
  if (j.contains("merge_triangles")) placement.merge_triangles = r.boolean(j["merge_triangles"], path + ".merge_triangles");
  if (j.contains("mesh")) placement.max_divisions = read_mesh_settings(r, j["mesh"], path + ".mesh");
  const std::filesystem::path file_path = std::filesystem::path(file).is_absolute() ? std::filesystem::path(file) : base_dir / file;
  try {
    return import_mesh(file_path.string(), placement);
  } catch (const UserError& e) {
    throw UserError(r.source() + ": " + path + ".file", e.what());
  }
}

/// Appends a model's surfaces to the scene, a name already taken getting "@K" (K: the index of
/// the "meshes" entry) so that the same file can be placed twice.
void add_mesh_surfaces(Scene& scene, std::vector<Surface> surfaces, size_t entry) {
  std::set<std::string> taken;
  for (const Surface& s : scene.surfaces) taken.insert(s.name);
  for (Surface& s : surfaces) {
    if (taken.count(s.name)) s.name.append("@").append(std::to_string(entry));
    taken.insert(s.name);
    scene.surfaces.push_back(std::move(s));
  }
}

}  // namespace

Scene parse_scene_json(const std::string& text, const std::string& source) {
  const JsonReader r(source);
  const json doc = r.parse(text, "scene");
  if (!doc.is_object()) r.fail("(top level)", "must be a JSON object");
  r.no_unknown_keys(doc, {"name", "surfaces", "meshes", "cameras"}, "");
  Scene scene;
  scene.name = doc.contains("name") ? r.string(doc["name"], "name") : std::string("unnamed");
  if (!doc.contains("meshes") || doc.contains("surfaces")) {
    const json& surfaces = r.member(doc, "surfaces", "");
    if (!surfaces.is_array()) r.fail("surfaces", "must be an array");
    for (size_t i = 0; i < surfaces.size(); ++i)
      scene.surfaces.push_back(read_surface(r, surfaces[i], JsonReader::at("surfaces", i)));
  }
  std::vector<std::string> mesh_warnings;
  if (doc.contains("meshes")) {
    const json& meshes = doc["meshes"];
    if (!meshes.is_array()) r.fail("meshes", "must be an array");
    const std::filesystem::path base_dir = std::filesystem::path(source).parent_path();
    for (size_t i = 0; i < meshes.size(); ++i) {
      MeshImport model = read_mesh_entry(r, meshes[i], JsonReader::at("meshes", i), base_dir);
      mesh_warnings.insert(mesh_warnings.end(), model.warnings.begin(), model.warnings.end());
      add_mesh_surfaces(scene, std::move(model.surfaces), i);
    }
  }
  if (doc.contains("cameras")) {
    const json& cameras = doc["cameras"];
    if (!cameras.is_array()) r.fail("cameras", "must be an array");
    for (size_t i = 0; i < cameras.size(); ++i)
      scene.cameras.push_back(read_camera(r, cameras[i], JsonReader::at("cameras", i)));
  }
  for (const std::string& warning : regularise_surfaces(scene, source)) mesh_warnings.push_back(warning);
  print_warnings(mesh_warnings, 20);
  validate_scene(scene, source);
  if (doc.contains("meshes") && scene.cameras.empty()) scene.cameras.push_back(default_camera(scene));
  return scene;
}

Scene load_mesh_scene(const std::string& path) {
  MeshImport model = import_mesh(path);
  Scene scene;
  scene.name = std::filesystem::path(path).stem().string();
  scene.surfaces = std::move(model.surfaces);
  bool emits = false;
  for (const Surface& s : scene.surfaces) emits = emits || (s.emission_w_m2 > 0).any();
  if (!emits) print_warnings(model.warnings, 20);  // they may say why: an MTL file not found
  if (!emits)
    throw UserError(path, std::string(lower_extension(path) == ".ply" ? "a PLY model has no emission (the format holds none)"
                                                                       : "the model has no emitting face (no OBJ Ke, no glTF emissiveFactor)") +
                              ": write a scene JSON "
                          "with \"meshes\": [{\"file\": \"" + std::filesystem::path(path).filename().string() +
                          "\"}] and a light in \"surfaces\" (docs/formats.md, Meshes)");
  for (const std::string& warning : regularise_surfaces(scene, path)) model.warnings.push_back(warning);
  print_warnings(model.warnings, 20);
  validate_scene(scene, path);
  scene.cameras.push_back(default_camera(scene));
  return scene;
}

Scene load_scene(const std::string& file_or_builtin) {
  if (file_or_builtin == "paper") return paper_scene();
  if (file_or_builtin == "cornell") return cornell_scene();
  if (is_mesh_file(file_or_builtin)) return load_mesh_scene(file_or_builtin);
  const std::string text = read_text_file(file_or_builtin, "scene file");
  // A file of another extension that is no JSON object (an .stl, .fbx, .dae model): said as
  // such, not as the JSON parser's complaint about its first byte.
  const size_t first = text.find_first_not_of(" \t\r\n");
  const bool object = first != std::string::npos && (text[first] == '{' || text.compare(first, 3, "\xEF\xBB\xBF") == 0);
  if (lower_extension(file_or_builtin) != ".json" && !object)
    throw UserError(file_or_builtin,
                    "not a scene: a scene is a JSON file (docs/formats.md) or a model file (.obj, .gltf, .glb or .ply; "
                    "docs/formats.md, \"Meshes\"), or 'paper' or 'cornell'");
  return parse_scene_json(text, file_or_builtin);
}

namespace {

/// The files a model file names that its reader opens too, resolved beside it: an OBJ's
/// "mtllib" files, a .gltf's buffers other than data URIs. Unreadable or malformed: none.
std::vector<std::string> model_companion_files(const std::filesystem::path& model) {
  std::vector<std::string> out;
  const std::string ext = lower_extension(model.string());
  if (ext != ".obj" && ext != ".gltf") return out;
  // Not a pipe or a device (a FIFO hung here, /dev/zero read 2 GB): the reader refuses those.
  std::error_code ec;
  if (!std::filesystem::is_regular_file(model, ec)) return out;
  std::string text;
  try {
    text = read_text_file(model.string(), "model file");
  } catch (const UserError&) {
    return out;
  }
  const std::filesystem::path dir = model.parent_path();
  if (ext == ".obj") {
    if (text.compare(0, 3, "\xEF\xBB\xBF") == 0) text.erase(0, 3);  // a UTF-8 byte order mark, as the reader skips it
    std::istringstream lines(text);
    std::string line;
    while (std::getline(lines, line)) {
      std::istringstream words(line);
      std::string keyword, name, all;
      if (!(words >> keyword) || keyword != "mtllib") continue;
      // Each name, and all of them as one (a name with spaces): refusing one too many is harmless.
      while (words >> name) {
        out.push_back((dir / name).string());
        all += (all.empty() ? "" : " ") + name;
      }
      if (all.find(' ') != std::string::npos) out.push_back((dir / all).string());
    }
    return out;
  }
  const nlohmann::json gltf = nlohmann::json::parse(text, nullptr, false);
  if (!gltf.is_object() || !gltf.contains("buffers") || !gltf["buffers"].is_array()) return out;
  for (const auto& buffer : gltf["buffers"])
    if (buffer.is_object() && buffer.contains("uri") && buffer["uri"].is_string()) {
      const std::string uri = buffer["uri"].get<std::string>();
      // The file the reader opens (percent-decoded: "my%20model.bin" is "my model.bin"), and the
      // name as written: refusing one too many is harmless.
      if (!uri.empty() && uri.rfind("data:", 0) != 0) {
        out.push_back(gltf_uri_file(dir.string(), uri));
        out.push_back((dir / uri).string());
      }
    }
  return out;
}

}  // namespace

std::vector<std::string> scene_input_files(const std::string& file_or_builtin) {
  if (is_builtin_scene(file_or_builtin)) return {};
  std::vector<std::string> out = {file_or_builtin};
  std::vector<std::filesystem::path> models;
  if (is_mesh_file(file_or_builtin)) {
    models.emplace_back(file_or_builtin);
  } else {
    // A scene from a pipe is read once, by load_scene(): its meshes are not looked for here.
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file_or_builtin, ec)) return out;
    std::string text;
    try {
      text = read_text_file(file_or_builtin, "scene file");
    } catch (const UserError&) {
      return out;
    }
    const nlohmann::json scene = nlohmann::json::parse(text, nullptr, false);
    if (scene.is_object() && scene.contains("meshes") && scene["meshes"].is_array()) {
      const std::filesystem::path base = std::filesystem::path(file_or_builtin).parent_path();
      for (const auto& entry : scene["meshes"])
        if (entry.is_object() && entry.contains("file") && entry["file"].is_string()) {
          const std::filesystem::path file(entry["file"].get<std::string>());
          models.push_back(file.is_absolute() ? file : base / file);
        }
    }
  }
  for (const std::filesystem::path& model : models) {
    if (model.string() != file_or_builtin) out.push_back(model.string());
    for (std::string& companion : model_companion_files(model)) out.push_back(std::move(companion));
  }
  return out;
}

bool is_builtin_scene(const std::string& name) { return name == "paper" || name == "cornell"; }

}  // namespace radrecon
