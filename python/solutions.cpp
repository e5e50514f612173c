// Solutions for Python (python/solutions.h).

#include "solutions.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "arguments.h"
#include "core/error.h"
#include "core/limits.h"
#include "io/paths.h"
#include "io/scene_json.h"
#include "io/solution_json.h"
#include "reconstruct/methods.h"
#include "sampling/solution_reconstruction.h"
#include "solver/solve.h"

namespace py = pybind11;

namespace radrecon::python {

namespace {

/// A solution as Python holds it: with the files it was solved from (the scene and its model
/// files), which save() must not overwrite, as the command line refuses to.
struct PySolution : Solution {
  std::vector<std::string> inputs;
  /// Read from a file: its statistics as it has them (JSON text; "" for none), handed on as they
  /// are rather than through SolveStats, whose defaults (0 shots, converged) a file without them
  /// would seem to hold.
  std::optional<std::string> file_stats;
};

/// A surface side of a solution, its elements as arrays.
py::dict surface_dict(const SurfaceSolution& s) {
  const auto n = static_cast<py::ssize_t>(s.elements.size());
  py::array_t<double> center({n, py::ssize_t{3}}), radiosity({n, py::ssize_t{3}}), area(n), cell({n, py::ssize_t{4}});
  py::array_t<bool> triangle(n);
  auto c = center.mutable_unchecked<2>(), b = radiosity.mutable_unchecked<2>(), uv = cell.mutable_unchecked<2>();
  auto a = area.mutable_unchecked<1>();
  auto t = triangle.mutable_unchecked<1>();
  py::list shape;  // which half of its cell a triangle's element is, as the solution file names it
  for (py::ssize_t i = 0; i < n; ++i) {
    const SolutionElement& e = s.elements[static_cast<size_t>(i)];
    for (int k = 0; k < 3; ++k) c(i, k) = e.center[k], b(i, k) = e.radiosity_w_m2[k];
    a(i) = e.area_m2;
    uv(i, 0) = e.u0, uv(i, 1) = e.v0, uv(i, 2) = e.u1, uv(i, 3) = e.v1;
    t(i) = e.is_triangle();
    shape.append(cell_shape_name(e.shape));
  }
  // Polylines in the side's (s, t) metres, each a (k, 2) array.
  const auto polylines = [](const std::vector<Polyline>& lines) {
    py::list out;
    for (const Polyline& l : lines) {
      py::array_t<double> points({static_cast<py::ssize_t>(l.size()), py::ssize_t{2}});
      auto p = points.mutable_unchecked<2>();
      for (size_t k = 0; k < l.size(); ++k) p(static_cast<py::ssize_t>(k), 0) = l[k].x(), p(static_cast<py::ssize_t>(k), 1) = l[k].y();
      out.append(points);
    }
    return out;
  };
  py::dict d;
  d["name"] = s.name;
  d["scene_surface"] = s.scene_surface;
  d["back_side"] = s.back_side;
  d["grid"] = s.grid_nu > 0 ? py::object(py::make_tuple(s.grid_nu, s.grid_nv)) : py::object(py::none());
  d["center"] = center;
  d["radiosity"] = radiosity;
  d["area"] = area;
  d["cell"] = cell;
  d["triangle"] = triangle;
  d["shape"] = shape;
  d["length_u_m"] = s.length_u_m;
  d["length_v_m"] = s.length_v_m;
  d["shear_m"] = s.shear_m;
  d["barriers"] = polylines(s.barriers);
  d["excluded"] = polylines(s.excluded);
  d["outline"] = polylines({s.outline_st()})[0];
  py::array_t<double> st({n, py::ssize_t{2}});
  auto q = st.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < n; ++i) {
    const Vec2 c = s.centroid_st(s.elements[static_cast<size_t>(i)]);
    q(i, 0) = c.x(), q(i, 1) = c.y();
  }
  d["st"] = st;
  return d;
}

/// The domain of a side's rasters: its outline's bounding box in (s, t) metres.
Rect side_domain(const SurfaceSolution& side) {
  Rect r{0, 0, 0, 0};
  for (const Vec2& p : side.outline_st())
    r.x0 = std::min(r.x0, p.x()), r.y0 = std::min(r.y0, p.y()), r.x1 = std::max(r.x1, p.x()), r.y1 = std::max(r.y1, p.y());
  return r;
}

/// Solution.reconstruct(): one side reconstructed as `radrecon render` reconstructs it, at points
/// of its (s, t) frame or on a raster over its outline's bounding box; NaN off the side and in
/// its excluded regions.
py::array reconstruct(const PySolution& sol, const py::object& side_arg, const py::object& queries_arg,
                      const py::object& raster_arg, const py::object& method_arg, const py::object& barriers_arg,
                      const py::object& border_samples_arg, const py::kwargs& kwargs) {
  const std::string side_name = text_of(side_arg, "side", "a side's name (str: \"floor\", \"wall1/front\") is expected");
  const SurfaceSolution* side = sol.find(side_name);
  if (side == nullptr) {
    std::string names;
    for (size_t k = 0; k < std::min<size_t>(sol.surfaces.size(), 8); ++k) names += (k ? ", " : "") + sol.surfaces[k].name;
    if (sol.surfaces.size() > 8) names += ", ... (" + std::to_string(sol.surfaces.size()) + " in all)";
    throw UserError("side", "the solution has no side '" + side_name + "'; its sides: " + names);
  }
  if (!py::isinstance<py::str>(method_arg))
    throw UserError("method", "a method's name is expected (radrecon.methods() lists them), got " +
                                  py::repr(method_arg).cast<std::string>());
  const std::string method_text = method_arg.cast<std::string>();
  const Method method = method_by_name(method_text, "method");
  const bool barriers = flag_of(barriers_arg, "barriers"), border_samples = flag_of(border_samples_arg, "border_samples");
  if (const std::string problem = border_samples ? border_samples_problem(method) : ""; !problem.empty())
    throw UserError("border_samples", problem);
  const MethodParams params = parse_params(method, settings_of(kwargs), "params");
  if (barriers && !takes_barriers(method) && !side->barriers.empty()) {
    const std::string message = method_text + " takes no barriers: side '" + side_name +
                                "' is reconstructed across them (barriers=False asks for that)";
    if (PyErr_WarnEx(PyExc_UserWarning, message.c_str(), 1) != 0) throw py::error_already_set();
  }
  constexpr int kChannels = 3;  // a solution's radiosity: red, green, blue
  const std::optional<std::pair<int, int>> size = raster_of(raster_arg, kChannels);
  if (queries_arg.is_none() == !size.has_value())
    throw UserError("queries/raster", size ? "give either queries or raster, not both"
                                           : "give the query points: queries=(m, 2) array of (s, t) metres, or "
                                             "raster=(width, height)");
  std::optional<Raster> raster;
  std::vector<Vec2> at;
  std::vector<py::ssize_t> shape;
  if (size) {
    raster = Raster{size->first, size->second, side_domain(*side)};
    shape = {size->second, size->first, kChannels};
  } else {
    at = query_points(doubles_of(queries_arg, "queries"), kChannels);
    shape = {static_cast<py::ssize_t>(at.size()), kChannels};
    // A point outside the outline by rounding (on it, as contains_st() takes it) is asked on it:
    // a triangle's cells gave it no value (an outside-in trial).
    for (Vec2& p : at)
      if (side->contains_st(p)) p = side->onto_side_st(p);
  }
  py::array_t<double> out(shape);
  const std::span<double> values(out.mutable_data(), static_cast<size_t>(out.size()));
  WarningCollector warnings;  // the library's (a poorly conditioned system), raised as Python's below
  {
    py::gil_scoped_release release;
    // As render: a side the method cannot serve is drawn piecewise constant, with a warning unless
    // every element holds one value (a lamp of one leaf).
    std::optional<Fallback> fallback;
    const InterpolantResult f = reconstruct_side_or_constant(
        *side, method, params, SideSampling{.barriers = barriers, .border_samples = border_samples}, fallback);
    if (!f) throw UserError("side", "'" + side_name + "': " + f.reason());
    if (fallback && !fallback->exact)
      warn(method_text + " cannot reconstruct side '" + side_name + "' (" + fallback->reason +
           "); it is drawn piecewise constant, as render draws it");
    evaluate_all(*f.value(), raster, at, values);
    // Off the side (a triangle's raster corners, a query beyond its outline): no value.
    const size_t count = values.size() / kChannels;
    for (size_t k = 0; k < count; ++k) {
      const Vec2 p = raster ? raster->point(k % static_cast<size_t>(raster->width), k / static_cast<size_t>(raster->width)) : at[k];
      if (!side->contains_st(p))
        std::fill_n(values.begin() + static_cast<std::ptrdiff_t>(k * kChannels), kChannels, std::numeric_limits<double>::quiet_NaN());
    }
  }
  raise_warnings(warnings);
  return out;
}

py::dict stats_dict(const SolveStats& s) {
  auto rgb = [](const Rgb& c) { return py::make_tuple(c[0], c[1], c[2]); };
  py::dict d;
  d["method"] = s.method;
  d["shots"] = s.shots;
  d["patches"] = s.patches;
  d["elements"] = s.elements;
  if (s.method == "hierarchical") {  // as the file has them (io/solution_json.cpp)
    d["links"] = s.links;
    d["epsilon_w"] = s.epsilon_w;
  }
  d["emitted_w"] = rgb(s.emitted_w);
  d["absorbed_w"] = rgb(s.absorbed_w);
  d["unshot_w"] = rgb(s.unshot_w);
  d["escaped_w"] = rgb(s.escaped_w);
  d["residual"] = s.residual;
  d["converged"] = s.converged;
  d["seconds"] = s.seconds;
  return d;
}

}  // namespace

void bind_solutions(py::module_& m) {
  py::class_<PySolution>(m, "Solution", "A solved scene: its statistics and its surface sides' elements as arrays.")
      .def_property_readonly("scene", [](const PySolution& s) { return s.scene; })
      .def_property_readonly("mesh", [](const PySolution& s) { return s.mesh; })
      .def_property_readonly("stats", [](const PySolution& s) {
        if (!s.file_stats) return py::object(stats_dict(s.stats));
        if (s.file_stats->empty()) return py::object(py::dict());
        return py::module_::import("json").attr("loads")(*s.file_stats);
      })
      .def_property_readonly("surfaces", [](const PySolution& s) {
        py::list out;
        for (const SurfaceSolution& side : s.surfaces) out.append(surface_dict(side));
        return out;
      }, "Per side: name, scene_surface, back_side, grid ((nu, nv) or None), and per element center (n, 3) "
         "metres, radiosity (n, 3) W/m^2, area (n,) m^2, cell (n, 4) its (u0, v0, u1, v1), triangle (n,), shape "
         "(n names: box, lower or upper half of the cell); per side length_u_m, length_v_m, shear_m (its (s, t) "
         "frame), barriers and excluded (lists of (k, 2) polylines in (s, t) metres)")
      .def("reconstruct", &reconstruct, py::arg("side"), py::arg("queries") = py::none(), py::arg("raster") = py::none(),
           py::arg("method") = "natural-neighbour", py::arg("barriers") = py::bool_(true),
           py::arg("border_samples") = py::bool_(false),
           R"doc(Reconstruct one side's radiosity, as `radrecon render` does.

side: its name ("floor", "wall1/front"). Either queries: (m, 2) points of the side's (s, t) frame,
metres, giving (m, 3) W/m^2; or raster=(width, height) over the bounding box of its outline
(surfaces[i]["outline"]), giving (height, width, 3), row 0 at the lowest t. NaN off the side
and in its excluded regions. method: any of methods(); a side the method cannot serve (a grid
method on a triangle's side, too few samples) is drawn piecewise constant, as render draws it,
with a UserWarning.
barriers: honour the side's barriers (as render without --no-barriers); border_samples: as
render --border-samples. Further keywords are the method's parameters as in --param.
Raises radrecon.Error (a ValueError) for refused input.)doc")
      .def("save", [](const PySolution& s, const py::object& path_arg) {
        if (!is_path(path_arg))
          throw UserError("path", "expected a file name (str or os.PathLike), got " + py::repr(path_arg).cast<std::string>());
        const std::string path = path_of(path_arg, "path");
        check_output_file(path, "path");
        refuse_overwriting_inputs(path, "path", s.inputs);
        py::gil_scoped_release release;
        write_solution_json(path, s);
      }, py::arg("path"), "Write the solution JSON that `radrecon solve --out` writes.");

  m.def("load_solution", [](const py::object& path_arg) {
    if (!is_path(path_arg))
      throw UserError("path", "expected a file name (str or os.PathLike), got " + py::repr(path_arg).cast<std::string>());
    const std::string path = path_of(path_arg, "path");
    PySolution out;
    {
      py::gil_scoped_release release;
      std::string stats;
      static_cast<Solution&>(out) = read_solution_json(path, &stats);
      out.file_stats = std::move(stats);
    }
    out.inputs.push_back(std::filesystem::absolute(path).string());  // save() must not overwrite it
    return out;
  }, py::arg("path"), "Read a solution file written by `radrecon solve --out` (or Solution.save()) as a Solution.");

  m.def("solve", [](const py::object& scene_arg, const py::object& mesh_arg, const py::object& residual_arg,
                    const py::object& patches_arg, const py::object& leaves_on_arg, const py::object& clusters_arg,
                    const py::object& far_field_error_arg, const py::object& shadow_barriers_arg) {
    // Each argument converted here, so that a wrong type is refused naming it (pybind's own
    // TypeError named none).
    const std::string mesh = text_of(mesh_arg, "mesh", "grid:N, quadtree:LEAVES or quadtree-eps:E is expected");
    const std::optional<double> residual = optional_number(residual_arg, "residual");
    const std::optional<double> far_field_error = optional_number(far_field_error_arg, "far_field_error");
    const std::optional<double> patches_number = optional_number(patches_arg, "patches", true);
    const std::optional<long long> patches =
        patches_number ? std::optional<long long>(static_cast<long long>(std::clamp(*patches_number, -1e18, 1e18))) : std::nullopt;
    const std::optional<std::string> leaves_on =
        leaves_on_arg.is_none() ? std::nullopt : std::optional<std::string>(text_of(leaves_on_arg, "leaves_on", "a side's name (or None) is expected"));
    const std::optional<bool> clusters =
        clusters_arg.is_none() ? std::nullopt : std::optional<bool>(flag_of(clusters_arg, "clusters"));
    const bool shadow_barriers = flag_of(shadow_barriers_arg, "shadow_barriers");
    // A file by str or os.PathLike, or a built-in scene's name.
    if (!is_path(scene_arg))
      throw UserError("scene", "expected a file name (str or os.PathLike) or 'paper' or 'cornell', got " +
                                   py::repr(scene_arg).cast<std::string>());
    const std::string scene_spec = path_of(scene_arg, "scene");
    // As the command line: options the mesh does not use are refused, not ignored.
    std::vector<std::string> grid_only_given;
    if (residual) grid_only_given.emplace_back("residual");
    if (patches) grid_only_given.emplace_back("patches");
    if (far_field_error) grid_only_given.emplace_back("far_field_error");
    if (clusters) grid_only_given.emplace_back("clusters");
    refuse_unused_options(mesh, grid_only_given, leaves_on ? "leaves_on" : "");
    // Checked before the int it goes into, as a count from 1 as --patches takes it (the library's
    // 0 for its default is None here); the other settings by check_settings(), before the scene
    // is read (solve_scene() checks them again).
    if (patches && !(*patches >= 1 && *patches <= kMostPatches))
      throw UserError("patches", "must be a count from 1 to " + std::to_string(kMostPatches) + " (None: the default, " +
                                     std::to_string(default_patches()) + "), got " + std::to_string(*patches));
    SolveSettings settings;
    if (residual) settings.residual = *residual;
    if (far_field_error) settings.far_field_error = *far_field_error;
    if (patches) settings.patches = static_cast<int>(*patches);
    if (clusters) settings.clusters = *clusters;
    if (leaves_on) settings.leaves_on = *leaves_on;
    settings.shadow_barriers = shadow_barriers;
    check_settings(settings);
    PySolution out;
    WarningCollector warnings;  // the library's (a model's clamped colours, ...), raised as Python's below
    {
      py::gil_scoped_release release;
      const Scene scene = load_scene(scene_spec);
      static_cast<Solution&>(out) = solve_scene(scene, mesh, settings, "mesh");
      // Absolute: the working folder may change between solve() and save().
      for (const std::string& file : scene_input_files(scene_spec)) out.inputs.push_back(std::filesystem::absolute(file).string());
    }
    raise_warnings(warnings);
    return out;
  }, py::arg("scene") = py::str("paper"), py::arg("mesh") = "grid:16", py::arg("residual") = py::none(),
     py::arg("patches") = py::none(), py::arg("leaves_on") = py::none(), py::arg("clusters") = py::none(),
     py::arg("far_field_error") = py::none(), py::arg("shadow_barriers") = py::bool_(false),
     R"doc(Solve a scene's radiosity, as `radrecon solve` does.

scene: a scene JSON file, a mesh file (.obj, .gltf, .glb, .ply) with emitters (str or
os.PathLike), or 'paper' or 'cornell'. mesh: grid:N, quadtree:LEAVES or quadtree-eps:E. For grid:N only (refused with the
others, as on the command line): residual (default 1e-4); patches: shooting patches along the
longest edge (None: the default, 4); clusters (default True): a model's many small
triangles shoot in clusters (radrecon solve --clusters); far_field_error (default 0.02): the far
field's error bound, a fraction of each receiver's irradiance, 0 the distance rule. For
quadtree:LEAVES only: leaves_on, the side that gets the leaves. shadow_barriers: also the direct
light's umbra and penumbra lines among each side's barriers (--shadow-barriers). Returns a
Solution.)doc");
}

}  // namespace radrecon::python
