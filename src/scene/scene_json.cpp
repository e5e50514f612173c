// The JSON scene format (docs/formats.md):
//   {"name": ..., "surfaces": [{"name", "corners": [[x,y,z] x4], "reflectance": number|[r,g,b],
//     "emission": number|[r,g,b], "two_sided": bool, "mesh": {"max_divisions": int}}],
//    "cameras": [{"name", "eye", "target", "up", "fov_deg"}]}

#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "scene/scene.h"

namespace radrecon {

namespace {

using json = nlohmann::json;

class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw UserError(source_ + ": " + field, what);
  }

  const json& member(const json& obj, const std::string& key, const std::string& path) const {
    if (!obj.is_object()) fail(path, "must be an object");
    auto it = obj.find(key);
    if (it == obj.end()) fail(path.empty() ? key : path + "." + key, "missing");
    return *it;
  }

  double number(const json& j, const std::string& path) const {
    if (!j.is_number()) fail(path, "must be a number");
    double v = j.get<double>();
    if (!std::isfinite(v)) fail(path, "must be finite");
    return v;
  }

  std::string string(const json& j, const std::string& path) const {
    if (!j.is_string()) fail(path, "must be a string");
    return j.get<std::string>();
  }

  Vec3 vec3(const json& j, const std::string& path) const {
    if (!j.is_array() || j.size() != 3) fail(path, "must be an array of 3 numbers");
    return Vec3(number(j[0], path + "[0]"), number(j[1], path + "[1]"), number(j[2], path + "[2]"));
  }

  /// A grey number or an [r, g, b] triple.
  Rgb colour(const json& j, const std::string& path) const {
    if (j.is_number()) {
      double v = number(j, path);
      return Rgb(v, v, v);
    }
    if (!j.is_array() || j.size() != 3) fail(path, "must be a number or an array [r, g, b]");
    return Rgb(number(j[0], path + "[0]"), number(j[1], path + "[1]"), number(j[2], path + "[2]"));
  }

  void no_unknown_keys(const json& obj, std::initializer_list<const char*> known,
                       const std::string& path) const {
    for (auto it = obj.begin(); it != obj.end(); ++it) {
      bool ok = false;
      for (const char* k : known) ok = ok || it.key() == k;
      if (!ok) fail(path.empty() ? it.key() : path + "." + it.key(), "unknown field");
    }
  }

 private:
  std::string source_;
};

Surface read_surface(const Reader& r, const json& j, const std::string& path) {
  if (!j.is_object()) r.fail(path, "must be an object");
  r.no_unknown_keys(j, {"name", "corners", "reflectance", "emission", "two_sided", "mesh"}, path);
  Surface s;
  s.name = r.string(r.member(j, "name", path), path + ".name");
  const json& corners = r.member(j, "corners", path);
  if (!corners.is_array() || corners.size() != 4)
    r.fail(path + ".corners", "must be an array of 4 points [x, y, z]");
  for (int i = 0; i < 4; ++i)
    s.corners[i] = r.vec3(corners[i], path + ".corners[" + std::to_string(i) + "]");
  s.reflectance = r.colour(r.member(j, "reflectance", path), path + ".reflectance");
  if (j.contains("emission")) s.emission_w_m2 = r.colour(j["emission"], path + ".emission");
  if (j.contains("two_sided")) {
    if (!j["two_sided"].is_boolean()) r.fail(path + ".two_sided", "must be true or false");
    s.two_sided = j["two_sided"].get<bool>();
  }
  if (j.contains("mesh")) {
    const json& m = j["mesh"];
    if (!m.is_object()) r.fail(path + ".mesh", "must be an object");
    r.no_unknown_keys(m, {"max_divisions"}, path + ".mesh");
    if (m.contains("max_divisions")) {
      const json& d = m["max_divisions"];
      if (!d.is_number_integer() || d.get<long long>() < 1 || d.get<long long>() > 100000)
        r.fail(path + ".mesh.max_divisions", "must be an integer in [1, 100000]");
      s.max_divisions = d.get<int>();
    }
  }
  return s;
}

Camera read_camera(const Reader& r, const json& j, const std::string& path) {
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

}  // namespace

Scene parse_scene_json(const std::string& text, const std::string& source) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::out_of_range& e) {  // a number too large for a double, e.g. 1e999
    throw UserError(source, std::string("not a valid scene: ") + e.what());
  } catch (const json::parse_error& e) {
    // nlohmann reports a byte offset; turn it into a line number.
    size_t line = 1;
    for (size_t i = 0; i < std::min<size_t>(e.byte, text.size()); ++i) line += text[i] == '\n';
    throw UserError(source + ":" + std::to_string(line), std::string("not valid JSON: ") + e.what());
  }
  Reader r(source);
  if (!doc.is_object()) r.fail("(top level)", "must be a JSON object");
  r.no_unknown_keys(doc, {"name", "surfaces", "cameras"}, "");
  Scene scene;
  scene.name = doc.contains("name") ? r.string(doc["name"], "name") : std::string("unnamed");
  const json& surfaces = r.member(doc, "surfaces", "");
  if (!surfaces.is_array()) r.fail("surfaces", "must be an array");
  for (size_t i = 0; i < surfaces.size(); ++i)
    scene.surfaces.push_back(read_surface(r, surfaces[i], "surfaces[" + std::to_string(i) + "]"));
  if (doc.contains("cameras")) {
    const json& cameras = doc["cameras"];
    if (!cameras.is_array()) r.fail("cameras", "must be an array");
    for (size_t i = 0; i < cameras.size(); ++i)
      scene.cameras.push_back(read_camera(r, cameras[i], "cameras[" + std::to_string(i) + "]"));
  }
  validate_scene(scene, source);
  return scene;
}

Scene load_scene(const std::string& file_or_builtin) {
  if (file_or_builtin == "paper") return paper_scene();
  std::ifstream in(file_or_builtin, std::ios::binary);
  if (!in) throw UserError(file_or_builtin, "cannot open scene file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse_scene_json(buffer.str(), file_or_builtin);
}

}  // namespace radrecon
