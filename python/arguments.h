#pragma once
// Python arguments as radrecon's values, for the module (radrecon_module.cpp, solutions.cpp):
// arrays of any dtype and layout, paths, flags, keyword settings, rasters and query points, each
// refused with a radrecon.Error naming the argument where pybind would raise a TypeError naming
// none; and an interpolant evaluated over them.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/vec.h"
#include "reconstruct/barriers.h"
#include "reconstruct/interpolant.h"
#include "reconstruct/samples.h"

namespace radrecon::python {

namespace py = pybind11;

/// A C-contiguous float64 view of any array-like: no copy when it already is one.
using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// An array's shape as Python prints it, "(3, 2)".
std::string shape_of(const py::array& a);

/// An (n, 2) array of finite coordinates of magnitude at most tol::kMaxSampleCoordinate (the
/// command line's bound), named `what` in messages.
void check_points(const Doubles& a, const std::string& what);

/// `o` as an array of doubles (any real dtype, layout or nesting of sequences NumPy takes), or
/// UserError naming `what`: pybind's own TypeError for queries="abc" printed every argument's
/// whole array (23,605 characters) and named none of them. Complex numbers and masked arrays are
/// refused: NumPy's conversion would drop the imaginary parts or the mask unseen.
Doubles doubles_of(const py::handle& o, const std::string& what);

/// The points of an (n, 2) array as Vec2 (a copy: 16 bytes a point, small beside the work).
std::vector<Vec2> as_vec2(const Doubles& a);

/// Keyword arguments as the NAME=VALUE settings of --param (True/False as on/off for
/// barrier_samples, the one switch; elsewhere as Python writes them, so that mu=True is refused
/// as 'True', not as 'on').
std::vector<std::string> settings_of(const py::kwargs& params);

/// The library's warnings collected (core/error.h) as Python UserWarnings; with the GIL held.
void raise_warnings(const WarningCollector& warnings);

/// Whether `o` is a path: a str or an os.PathLike (pathlib.Path); and its text, refused (naming
/// `field`) when it holds a NUL character, at which the system would end it.
bool is_path(const py::handle& o);
std::string path_of(const py::handle& o, const std::string& field);

/// `o` as a sequence of `count` numbers (a tuple, list or array; not a string), each a whole
/// number if `whole` (not a bool); UserError naming `field` with what is `expected` otherwise.
/// pybind gave a TypeError of its own ("incompatible function arguments") for raster=(2.5, 3) or
/// "4x3".
std::vector<double> numbers_of(const py::handle& o, size_t count, bool whole, const std::string& field,
                               const std::string& expected);

/// `o` as text: a str (not bytes); UserError naming `field`, with what is `expected`, otherwise
/// (pybind's own TypeError named no argument).
std::string text_of(const py::handle& o, const std::string& field, const std::string& expected);

/// `o` as a number, or nullopt for None: a real number (int, float, a NumPy scalar; not a bool or
/// text), a whole one if `whole`; UserError naming `field` otherwise.
std::optional<double> optional_number(const py::handle& o, const std::string& field, bool whole = false);

/// `o` as a flag: True or False (a numpy bool too); UserError naming `field` otherwise. pybind's
/// own TypeError printed every argument, the arrays whole, and named none.
bool flag_of(const py::handle& o, const std::string& field);

/// Barriers from a file (GeoJSON, or any OGR line source through GDAL) or a sequence of (k, 2)
/// polylines.
Barriers barriers_of(const py::object& barriers);

/// raster=(width, height) as a size, or none; refused (naming "raster") beyond kMaxRasterSide
/// or, as the command line's limit, beyond Limit::raster_points cells counted once for each of
/// the `channels` value columns.
std::optional<std::pair<int, int>> raster_of(const py::object& raster_arg, int channels);

/// queries=(m, 2) as points, refused (naming "queries") as check_points() does or, as the command
/// line's limit, beyond Limit::raster_points points counted once for each value column.
std::vector<Vec2> query_points(const Doubles& queries, int channels);

/// The interpolant's values at the raster's cells (row by row, the domain's y0 row first) or at
/// the points, in batches of kEvaluateBatch, into `out` (channels() values a point). Without the GIL.
void evaluate_all(const Interpolant& f, const std::optional<Raster>& raster, std::span<const Vec2> points,
                  std::span<double> out);

}  // namespace radrecon::python
