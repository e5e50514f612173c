#include "reconstruct/methods.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

#include "core/check.h"
#include "core/error.h"
#include "core/parse.h"
#include "core/tolerances.h"
#include "reconstruct/barrier_grid.h"
#include "reconstruct/bicubic.h"
#include "reconstruct/bilinear.h"
#include "reconstruct/border_samples.h"
#include "reconstruct/clough_tocher.h"
#include "reconstruct/constant.h"
#include "reconstruct/delaunay_linear.h"
#include "reconstruct/gouraud.h"
#include "reconstruct/hermite.h"
#include "reconstruct/local_multiquadric.h"
#include "reconstruct/multiquadric.h"
#include "reconstruct/natural_neighbour.h"
#include "reconstruct/nearest.h"
#include "reconstruct/nodal.h"
#include "reconstruct/radius_gate.h"
#include "reconstruct/sample_set.h"
#include "reconstruct/shepard.h"

namespace radrecon {

std::string method_name(Method m) {
  switch (m) {
    case Method::constant: return "constant";
    case Method::bilinear: return "bilinear";
    case Method::bicubic: return "bicubic";
    case Method::shepard: return "shepard";
    case Method::multiquadric: return "multiquadric";
    case Method::natural_neighbour: return "natural-neighbour";
    case Method::linear: return "linear";
    case Method::clough_tocher: return "clough-tocher";
    case Method::sibson_c1: return "sibson-c1";
    case Method::laplace: return "laplace";
    case Method::thin_plate: return "thin-plate";
    case Method::gouraud: return "gouraud";
    case Method::hermite: return "hermite";
  }
  return "?";
}

std::optional<Method> parse_method(const std::string& name) {
  for (Method m : all_methods())
    if (method_name(m) == name) return m;
  return std::nullopt;
}

std::vector<Method> all_methods() {
  return {Method::constant,   Method::bilinear,      Method::bicubic,   Method::shepard, Method::multiquadric,
          Method::natural_neighbour, Method::hermite, Method::gouraud, Method::thin_plate, Method::linear,
          Method::clough_tocher, Method::sibson_c1, Method::laplace};
}

std::vector<Method> paper_methods() {
  return {Method::constant, Method::bilinear, Method::bicubic, Method::shepard, Method::multiquadric,
          Method::natural_neighbour};
}

bool is_paper_method(Method m) {
  const std::vector<Method> paper = paper_methods();
  return std::find(paper.begin(), paper.end(), m) != paper.end();
}

std::vector<Method> scattered_methods() {
  return {Method::constant, Method::shepard, Method::multiquadric, Method::natural_neighbour, Method::gouraud,
          Method::thin_plate, Method::linear, Method::clough_tocher, Method::sibson_c1, Method::laplace};
}

bool is_grid_method(Method m) { return m == Method::bilinear || m == Method::bicubic || m == Method::hermite; }

bool is_cell_method(Method m) { return m == Method::gouraud; }

bool takes_barriers(Method m) {
  return m != Method::linear && m != Method::clough_tocher && m != Method::gouraud;
}

namespace {

/// The global multiquadric solves a dense n x n system: 8000 samples take 0.5 GB and a minute.
constexpr size_t kMaxGlobalMultiquadric = 8000;

}  // namespace

namespace {

/// Builds an interpolant, turning a constructor's ReconstructionError into a Failure.
template <typename T, typename... Args>
InterpolantResult build(Args&&... args) {
  try {
    return InterpolantResult(std::unique_ptr<Interpolant>(std::make_unique<T>(std::forward<Args>(args)...)));
  } catch (const ReconstructionError& e) {
    return Failure{e.what()};
  }
}

BarrierGrid::Kind grid_kind(Method m) {
  return m == Method::bilinear  ? BarrierGrid::Kind::bilinear
         : m == Method::bicubic ? BarrierGrid::Kind::bicubic
                                : BarrierGrid::Kind::hermite;
}

/// Methods that do not take barriers refuse them, naming those that do.
std::optional<Failure> refuse_barriers(Method method, const MethodParams& params) {
  if (params.barriers.empty() || takes_barriers(method)) return std::nullopt;
  return Failure{barriers_problem(method)};
}

}  // namespace

InterpolantResult make_grid_interpolant(Method method, const GridCells& cells, const MethodParams& params) {
  if (auto refused = refuse_barriers(method, params)) return *refused;
  // Constant is the cells themselves; with barriers, the nearest visible cell centre (the cell
  // that holds the point, unless a barrier hides its centre).
  if (method == Method::constant && params.barriers.empty()) return build<PiecewiseConstant>(to_cells(cells));
  if (is_cell_method(method)) return make_cell_interpolant(method, to_cells(cells), params);
  if (is_grid_method(method)) {
    if (!params.barriers.empty()) return build<BarrierGrid>(cells, grid_kind(method), params.barriers);
    return make_nodal_interpolant(method, nodal_average(cells), params);
  }
  return make_scattered_interpolant(method, cells.centres(), params);
}

InterpolantResult make_cell_interpolant(Method method, const CellSamples& cells, const MethodParams& params) {
  if (auto refused = refuse_barriers(method, params)) return *refused;
  if (cells.cells.empty()) return Failure{"no cells"};
  if (method == Method::constant) return build<PiecewiseConstant>(cells);
  if (method == Method::gouraud) {
    if (!cells.triangles.empty()) return Failure{"gouraud needs rectangular cells; these are triangles"};
    return build<Gouraud>(cells);
  }
  return Failure{method_name(method) + " takes points, not cells"};
}

InterpolantResult make_nodal_interpolant(Method method, const GridNodes& nodes, const MethodParams& params) {
  if (auto refused = refuse_barriers(method, params)) return *refused;
  if (is_grid_method(method)) {
    if (nodes.nx < 2 || nodes.ny < 2) return Failure{method_name(method) + " needs a grid of at least 2 x 2 samples"};
    if (!params.barriers.empty()) return build<BarrierGrid>(nodes, grid_kind(method), params.barriers);
    if (method == Method::bilinear) return build<Bilinear>(nodes);
    if (method == Method::bicubic) return build<Bicubic>(nodes);
    return build<Hermite>(nodes);
  }
  ScatteredSamples s;
  s.channels = nodes.channels;
  s.values = nodes.values;
  for (int j = 0; j < nodes.ny; ++j)
    for (int i = 0; i < nodes.nx; ++i) s.points.emplace_back(nodes.x0 + i * nodes.dx, nodes.y0 + j * nodes.dy);
  return make_scattered_interpolant(method, s, params);
}

namespace {

/// Samples along both sides of each barrier, within the samples' bounding box (unless the samples
/// lie on one line: the methods refuse them then): without them, a query next to a barrier would
/// take far samples around its ends as natural neighbours (its Voronoi cell among the samples it
/// sees reaches across the barrier).
Result<ScatteredSamples> with_barrier_samples(const ScatteredSamples& samples, const MethodParams& params) {
  if (params.barriers.empty() || !params.barrier_samples || all_on_one_line(samples.points)) return samples;
  Vec2 lo = samples.points[0], hi = lo;
  for (const Vec2& p : samples.points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  BorderSampleSettings settings;
  settings.on_domain_border = false;
  Result<ScatteredSamples> with = with_border_samples(samples, Rect{lo.x(), lo.y(), hi.x(), hi.y()}, params.barriers, settings);
  if (!with) return Failure{"its barrier samples: " + with.reason()};
  return with;
}

}  // namespace

InterpolantResult make_scattered_interpolant(Method method, const ScatteredSamples& samples,
                                             const MethodParams& params) {
  RR_CHECK_EQ(samples.values.size(), samples.points.size() * static_cast<size_t>(samples.channels),
              "sample values do not match the points");
  if (samples.points.empty()) return Failure{"no samples"};
  Vec2 lo = samples.points[0], hi = lo;
  for (const Vec2& p : samples.points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  if (const double extent = (hi - lo).maxCoeff(); extent > 0 && extent < tol::kMinSampleExtent)
    return Failure{"the samples span only " + format_number(extent) + " (less than " + format_number(tol::kMinSampleExtent) +
                   "), where squared distances underflow: rescale the coordinates"};
  if (auto refused = refuse_barriers(method, params)) return *refused;
  switch (method) {
    case Method::constant: return build<NearestSample>(samples, params.barriers);
    case Method::bilinear:
    case Method::bicubic:
    case Method::hermite: return Failure{method_name(method) + " needs samples on a regular grid"};
    case Method::gouraud: return Failure{"gouraud needs cells (a grid's or a quadtree's), not points"};
    case Method::shepard:
      return build<Shepard>(samples, params.shepard_mu, params.shepard_k, params.barriers,
                            params.search_radius_m.value_or(std::numeric_limits<double>::infinity()),
                            params.min_points);
    case Method::multiquadric:
    case Method::thin_plate: {
      const bool thin = method == Method::thin_plate;
      const RbfKernel kernel = thin ? RbfKernel::thin_plate()
                                    : RbfKernel::multiquadric(params.multiquadric_mu, params.multiquadric_poly);
      const std::optional<double> r = thin ? std::nullopt : params.multiquadric_r;
      const int k = thin ? params.thin_plate_k : params.multiquadric_k;
      if (!(k > 0 && static_cast<size_t>(k) < samples.points.size()) && samples.points.size() > kMaxGlobalMultiquadric)
        return Failure{std::to_string(samples.points.size()) + " samples are too many for one global " + kernel.name() +
                       " system (at most " + std::to_string(kMaxGlobalMultiquadric) +
                       "); use local patches (parameter k, e.g. 32)"};
      InterpolantResult rbf = k > 0 && static_cast<size_t>(k) < samples.points.size()
                                  ? build<LocalMultiquadric>(samples, kernel, r, k, params.barriers)
                                  : build<Multiquadric>(samples, kernel, r, params.barriers);
      if (!rbf || !params.search_radius_m) return rbf;
      return InterpolantResult(std::unique_ptr<Interpolant>(std::make_unique<RadiusGate>(
          std::move(rbf).value(), samples, *params.search_radius_m, params.min_points)));
    }
    case Method::linear: return build<DelaunayLinear>(samples, params.outside);
    case Method::clough_tocher: return build<CloughTocher>(samples, params.outside, std::span<const double>{});
    case Method::natural_neighbour:
    case Method::laplace:
    case Method::sibson_c1: {
      Result<ScatteredSamples> with = with_barrier_samples(samples, params);
      if (!with) return Failure{with.reason()};
      const NeighbourRule rule = method == Method::laplace     ? NeighbourRule::laplace
                                 : method == Method::sibson_c1 ? NeighbourRule::sibson_c1
                                                               : NeighbourRule::sibson;
      return build<NaturalNeighbour>(with.value(), params.outside, params.barriers, rule);
    }
  }
  RR_CHECK(false, "unknown method");
  return Failure{"unknown method"};
}

std::string barriers_problem(Method method) {
  if (takes_barriers(method)) return {};
  std::string names;
  for (Method m : all_methods())
    if (takes_barriers(m)) names += (names.empty() ? "" : ", ") + method_name(m);
  return method_name(method) + " does not take barriers (methods that do: " + names + ")";
}

std::string point_method_problem(Method method) {
  if (!is_cell_method(method)) return {};
  return method_name(method) + " reconstructs cells (a grid's or a quadtree's leaves: radrecon render and paper), not "
                               "points; use e.g. linear or natural-neighbour";
}

std::string border_samples_problem(Method method) {
  if (method != Method::constant && !is_grid_method(method) && !is_cell_method(method)) return {};
  return "applies to the scattered methods that interpolate, not " + method_name(method) + " (which uses the data as it is)";
}

namespace {

/// How far from equal spacing 32-bit coordinates may stray, as a fraction of their extent (a
/// float's 6e-8, with margin): the message's hint about them, not a tolerance.
constexpr double kFloat32Stray = 1e-6;

/// `v` to two significant digits ("2.4e-08"), for a message.
std::string two_digits(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2g", v);
  return text;
}

}  // namespace

namespace {

/// Warns when Hardy's global multiquadric without a polynomial is given values whose mean is
/// large against their range: B(q) = sum alpha_j phi_j(q) holds no constant, so a constant added
/// to the values is not added to the interpolant (200 samples of 1000 gave 999.98 inside their
/// hull and 1119 0.6 m outside it: an outside-in trial). poly=1 and the local patches (k > 0)
/// fit the deviations from the mean. The paper's form, kept as it is; only interpolate's entry
/// warns (the command line on stderr, Python as a UserWarning), once the interpolant is made.
void warn_of_multiquadric_offset(const ScatteredSamples& samples, const MethodParams& params) {
  if (params.multiquadric_k != 0 || params.multiquadric_poly != 0 || samples.points.empty()) return;
  const size_t C = static_cast<size_t>(samples.channels), n = samples.points.size();
  for (size_t c = 0; c < C; ++c) {
    double sum = 0, lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (size_t k = 0; k < n; ++k) {
      const double v = samples.values[k * C + c];
      sum += v, lo = std::min(lo, v), hi = std::max(hi, v);
    }
    const double mean = sum / static_cast<double>(n);
    if (!(std::abs(mean) > tol::kMultiquadricOffsetWarning * (hi - lo))) continue;
    warn("multiquadric: the values' mean, " + format_number(mean) + ", is large against their range, " +
         format_number(hi - lo) + (C > 1 ? " (value column " + std::to_string(c + 1) + ")" : "") +
         ": Hardy's multiquadric holds no constant, so it bends toward 0 between and beyond the samples; "
         "--param poly=1 (or local patches, --param k=32) fits their deviations from the mean");
    return;
  }
}

}  // namespace

InterpolantResult make_point_interpolant(Method method, const ScatteredSamples& samples, const MethodParams& params) {
  if (const std::string problem = point_method_problem(method); !problem.empty()) return Failure{problem};
  if (!is_grid_method(method)) {
    InterpolantResult made = make_scattered_interpolant(method, samples, params);
    if (made && method == Method::multiquadric) warn_of_multiquadric_offset(samples, params);
    return made;
  }
  const std::optional<GridNodes> grid = as_regular_grid(samples);
  if (!grid) {
    const DistinctCoordinates d = count_distinct_coordinates(samples);
    // The counts of a whole grid, spaced unevenly: say so (float32 coordinates, rounded to 6e-8,
    // looked like a grid with the wrong counts).
    std::string spacing;
    for (const auto& [axis, off, tolerance] : {std::tuple{"x", d.x_uneven, d.x_tolerance}, std::tuple{"y", d.y_uneven, d.y_tolerance}})
      if (off > tolerance && spacing.empty())
        spacing = "; the " + std::string(axis) + " values are unevenly spaced: one lies " + two_digits(off) +
                  " of their extent from its equally spaced place, beyond the tolerance of " + two_digits(tolerance) +
                  (off < kFloat32Stray ? " (coordinates rounded to 32-bit floats stray by about 6e-8: give 64-bit ones)" : "");
    return Failure{method_name(method) + " needs samples on a regular grid: every combination of nx equally spaced "
                                         "x values and ny equally spaced y values (nx, ny >= 2), each exactly once; found " +
                   std::to_string(samples.points.size()) + " samples, " + std::to_string(d.x) + " distinct x, " +
                   std::to_string(d.y) + " distinct y" + spacing +
                   "; use a scattered method (e.g. natural-neighbour, linear, shepard)"};
  }
  return make_nodal_interpolant(method, *grid, params);
}

namespace {

/// The number of single-character insertions, deletions and substitutions that turn a into b.
size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

/// The method a user most likely meant by an unknown name: other tools' names for it (gdal_grid's
/// invdist, scipy's nearest and cubic, American spelling), else the nearest name within 2 edits;
/// none if neither.
std::optional<Method> meant_method(const std::string& name) {
  static const std::vector<std::pair<std::string, Method>> others = {
      {"natural-neighbor", Method::natural_neighbour}, {"natural_neighbour", Method::natural_neighbour},
      {"natural_neighbor", Method::natural_neighbour}, {"nn", Method::natural_neighbour},
      {"sibson", Method::natural_neighbour},           {"invdist", Method::shepard},
      {"idw", Method::shepard},                         {"inverse-distance", Method::shepard},
      {"nearest", Method::constant},                    {"rbf", Method::multiquadric},
      {"tps", Method::thin_plate},                      {"thin_plate", Method::thin_plate},
      {"thinplate", Method::thin_plate},                {"cubic", Method::clough_tocher},
      {"clough_tocher", Method::clough_tocher},         {"sibson_c1", Method::sibson_c1},
      {"barycentric", Method::linear},                  {"delaunay", Method::linear}};
  const std::string lower = ascii_lower(name);
  for (const auto& [other, m] : others)
    if (lower == other) return m;
  std::optional<Method> best;
  size_t best_distance = 3;  // at most 2 edits
  for (Method m : all_methods())
    if (const size_t d = edit_distance(lower, method_name(m)); d < best_distance) best = m, best_distance = d;
  return best;
}

}  // namespace

Method method_by_name(const std::string& name, const std::string& where, bool (*listed)(Method)) {
  if (const std::optional<Method> m = parse_method(name)) return *m;
  std::string names;
  for (Method m : all_methods())
    if (listed == nullptr || listed(m)) names += (names.empty() ? "" : ", ") + method_name(m);
  const std::optional<Method> meant = meant_method(name);
  throw UserError(where, "unknown method '" + name + "'" +
                             (meant ? " (did you mean " + method_name(*meant) + "?)" : std::string()) +
                             "; valid methods: " + names);
}

}  // namespace radrecon
