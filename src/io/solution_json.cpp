#include "io/solution_json.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string>
#include <system_error>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/check.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/parse.h"
#include "core/tolerances.h"
#include "io/atomic_file.h"
#include "io/json_reader.h"

namespace radrecon {

namespace {

std::string json_string(const std::string& s) { return nlohmann::json(s).dump(); }

/// v as printf's "%.{precision}g" would write it, appended to out.
void append_g(std::string& out, double v, int precision) {
  char buf[32];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, precision);
  RR_CHECK(ec == std::errc(), "a number does not fit its buffer");  // %.17g takes at most 24 characters
  out.append(buf, end);
}

/// The elements' text is made in chunks of this many elements (some 200 bytes each), this many
/// chunks at a time, side by side (core/parallel.h), and written in order.
constexpr size_t kChunkElements = 1024, kChunksAtOnce = 16;

/// One element's JSON object, after a comma and a new line (or only a new line for the first),
/// its numbers by std::to_chars: the same text as printf's %.17g and %.9g, several times faster.
void append_element(std::string& text, const SolutionElement& el, bool first) {
  text += first ? "\n      {\"u0\": " : ",\n      {\"u0\": ";
  append_g(text, el.u0, 17);
  text += ", \"v0\": ";
  append_g(text, el.v0, 17);
  text += ", \"u1\": ";
  append_g(text, el.u1, 17);
  text += ", \"v1\": ";
  append_g(text, el.v1, 17);
  text += ", ";
  if (el.is_triangle()) text.append("\"shape\": \"").append(cell_shape_name(el.shape)).append("\", ");
  text += "\"center\": [";
  append_g(text, el.center.x(), 9);
  text += ", ";
  append_g(text, el.center.y(), 9);
  text += ", ";
  append_g(text, el.center.z(), 9);
  text += "], \"area\": ";
  append_g(text, el.area_m2, 9);
  text += ", \"radiosity\": [";
  for (int c = 0; c < 3; ++c) {
    if (c) text += ", ";
    append_g(text, el.radiosity_w_m2[c], 9);
  }
  text += "]}";
}

void put_rgb(OutputFile& f, const Rgb& c) { f.print("[%.9g, %.9g, %.9g]", c[0], c[1], c[2]); }

/// Polylines as [[s, t], ...], comma-separated, full precision (the enclosing brackets are the
/// caller's).
void put_polylines(OutputFile& f, const std::vector<Polyline>& lines) {
  for (size_t k = 0; k < lines.size(); ++k) {
    f.print("%s[", k ? ", " : "");
    for (size_t i = 0; i < lines[k].size(); ++i)
      f.print("%s[%.17g, %.17g]", i ? ", " : "", lines[k][i].x(), lines[k][i].y());
    f.write("]");
  }
}

}  // namespace

void write_solution_json(const std::filesystem::path& path, const Solution& sol) {
  write_file_atomically(path, [&](const std::filesystem::path& tmp) {
    OutputFile f(tmp, path.string());
    f.print("{\n  \"scene\": %s,\n  \"mesh\": %s,\n  \"surfaces\": [", json_string(sol.scene).c_str(),
                 json_string(sol.mesh).c_str());
    for (size_t s = 0; s < sol.surfaces.size(); ++s) {
      const SurfaceSolution& surf = sol.surfaces[s];
      f.print("%s\n    {\"name\": %s, \"scene_surface\": %s, \"back_side\": %s,\n", s ? "," : "",
                   json_string(surf.name).c_str(), json_string(surf.scene_surface).c_str(),
                   surf.back_side ? "true" : "false");
      f.print("     \"length_u_m\": %.17g, \"length_v_m\": %.17g, \"grid\": [%d, %d],\n", surf.length_u_m,
                   surf.length_v_m, surf.grid_nu, surf.grid_nv);
      if (surf.triangle) f.print("     \"triangle\": true, \"shear_m\": %.17g,\n", surf.shear_m);
      f.print("     \"barriers\": [");
      put_polylines(f, surf.barriers);
      f.print("],\n     \"excluded\": [");
      put_polylines(f, surf.excluded);
      f.print("],\n     \"elements\": [");
      // The elements (most of the file): their text made side by side, a run of chunks at a
      // time, and written in order (the same text whatever the threads).
      const size_t count = surf.elements.size();
      std::vector<std::string> chunks(kChunksAtOnce);
      for (size_t first = 0; first < count; first += kChunksAtOnce * kChunkElements) {
        const size_t chunks_now = std::min(kChunksAtOnce, (count - first + kChunkElements - 1) / kChunkElements);
        parallel_for_coarse(0, static_cast<std::int64_t>(chunks_now), [&](std::int64_t c) {
          std::string& text = chunks[static_cast<size_t>(c)];
          text.clear();
          const size_t lo = first + static_cast<size_t>(c) * kChunkElements, hi = std::min(count, lo + kChunkElements);
          for (size_t e = lo; e < hi; ++e) append_element(text, surf.elements[e], e == 0);
        });
        for (size_t c = 0; c < chunks_now; ++c)
          f.write(chunks[c]);
      }
      f.print("\n    ]}");
    }
    const SolveStats& st = sol.stats;
    f.print("\n  ],\n  \"stats\": {\"method\": %s, \"shots\": %zu, \"elements\": %zu, \"patches\": %zu,\n",
                 json_string(st.method).c_str(), st.shots, st.elements, st.patches);
    if (st.method == "hierarchical")
      f.print("    \"links\": %zu, \"epsilon_w\": %.9g,\n", st.links, st.epsilon_w);
    f.print("    \"emitted_w\": ");
    put_rgb(f, st.emitted_w);
    f.print(", \"absorbed_w\": ");
    put_rgb(f, st.absorbed_w);
    f.print(", \"unshot_w\": ");
    put_rgb(f, st.unshot_w);
    f.print(", \"escaped_w\": ");
    put_rgb(f, st.escaped_w);
    f.print(",\n    \"residual\": %.9g, \"converged\": %s, \"seconds\": %.6g}\n}\n", st.residual,
                 st.converged ? "true" : "false", st.seconds);
    f.close();
  });
}

namespace {

using json = nlohmann::json;

double positive_or_fail(const JsonReader& r, double v, const std::string& path) {
  if (!(v > 0)) r.fail(path, "must be positive");
  return v;
}

/// An array of polylines [[[s, t], ...], ...] of at least `min_points` finite points each (a
/// `what`: "polyline" or "polygon"), or a refusal naming the offending element's path.
std::vector<Polyline> polylines(const JsonReader& r, const json& j, const std::string& path, size_t min_points,
                                const std::string& what) {
  if (!j.is_array()) r.fail(path, "must be an array of " + what + "s [[s, t], ...]");
  std::vector<Polyline> out;
  for (size_t b = 0; b < j.size(); ++b) {
    const std::string lp = JsonReader::at(path, b);
    if (!j[b].is_array() || j[b].size() < min_points)
      r.fail(lp, "must be a " + what + " of at least " + std::to_string(min_points) + " points [s, t]");
    Polyline line;
    for (size_t i = 0; i < j[b].size(); ++i) {
      const std::string pp = JsonReader::at(lp, i);
      const json& pt = j[b][i];
      if (!pt.is_array() || pt.size() != 2) r.fail(pp, "must be a point [s, t]");
      line.emplace_back(r.number(pt[0], JsonReader::at(pp, 0)), r.number(pt[1], JsonReader::at(pp, 1)));
      // A barrier's segment of no length blocks nothing and fails every reconstruction of the
      // side (each fell back to piecewise constant with a warning): refused where it is.
      if (i > 0 && line[i] == line[i - 1]) r.fail(pp, "repeats the point before it (a segment of zero length)");
    }
    out.push_back(std::move(line));
  }
  return out;
}

}  // namespace

Solution read_solution_json(const std::filesystem::path& path, std::string* stats_json) {
  const std::string text = read_text_file(path.string(), "solution file");
  const JsonReader r(path.string());
  // Written by radrecon (tens of MB for a fine mesh), whose writer gives each key once: not
  // searched for repeated keys, which would cost half again the parse.
  const json doc = r.parse(text, "solution", JsonReader::Keys::as_parsed);
  if (!doc.is_object()) r.fail("(top level)", "must be a JSON object");
  Solution sol;
  if (doc.contains("scene")) sol.scene = r.string(doc["scene"], "scene");
  if (doc.contains("mesh")) sol.mesh = r.string(doc["mesh"], "mesh");
  const json& surfaces = r.member(doc, "surfaces", "");
  // A solution holds at least one side: one of none has nothing to render, export or compare.
  if (!surfaces.is_array() || surfaces.empty()) r.fail("surfaces", "must be a non-empty array (a solution holds its surface sides)");
  for (size_t s = 0; s < surfaces.size(); ++s) {
    const std::string sp = JsonReader::at("surfaces", s);
    const json& js = surfaces[s];
    SurfaceSolution out;
    out.name = r.string(r.member(js, "name", sp), sp + ".name");
    if (sol.find(out.name)) r.fail(sp + ".name", "duplicate surface side '" + out.name + "'");
    out.scene_surface = js.contains("scene_surface") ? r.string(js["scene_surface"], sp + ".scene_surface") : out.name;
    if (js.contains("back_side")) out.back_side = r.boolean(js["back_side"], sp + ".back_side");
    out.length_u_m = positive_or_fail(r, r.number(r.member(js, "length_u_m", sp), sp + ".length_u_m"), sp + ".length_u_m");
    out.length_v_m = positive_or_fail(r, r.number(r.member(js, "length_v_m", sp), sp + ".length_v_m"), sp + ".length_v_m");
    // Both optional: a quad's side has neither.
    if (js.contains("triangle")) out.triangle = r.boolean(js["triangle"], sp + ".triangle");
    if (js.contains("shear_m")) {
      out.shear_m = r.number(js["shear_m"], sp + ".shear_m");
      if (!std::isfinite(out.shear_m) || !out.triangle) r.fail(sp + ".shear_m", "must be a finite number, on a triangle's side only");
    }
    const json& elements = r.member(js, "elements", sp);
    if (!elements.is_array() || elements.empty()) r.fail(sp + ".elements", "must be a non-empty array");
    if (js.contains("grid")) {
      const json& g = js["grid"];
      if (!g.is_array() || g.size() != 2 || !g[0].is_number_integer() || !g[1].is_number_integer())
        r.fail(sp + ".grid", "must be [nu, nv]");
      const long long nu = g[0].get<long long>(), nv = g[1].get<long long>();
      const bool adaptive = nu == 0 && nv == 0;
      if (!adaptive && (nu < 1 || nv < 1 || nu > 1'000'000 || nv > 1'000'000 ||
                        static_cast<unsigned long long>(nu) * static_cast<unsigned long long>(nv) != elements.size()))
        r.fail(sp + ".grid", "must be [0, 0] or [nu, nv] with nu * nv = the number of elements");
      if (out.triangle && !adaptive) r.fail(sp + ".grid", "must be [0, 0] on a triangle's side (its elements are no grid of boxes)");
      out.grid_nu = static_cast<int>(nu);
      out.grid_nv = static_cast<int>(nv);
    }
    // Both optional: files of earlier versions lack them.
    if (js.contains("barriers")) out.barriers = polylines(r, js["barriers"], sp + ".barriers", 2, "polyline");
    if (js.contains("excluded")) out.excluded = polylines(r, js["excluded"], sp + ".excluded", 3, "polygon");
    out.elements.reserve(elements.size());
    for (size_t e = 0; e < elements.size(); ++e) {
      const std::string ep = JsonReader::at(sp + ".elements", e);
      const json& je = elements[e];
      const auto num = [&](const char* key) { return r.number(r.member(je, key, ep), ep + "." + key); };
      SolutionElement el;
      el.u0 = num("u0");
      el.v0 = num("v0");
      el.u1 = num("u1");
      el.v1 = num("v1");
      if (!(0 <= el.u0 && el.u0 < el.u1 && el.u1 <= 1 && 0 <= el.v0 && el.v0 < el.v1 && el.v1 <= 1))
        r.fail(ep, "its (u,v) rectangle must satisfy 0 <= u0 < u1 <= 1 and 0 <= v0 < v1 <= 1");
      if (je.contains("shape")) {
        const std::optional<CellShape> shape = parse_cell_shape(r.string(je["shape"], ep + ".shape"));
        if (!shape) r.fail(ep + ".shape", "must be \"box\", \"lower\" or \"upper\"");
        el.shape = *shape;
      }
      if (el.is_triangle() != out.triangle)
        r.fail(ep + ".shape", out.triangle ? "must be \"lower\" or \"upper\" on a triangle's side" : "must be \"box\" on a quad's side");
      // A triangle's cells lie in its domain u + v <= 1: the vertex farthest along u + v.
      const double far = el.shape == CellShape::upper ? el.u1 + el.v1 : std::max(el.u1 + el.v0, el.u0 + el.v1);
      if (out.triangle && far > 1 + tol::kSolutionGridParameter)
        r.fail(ep, "its (u,v) cell reaches beyond the triangle's parameter domain u + v <= 1");
      if (out.grid_nu > 0) {  // a regular grid stores element (i, j) at index j * nu + i
        const size_t i = e % static_cast<size_t>(out.grid_nu), j = e / static_cast<size_t>(out.grid_nu);
        const double u0 = double(i) / out.grid_nu, v0 = double(j) / out.grid_nv;
        if (std::abs(el.u0 - u0) > tol::kSolutionGridParameter || std::abs(el.v0 - v0) > tol::kSolutionGridParameter)
          r.fail(ep, "a grid [" + std::to_string(out.grid_nu) + ", " + std::to_string(out.grid_nv) + "] stores element (" +
                         std::to_string(i) + ", " + std::to_string(j) + ") here, at (u0, v0) = (" + format_number(u0) +
                         ", " + format_number(v0) + "); this element is elsewhere");
      }
      el.center = r.vec3(r.member(je, "center", ep), ep + ".center");
      el.area_m2 = num("area");
      el.radiosity_w_m2 = r.vec3(r.member(je, "radiosity", ep), ep + ".radiosity").array();
      // Reconstructions take these as samples (io/samples_csv.h's bound: beyond it their sums and
      // gradients overflow); a solve's own stay far below (emission at most 1e12 W/m^2).
      if ((el.radiosity_w_m2.abs() > tol::kMaxSampleValue).any())
        r.fail(ep + ".radiosity", "beyond the largest value, " + format_number(tol::kMaxSampleValue));
      // Radiosity is emitted plus reflected power per area: never negative (a solve's is >= 0).
      if ((el.radiosity_w_m2 < 0).any()) r.fail(ep + ".radiosity", "must not be negative (W/m^2)");
      out.elements.push_back(el);
    }
    sol.surfaces.push_back(std::move(out));
  }
  if (stats_json != nullptr) *stats_json = doc.contains("stats") ? doc["stats"].dump() : std::string();
  return sol;
}

}  // namespace radrecon
