// Python arguments as radrecon's values (python/arguments.h).

#include "arguments.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/limits.h"
#include "core/parse.h"
#include "core/tolerances.h"
#include "io/geojson.h"
#include "io/raster.h"

namespace radrecon::python {

std::string shape_of(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) s += (d ? ", " : "") + std::to_string(a.shape(d));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

void check_points(const Doubles& a, const std::string& what) {
  if (a.ndim() != 2 || a.shape(1) != 2) throw UserError(what, "an array of shape (n, 2) is expected; got shape " + shape_of(a));
  const double* p = a.data();
  for (py::ssize_t i = 0; i < a.size(); ++i) {
    if (!std::isfinite(p[i])) throw UserError(what + "[" + std::to_string(i / 2) + "]", "not a finite number");
    if (std::abs(p[i]) > tol::kMaxSampleCoordinate)
      throw UserError(what + "[" + std::to_string(i / 2) + "]",
                      format_number(p[i]) + " is beyond the largest coordinate, " + format_number(tol::kMaxSampleCoordinate));
  }
}

Doubles doubles_of(const py::handle& o, const std::string& what) {
  const auto refuse = [&] {
    std::string shown = py::repr(o).cast<std::string>();
    if (shown.size() > 60) shown = shown.substr(0, 57) + "...";
    throw UserError(what, "an array of numbers is expected, got " + shown + " (" +
                              py::str(py::type::of(o).attr("__name__")).cast<std::string>() + ")");
  };
  if (py::isinstance<py::str>(o) || py::isinstance<py::bytes>(o) || o.is_none()) refuse();
  // What NumPy would convert with a loss the caller would not see: a masked array's mask (its
  // hidden entries would count) and complex numbers (their imaginary parts would go, with only
  // NumPy's ComplexWarning).
  if (py::isinstance(o, py::module_::import("numpy.ma").attr("MaskedArray")))
    throw UserError(what, "a masked array: its mask would be ignored; pass the entries to use alone (e.g. a[~a.mask] "
                          "or, for points and values together, the rows no mask hides)");
  const py::object dtype = py::hasattr(o, "dtype") ? py::object(o.attr("dtype")) : [&] {
    try {
      return py::object(py::module_::import("numpy").attr("asarray")(o).attr("dtype"));
    } catch (const py::error_already_set&) {
      return py::object(py::none());  // ragged or not numbers: refused below as before
    }
  }();
  const std::string kind = !dtype.is_none() && py::hasattr(dtype, "kind") ? py::str(dtype.attr("kind")).cast<std::string>() : "";
  if (kind == "c")
    throw UserError(what, "complex numbers are not taken (their imaginary parts would be dropped); pass the real "
                          "parts (numpy.real) if they are what is meant");
  // NumPy would parse text as numbers ("0.5") and take dates as counts of their unit, in silence;
  // an object array (a pandas column of text) holds its text as str.
  bool text = false;
  if (kind == "O") {
    const py::object flat = py::module_::import("numpy").attr("asarray")(o, py::arg("dtype") = "O").attr("ravel")();
    for (const py::handle item : flat)
      if (py::isinstance<py::str>(item) || py::isinstance<py::bytes>(item)) {
        text = true;
        break;
      }
  }
  if (text)
    throw UserError(what, "an array of numbers is expected, got an object array holding text; convert it first (e.g. "
                          "a.astype(float)) if it holds numbers");
  if (kind == "U" || kind == "S" || kind == "M" || kind == "m" || kind == "V")
    throw UserError(what, "an array of numbers is expected, got one of " + py::str(dtype).cast<std::string>() +
                              (kind == "M" || kind == "m" ? " (dates or times)" : kind == "V" ? " (records)" : " (text)") +
                              "; convert it first (e.g. a.astype(float)) if it holds numbers");
  Doubles a = Doubles::ensure(o);
  if (!a) {
    PyErr_Clear();
    refuse();
  }
  return a;
}

std::vector<Vec2> as_vec2(const Doubles& a) {
  std::vector<Vec2> out(static_cast<size_t>(a.shape(0)));
  for (size_t i = 0; i < out.size(); ++i) out[i] = Vec2(a.data()[2 * i], a.data()[2 * i + 1]);
  return out;
}

std::vector<std::string> settings_of(const py::kwargs& params) {
  std::vector<std::string> out;
  for (const auto& [key, value] : params) {
    std::string name = py::str(key).cast<std::string>();
    if (name == "barrier_samples") name = "barrier-samples";  // a keyword cannot hold a hyphen
    std::string text;
    // A Python or NumPy bool (numpy.bool_ is no Python bool: its str() is "True").
    const bool is_bool = py::isinstance<py::bool_>(value) || py::isinstance(value, py::module_::import("numpy").attr("bool_"));
    if (is_bool && name == "barrier-samples") text = PyObject_IsTrue(value.ptr()) == 1 ? "on" : "off";
    else text = py::str(value).cast<std::string>();
    out.push_back(name + "=" + text);
  }
  return out;
}

void raise_warnings(const WarningCollector& warnings) {
  for (const std::string& w : warnings.messages())
    if (PyErr_WarnEx(PyExc_UserWarning, w.c_str(), 1) != 0) throw py::error_already_set();  // warnings turned into errors
}

bool is_path(const py::handle& o) { return py::isinstance<py::str>(o) || py::hasattr(o, "__fspath__"); }
std::string path_of(const py::handle& o, const std::string& field) {
  std::string path = py::module_::import("os").attr("fspath")(o).cast<std::string>();  // a PathLike's bytes: the name's bytes
  // The system's calls end a name at a NUL: "a.json\0x" would read or write a.json (as Python's
  // own open() refuses it).
  if (path.find('\0') != std::string::npos)
    throw UserError(field, "the file name " + py::repr(o).cast<std::string>() + " holds a NUL character");
  return path;
}

std::vector<double> numbers_of(const py::handle& o, size_t count, bool whole, const std::string& field,
                               const std::string& expected) {
  const auto refuse = [&] { throw UserError(field, expected + ", got " + py::repr(o).cast<std::string>()); };
  if (py::isinstance<py::str>(o) || py::isinstance<py::bytes>(o)) refuse();
  PyObject* list = PySequence_List(o.ptr());  // a tuple, list, array or any iterable
  if (list == nullptr) {
    PyErr_Clear();
    refuse();
  }
  const py::list items = py::reinterpret_steal<py::list>(list);
  if (items.size() != count) refuse();
  std::vector<double> out;
  for (const py::handle item : items) {
    if (PyBool_Check(item.ptr()) || py::isinstance<py::str>(item)) refuse();
    const double v = PyFloat_AsDouble(item.ptr());
    if (v == -1 && PyErr_Occurred()) {
      PyErr_Clear();
      refuse();
    }
    if (whole && !(v == std::floor(v) && std::abs(v) < 1e15)) refuse();
    out.push_back(v);
  }
  return out;
}

std::string text_of(const py::handle& o, const std::string& field, const std::string& expected) {
  if (!py::isinstance<py::str>(o)) throw UserError(field, expected + ", got " + py::repr(o).cast<std::string>());
  return o.cast<std::string>();
}

std::optional<double> optional_number(const py::handle& o, const std::string& field, bool whole) {
  if (o.is_none()) return std::nullopt;
  const std::string what = whole ? "a whole number" : "a number";
  const auto refuse = [&] { throw UserError(field, what + " (or None) is expected, got " + py::repr(o).cast<std::string>()); };
  if (py::isinstance<py::bool_>(o) || py::isinstance<py::str>(o) || py::isinstance<py::bytes>(o) ||
      py::isinstance(o, py::module_::import("numpy").attr("bool_")))
    refuse();
  PyObject* as_float = PyNumber_Float(o.ptr());
  if (as_float == nullptr) {
    PyErr_Clear();
    refuse();
  }
  const double v = PyFloat_AsDouble(as_float);
  Py_DECREF(as_float);
  if (whole && !(std::isfinite(v) && v == std::floor(v))) refuse();
  return v;
}

bool flag_of(const py::handle& o, const std::string& field) {
  if (PyBool_Check(o.ptr())) return o.ptr() == Py_True;
  if (py::hasattr(o, "dtype") && py::str(o.attr("dtype")).cast<std::string>() == "bool" && py::len(o.attr("shape")) == 0)
    return o.attr("item")().ptr() == Py_True;
  throw UserError(field, "True or False is expected, got " + py::repr(o).cast<std::string>());
}

Barriers barriers_of(const py::object& barriers) {
  if (barriers.is_none()) return {};
  if (is_path(barriers)) {
    const std::string path = path_of(barriers, "barriers");
    // pathlib.Path("") is "." : the working folder read as a vector source, no barriers meant.
    if (path.empty() || path == ".") throw UserError("barriers", "an empty file name (None: no barriers)");
    return read_barriers_file(path, "barriers");
  }
  if (py::isinstance<py::bytes>(barriers)) throw UserError("barriers", "a file name as bytes: give a str or a pathlib.Path");
  if (!py::isinstance<py::iterable>(barriers))
    throw UserError("barriers", "a file name (str or pathlib.Path) or a sequence of (k, 2) polylines is expected, got " +
                                    py::repr(barriers).cast<std::string>());
  std::vector<Polyline> lines;
  size_t index = 0;
  for (const py::handle item : barriers) {
    const std::string what = "barriers[" + std::to_string(index++) + "]";
    const Doubles line = doubles_of(item, what);  // complex and masked refused, as every array
    check_points(line, what);
    // Checked here so that messages count from 0, as Python does (the library's count from 1).
    if (line.shape(0) < 2) throw UserError(what, "a line needs 2 points, got " + std::to_string(line.shape(0)));
    Polyline& l = lines.emplace_back();
    for (py::ssize_t i = 0; i < line.shape(0); ++i) {
      l.emplace_back(line.at(i, 0), line.at(i, 1));
      if (i > 0 && l[i] == l[i - 1])
        throw UserError(what + "[" + std::to_string(i) + "]", "repeats the point before it: a segment of zero length");
    }
  }
  Result<Barriers> b = Barriers::from_polylines(lines);
  if (!b) throw UserError("barriers", b.reason());
  return std::move(b).value();
}

std::optional<std::pair<int, int>> raster_of(const py::object& raster_arg, int channels) {
  if (raster_arg.is_none()) return std::nullopt;
  const std::vector<double> r = numbers_of(raster_arg, 2, true, "raster", "(width, height), two whole numbers, is expected");
  if (r[0] < 1 || r[1] < 1 || r[0] > kMaxRasterSide || r[1] > kMaxRasterSide ||
      r[0] * r[1] * channels > static_cast<double>(limit_value(Limit::raster_points)))
    throw UserError("raster", "(" + format_number(r[0]) + ", " + format_number(r[1]) + ") is out of range: 1 <= width, height <= " +
                                  std::to_string(kMaxRasterSide) + ", at most " + std::to_string(limit_value(Limit::raster_points)) +
                                  " cells, each counted once for each value column (" + std::to_string(channels) + ")");
  return std::pair<int, int>(static_cast<int>(r[0]), static_cast<int>(r[1]));
}

std::vector<Vec2> query_points(const Doubles& queries, int channels) {
  check_points(queries, "queries");
  if (static_cast<double>(queries.shape(0)) * channels > static_cast<double>(limit_value(Limit::raster_points)))
    throw UserError("queries", std::to_string(queries.shape(0)) + " points of " + std::to_string(channels) +
                                   " value columns are beyond the limit of " + std::to_string(limit_value(Limit::raster_points)) +
                                   " (a point counts once for each value column)");
  return as_vec2(queries);
}

void evaluate_all(const Interpolant& f, const std::optional<Raster>& raster, std::span<const Vec2> points,
                  std::span<double> out) {
  const size_t channels = static_cast<size_t>(f.channels());
  const size_t count = raster ? static_cast<size_t>(raster->width) * static_cast<size_t>(raster->height) : points.size();
  for (size_t first = 0; first < count; first += kEvaluateBatch) {
    const size_t batch = std::min(kEvaluateBatch, count - first);
    const std::span<double> out_batch = out.subspan(first * channels, batch * channels);
    if (raster) f.evaluate_raster(*raster, first, batch, out_batch);
    else f.evaluate(points.subspan(first, batch), out_batch);
  }
}

}  // namespace radrecon::python
