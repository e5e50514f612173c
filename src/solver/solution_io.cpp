#include "solver/solution_io.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
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

}  // namespace radrecon
