#include "io/scene_json.h"

#include <cstdio>

#include "io/json_reader.h"

namespace radrecon {

namespace {

using json = nlohmann::json;

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

}  // namespace

Scene parse_scene_json(const std::string& text, const std::string& source) {
  const JsonReader r(source);
  const json doc = r.parse(text, "scene");
  if (!doc.is_object()) r.fail("(top level)", "must be a JSON object");
  r.no_unknown_keys(doc, {"name", "surfaces", "cameras"}, "");
  Scene scene;
  scene.name = doc.contains("name") ? r.string(doc["name"], "name") : std::string("unnamed");
  const json& surfaces = r.member(doc, "surfaces", "");
  if (!surfaces.is_array()) r.fail("surfaces", "must be an array");
  for (size_t i = 0; i < surfaces.size(); ++i)
    scene.surfaces.push_back(read_surface(r, surfaces[i], JsonReader::at("surfaces", i)));
  if (doc.contains("cameras")) {
    const json& cameras = doc["cameras"];
    if (!cameras.is_array()) r.fail("cameras", "must be an array");
    for (size_t i = 0; i < cameras.size(); ++i)
      scene.cameras.push_back(read_camera(r, cameras[i], JsonReader::at("cameras", i)));
  }
  for (const std::string& warning : regularise_surfaces(scene, source))
    std::fprintf(stderr, "radrecon: warning: %s\n", warning.c_str());
  validate_scene(scene, source);
  return scene;
}

Scene load_scene(const std::string& file_or_builtin) {
  if (file_or_builtin == "paper") return paper_scene();
  if (file_or_builtin == "cornell") return cornell_scene();
  return parse_scene_json(read_text_file(file_or_builtin, "scene file"), file_or_builtin);
}

}  // namespace radrecon
