// radrecon for Python (pybind11, NumPy): scattered-data interpolation by every reconstruction
// method of `radrecon interpolate`, the radiosity solvers of `radrecon solve`, and solutions
// (solved or read from their files) reconstructed side by side as `radrecon render` does, on arrays.
// The work runs without the GIL; refused input raises radrecon.Error (a ValueError) with the
// message the command line prints. docs/python.md.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "arguments.h"
#include "solutions.h"
#include "core/error.h"
#include "core/parse.h"
#include "core/tolerances.h"
#include "io/geojson.h"
#include "reconstruct/methods.h"
#include "reconstruct/sample_set.h"

namespace py = pybind11;

namespace radrecon {
namespace {

using namespace python;  // the arguments' conversions (arguments.h)

py::array interpolate(const py::object& points_arg, const py::object& values_arg, const py::object& queries_arg,
                      const py::object& raster_arg, const py::object& domain_arg, const py::object& method_arg,
                      const py::object& barriers, const py::object& border_samples_arg, const py::kwargs& kwargs) {
  const bool border_samples = flag_of(border_samples_arg, "border_samples");
  const Doubles points = doubles_of(points_arg, "points"), values = doubles_of(values_arg, "values");
  const std::optional<Doubles> queries =
      queries_arg.is_none() ? std::nullopt : std::optional<Doubles>(doubles_of(queries_arg, "queries"));
  if (!py::isinstance<py::str>(method_arg))
    throw UserError("method", "a method's name is expected (radrecon.methods() lists them), got " +
                                  py::repr(method_arg).cast<std::string>());
  const std::string method_text = method_arg.cast<std::string>();
  std::optional<std::array<double, 4>> domain;
  if (!domain_arg.is_none()) {
    const std::vector<double> d = numbers_of(domain_arg, 4, false, "domain", "(x0, y0, x1, y1), four numbers, is expected");
    domain = std::array<double, 4>{d[0], d[1], d[2], d[3]};
  }
  check_points(points, "points");
  const auto n = static_cast<size_t>(points.shape(0));
  if (values.ndim() < 1 || values.ndim() > 2 || static_cast<size_t>(values.shape(0)) != n)
    throw UserError("values", "an array of shape (" + std::to_string(n) + ",) or (" + std::to_string(n) +
                                  ", channels) is expected, one row per point; got shape " + shape_of(values));
  const int channels = values.ndim() == 2 ? static_cast<int>(values.shape(1)) : 1;
  if (channels < 1) throw UserError("values", "no value columns");
  const std::optional<std::pair<int, int>> raster = raster_of(raster_arg, channels);
  for (py::ssize_t i = 0; i < values.size(); ++i) {
    const double v = values.data()[i];
    if (!std::isfinite(v)) throw UserError("values[" + std::to_string(i / channels) + "]", "not a finite number");
    if (std::abs(v) > tol::kMaxSampleValue)
      throw UserError("values[" + std::to_string(i / channels) + "]",
                      format_number(v) + " is beyond the largest value, " + format_number(tol::kMaxSampleValue));
  }
  if (queries.has_value() == raster.has_value())
    throw UserError("queries/raster", queries ? "give either queries or raster, not both"
                                              : "give the query points: queries=(m, 2) array, or raster=(width, height) with "
                                                "domain=(x0, y0, x1, y1)");
  if (raster && !domain) throw UserError("domain", "raster needs domain=(x0, y0, x1, y1), the rectangle it covers");
  if (domain && !raster && !border_samples)
    throw UserError("domain", "domain goes with raster (or with border_samples: the border they go on)");
  if (domain) {
    const auto& d = *domain;
    const auto within = [](double v) { return std::abs(v) <= tol::kMaxSampleCoordinate; };  // false for NaN
    if (!(within(d[0]) && within(d[1]) && within(d[2]) && within(d[3]) && d[2] > d[0] && d[3] > d[1]))
      throw UserError("domain", "(x0, y0, x1, y1) with x1 > x0 and y1 > y0, each of magnitude at most " +
                                    format_number(tol::kMaxSampleCoordinate) + ", is expected");
  }
  const Method method = method_by_name(method_text, "method", [](Method m) { return point_method_problem(m).empty(); });
  if (const std::string problem = point_method_problem(method); !problem.empty()) throw UserError("method", problem);
  MethodParams params = parse_params(method, settings_of(kwargs), "params");
  params.barriers = barriers_of(barriers);
  if (const std::string problem = params.barriers.empty() ? "" : barriers_problem(method); !problem.empty())
    throw UserError("barriers", problem);

  ScatteredSamples samples;
  samples.channels = channels;
  samples.points.resize(n);
  for (size_t i = 0; i < n; ++i) samples.points[i] = Vec2(points.data()[2 * i], points.data()[2 * i + 1]);
  samples.values.assign(values.data(), values.data() + values.size());
  WarningCollector warnings;  // the library's warnings, raised as Python's below
  size_t removed = 0;
  {
    py::gil_scoped_release release;  // a million samples with barriers take a while
    const Result<size_t> merged = merge_duplicate_points(samples, params.barriers, "points");
    if (!merged) throw UserError("points", merged.reason());
    removed = merged.value();
  }
  if (removed > 0 &&
      PyErr_WarnEx(PyExc_UserWarning, merged_samples_message(removed, n, samples.points.size()).c_str(), 1) != 0)
    throw py::error_already_set();  // warnings turned into errors

  Raster grid;
  std::vector<Vec2> at;
  std::vector<py::ssize_t> shape;
  if (raster) {
    const auto [w, h] = *raster;
    const auto& d = *domain;  // checked above
    grid.width = w;
    grid.height = h;
    grid.domain = Rect{d[0], d[1], d[2], d[3]};
    shape = {h, w};
  } else {
    at = query_points(*queries, samples.channels);
    shape = {static_cast<py::ssize_t>(at.size())};
  }
  if (raster && !border_samples) warn_if_domain_apart(grid.domain, samples);  // raised with the others below
  // The border's rectangle holds the domain (checked above) and every sample (as --border-samples).
  std::optional<Rect> border_domain;
  if (domain) border_domain = Rect{(*domain)[0], (*domain)[1], (*domain)[2], (*domain)[3]};
  if (values.ndim() == 2) shape.push_back(channels);
  py::array_t<double> out(shape);
  double* result = out.mutable_data();
  const size_t count = raster ? static_cast<size_t>(grid.width) * grid.height : at.size();
  {
    py::gil_scoped_release release;
    size_t added_samples = 0;
    if (border_samples) {
      const Result<size_t> added = add_border_samples(method, samples, border_domain, params);
      if (!added) throw UserError("border_samples", added.reason());
      added_samples = added.value();
    }
    const InterpolantResult interpolant = make_point_interpolant(method, samples, params);
    if (!interpolant) throw UserError("points", reason_with_border_samples(interpolant.reason(), added_samples));
    evaluate_all(*interpolant.value(), raster ? std::optional<Raster>(grid) : std::nullopt, at,
                 std::span<double>(result, count * static_cast<size_t>(channels)));
  }
  raise_warnings(warnings);
  return out;
}

}  // namespace
}  // namespace radrecon

PYBIND11_MODULE(radrecon, m) {
  using namespace radrecon;
  m.doc() = "radrecon: radiosity solvers and scattered-data reconstruction (docs/python.md)";
  m.attr("__version__") = RADRECON_VERSION;
  py::register_exception<UserError>(m, "Error", PyExc_ValueError);

  m.def("methods", [] {
    std::vector<std::string> names;
    for (Method method : all_methods()) names.push_back(method_name(method));
    return names;
  }, "The reconstruction methods' names, as --method takes them; interpolate()'s method= takes all but 'gouraud' (it draws cells: render and paper).");

  m.def("interpolate", &interpolate, py::arg("points"), py::arg("values"), py::arg("queries") = py::none(),
        py::arg("raster") = py::none(), py::arg("domain") = py::none(), py::arg("method") = "natural-neighbour",
        py::arg("barriers") = py::none(), py::arg("border_samples") = py::bool_(false),
        R"doc(Interpolate scattered 2-D samples, as `radrecon interpolate` does.

points: (n, 2) coordinates; values: (n,) or (n, c). Either queries: (m, 2) points, giving (m,)
or (m, c); or raster=(width, height) with domain=(x0, y0, x1, y1), giving (height, width) or
(height, width, c) values at the cells' centres, row 0 the y0 row. method: any of methods().
barriers: a GeoJSON (or other OGR) file of lines, or a sequence of (k, 2) polylines.
border_samples: as --border-samples, samples on the border of the rectangle holding domain
(with queries too, as --domain with --queries) and every sample, and beside the barriers, each a
plane fitted to the samples it sees. Further
keywords are the method's parameters as in --param (k=32, mu=2, outside="none", radius=...).
NaN where a method has no value. Samples at the same point are merged (a UserWarning).
Raises radrecon.Error (a ValueError) for refused input.)doc");

  bind_solutions(m);
}
