#include "solver/solution_io.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <cmath>
#include <memory>

#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"

namespace radrecon {

const SurfaceSolution* Solution::find(const std::string& name) const {
  for (const SurfaceSolution& s : surfaces)
    if (s.name == name) return &s;
  return nullptr;
}

namespace {

std::string json_string(const std::string& s) { return nlohmann::json(s).dump(); }

void put_rgb(std::FILE* f, const Rgb& c) { std::fprintf(f, "[%.9g, %.9g, %.9g]", c[0], c[1], c[2]); }

}  // namespace

void write_solution_json(const std::filesystem::path& path, const Solution& sol) {
  write_file_atomically(path, [&](const std::filesystem::path& tmp) {
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(tmp.c_str(), "wb"), &std::fclose);
    if (!file) throw UserError(path.string(), std::string("cannot open for writing: ") + std::strerror(errno));
    std::FILE* f = file.get();
    std::fprintf(f, "{\n  \"scene\": %s,\n  \"mesh\": %s,\n  \"surfaces\": [", json_string(sol.scene).c_str(),
                 json_string(sol.mesh).c_str());
    for (size_t s = 0; s < sol.surfaces.size(); ++s) {
      const SurfaceSolution& surf = sol.surfaces[s];
      std::fprintf(f, "%s\n    {\"name\": %s, \"scene_surface\": %s, \"back_side\": %s,\n", s ? "," : "",
                   json_string(surf.name).c_str(), json_string(surf.scene_surface).c_str(),
                   surf.back_side ? "true" : "false");
      std::fprintf(f, "     \"length_u_m\": %.17g, \"length_v_m\": %.17g, \"grid\": [%d, %d],\n     \"elements\": [",
                   surf.length_u_m, surf.length_v_m, surf.grid_nu, surf.grid_nv);
      for (size_t e = 0; e < surf.elements.size(); ++e) {
        const SolutionElement& el = surf.elements[e];
        std::fprintf(f, "%s\n      {\"u0\": %.17g, \"v0\": %.17g, \"u1\": %.17g, \"v1\": %.17g, \"center\": [%.9g, %.9g, %.9g], \"area\": %.9g, \"radiosity\": ",
                     e ? "," : "", el.u0, el.v0, el.u1, el.v1, el.center.x(), el.center.y(), el.center.z(),
                     el.area_m2);
        put_rgb(f, el.radiosity_w_m2);
        std::fputc('}', f);
      }
      std::fprintf(f, "\n    ]}");
    }
    const SolveStats& st = sol.stats;
    std::fprintf(f, "\n  ],\n  \"stats\": {\"method\": %s, \"shots\": %zu, \"elements\": %zu, \"patches\": %zu,\n",
                 json_string(st.method).c_str(), st.shots, st.elements, st.patches);
    if (st.method == "hierarchical")
      std::fprintf(f, "    \"links\": %zu, \"epsilon_w\": %.9g,\n", st.links, st.epsilon_w);
    std::fprintf(f, "    \"emitted_w\": ");
    put_rgb(f, st.emitted_w);
    std::fprintf(f, ", \"absorbed_w\": ");
    put_rgb(f, st.absorbed_w);
    std::fprintf(f, ", \"unshot_w\": ");
    put_rgb(f, st.unshot_w);
    std::fprintf(f, ", \"escaped_w\": ");
    put_rgb(f, st.escaped_w);
    std::fprintf(f, ",\n    \"residual\": %.9g, \"seconds\": %.6g}\n}\n", st.residual, st.seconds);
    if (std::ferror(f)) throw UserError(path.string(), "write failed");
    if (std::fclose(file.release()) != 0) throw UserError(path.string(), "write failed");
  });
}

namespace {

using json = nlohmann::json;

/// Typed access to a JSON document with errors that name the file and the field.
struct Fields {
  std::string file;
  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw UserError(file + ": " + field, what);
  }
  const json& get(const json& o, const char* key, const std::string& path) const {
    if (!o.is_object() || !o.contains(key)) fail(path + "." + key, "missing");
    return o[key];
  }
  double number(const json& j, const std::string& path) const {
    if (!j.is_number() || !std::isfinite(j.get<double>())) fail(path, "must be a finite number");
    return j.get<double>();
  }
  double number(const json& o, const char* key, const std::string& path) const {
    return number(get(o, key, path), path + "." + key);
  }
  std::string string(const json& o, const char* key, const std::string& path) const {
    const json& j = get(o, key, path);
    if (!j.is_string()) fail(path + "." + key, "must be a string");
    return j.get<std::string>();
  }
  Eigen::Array3d triple(const json& o, const char* key, const std::string& path) const {
    const json& j = get(o, key, path);
    if (!j.is_array() || j.size() != 3) fail(path + "." + key, "must be an array of 3 numbers");
    Eigen::Array3d v;
    for (int i = 0; i < 3; ++i) v[i] = number(j[static_cast<size_t>(i)], path + "." + key + "[" + std::to_string(i) + "]");
    return v;
  }
};

}  // namespace

Solution read_solution_json(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UserError(path.string(), "cannot open solution file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::out_of_range& e) {  // a number too large for a double, e.g. 1e999
    throw UserError(path.string(), std::string("not a valid solution: ") + e.what());
  } catch (const json::parse_error& e) {
    size_t line = 1;
    for (size_t i = 0; i < std::min<size_t>(e.byte, text.size()); ++i) line += text[i] == '\n';
    throw UserError(path.string() + ":" + std::to_string(line), std::string("not valid JSON: ") + e.what());
  }
  const Fields F{path.string()};
  if (!doc.is_object()) F.fail("(top level)", "must be a JSON object");
  Solution sol;
  if (doc.contains("scene")) sol.scene = F.string(doc, "scene", "");
  if (doc.contains("mesh")) sol.mesh = F.string(doc, "mesh", "");
  const json& surfaces = F.get(doc, "surfaces", "");
  if (!surfaces.is_array()) F.fail("surfaces", "must be an array");
  for (size_t s = 0; s < surfaces.size(); ++s) {
    const std::string sp = "surfaces[" + std::to_string(s) + "]";
    const json& js = surfaces[s];
    SurfaceSolution out;
    out.name = F.string(js, "name", sp);
    out.scene_surface = js.contains("scene_surface") ? F.string(js, "scene_surface", sp) : out.name;
    if (js.contains("back_side")) {
      if (!js["back_side"].is_boolean()) F.fail(sp + ".back_side", "must be true or false");
      out.back_side = js["back_side"].get<bool>();
    }
    out.length_u_m = F.number(js, "length_u_m", sp);
    out.length_v_m = F.number(js, "length_v_m", sp);
    if (!(out.length_u_m > 0 && out.length_v_m > 0)) F.fail(sp + ".length_u_m", "lengths must be positive");
    const json& elements = F.get(js, "elements", sp);
    if (!elements.is_array() || elements.empty()) F.fail(sp + ".elements", "must be a non-empty array");
    if (js.contains("grid")) {
      const json& g = js["grid"];
      if (!g.is_array() || g.size() != 2 || !g[0].is_number_integer() || !g[1].is_number_integer())
        F.fail(sp + ".grid", "must be [nu, nv]");
      const long long nu = g[0].get<long long>(), nv = g[1].get<long long>();
      const bool adaptive = nu == 0 && nv == 0;
      if (!adaptive && (nu < 1 || nv < 1 || static_cast<unsigned long long>(nu) * static_cast<unsigned long long>(nv) != elements.size()))
        F.fail(sp + ".grid", "must be [0, 0] or [nu, nv] with nu * nv = the number of elements");
      out.grid_nu = static_cast<int>(nu);
      out.grid_nv = static_cast<int>(nv);
    }
    out.elements.reserve(elements.size());
    for (size_t e = 0; e < elements.size(); ++e) {
      const std::string ep = sp + ".elements[" + std::to_string(e) + "]";
      const json& je = elements[e];
      SolutionElement el;
      el.u0 = F.number(je, "u0", ep);
      el.v0 = F.number(je, "v0", ep);
      el.u1 = F.number(je, "u1", ep);
      el.v1 = F.number(je, "v1", ep);
      if (!(0 <= el.u0 && el.u0 < el.u1 && el.u1 <= 1 && 0 <= el.v0 && el.v0 < el.v1 && el.v1 <= 1))
        F.fail(ep, "its (u,v) rectangle must satisfy 0 <= u0 < u1 <= 1 and 0 <= v0 < v1 <= 1");
      el.center = F.triple(je, "center", ep).matrix();
      el.area_m2 = F.number(je, "area", ep);
      el.radiosity_w_m2 = F.triple(je, "radiosity", ep);
      out.elements.push_back(el);
    }
    sol.surfaces.push_back(std::move(out));
  }
  return sol;
}

}  // namespace radrecon
