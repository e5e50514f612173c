#pragma once
// The closed set of reconstruction methods, their parameters, and the factories that build an
// interpolant from grid data, nodal grids or scattered samples.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/result.h"
#include "reconstruct/barriers.h"
#include "reconstruct/interpolant.h"
#include "reconstruct/samples.h"

namespace radrecon {

/// The paper's six methods, then those it cites without running them (gouraud [CW93],
/// clough-tocher [SLD92], hermite [BdSF93], thin-plate: an RBF with a linear polynomial) and those
/// users of scattered-data tools expect (linear, sibson-c1, laplace). docs/method.md has each
/// one's construction and reference.
enum class Method {
  constant,
  bilinear,
  bicubic,
  shepard,
  multiquadric,
  natural_neighbour,
  linear,
  clough_tocher,
  sibson_c1,
  laplace,
  thin_plate,
  gouraud,
  hermite,
};

/// The command-line name of a method: constant, bilinear, bicubic, shepard, multiquadric,
/// natural-neighbour, linear, clough-tocher, sibson-c1, laplace, thin-plate, gouraud, hermite.
std::string method_name(Method m);
std::optional<Method> parse_method(const std::string& name);
/// parse_method(), with an unknown name refused: UserError naming `where` and listing the methods
/// (those `listed` accepts, if given: the ones the command takes).
Method method_by_name(const std::string& name, const std::string& where, bool (*listed)(Method) = nullptr);
/// Every method: the paper's Table 1 order, then the new ones.
std::vector<Method> all_methods();
/// The six methods the paper ran (its Table 1).
std::vector<Method> paper_methods();
bool is_paper_method(Method m);
/// The methods that apply to a quadtree's leaves (Table 2): the paper's four (constant, shepard,
/// multiquadric, natural-neighbour), then gouraud and the new scattered methods.
std::vector<Method> scattered_methods();
/// Methods that need their samples on a regular grid (bilinear, bicubic, hermite).
bool is_grid_method(Method m);
/// Methods that need cells (a grid's or a quadtree's leaves), not points: gouraud.
bool is_cell_method(Method m);
/// Methods that honour barriers (MethodParams::barriers). The others (linear, clough-tocher,
/// gouraud) refuse them in the factories; a solution's side is then reconstructed
/// without them (sampling/solution_reconstruction.h says so).
bool takes_barriers(Method m);
/// Why the method cannot take barriers ("linear does not take barriers (methods that do: ...)"),
/// or empty if it can.
std::string barriers_problem(Method m);
/// Why the method cannot interpolate points (gouraud reconstructs cells), or empty if it can.
std::string point_method_problem(Method m);
/// Why border samples (border_samples.h) do not apply to the method (constant, the grid methods
/// and gouraud use the data as it is), or empty if they do.
std::string border_samples_problem(Method m);

/// What the triangulation methods (natural-neighbour, linear, clough-tocher, sibson-c1, laplace)
/// return outside the convex hull of the samples (the other methods are defined everywhere).
enum class OutsideHull {
  nearest,  ///< the value at the nearest point of the hull (continuous extension)
  none,     ///< no value (NaN)
};

/// Method parameters, as NAME=VALUE settings (parse_params()):
///   shepard:           mu (> 0, default 4): weights 1 / d^mu;
///                      k (integer >= 0, default 0): use the k nearest samples, 0 = all.
///   multiquadric:      mu (nonzero, not within tol::kMultiquadricIntegerGap of a positive
///                      integer; default 0.5): basis (d^2 + r^2)^mu;
///                      r (> 0, metres; default: Eck's rule, r_i = distance from sample i to
///                      its nearest other sample);
///                      k (integer, 0 or >= 3, default 0): 0 solves one global system; k > 0
///                      blends local multiquadrics on patches of about k samples (a partition
///                      of unity, local_multiquadric.h), for large sample sets.
///                      poly (0 | 1, default 0): 1 adds a linear polynomial a + b x + c y with
///                      the side conditions sum alpha_j = sum alpha_j x_j = sum alpha_j y_j = 0
///                      (then linear functions are reproduced).
///   thin-plate:        k (as multiquadric's): r^2 log r with a linear polynomial.
///   natural-neighbour, laplace, sibson-c1:
///                      outside (nearest | none, default nearest);
///                      barrier-samples (on | off, default on): with barriers, also samples along
///                      both sides of each barrier (border_samples.h), so that a query next to a
///                      barrier has natural neighbours of its own side there.
///   linear, clough-tocher: outside (nearest | none, default nearest).
///   gouraud, hermite, constant, bilinear, bicubic: none.
/// and, for every method, the barriers (not a NAME=VALUE setting: they come from a file or the
/// scene).
struct MethodParams {
  double shepard_mu = 4.0;
  int shepard_k = 0;
  /// A search radius (m) and the fewest samples within it that give a value (gdal_grid's radius
  /// and min_points): shepard uses only the samples within it (shepard.h); the multiquadric and
  /// the thin-plate spline give no value where too few lie within it (radius_gate.h). None by
  /// default.
  std::optional<double> search_radius_m;
  int min_points = 1;
  double multiquadric_mu = 0.5;
  std::optional<double> multiquadric_r;
  int multiquadric_k = 0;
  int multiquadric_poly = 0;
  int thin_plate_k = 0;
  OutsideHull outside = OutsideHull::nearest;
  bool barrier_samples = true;
  /// Lines no sample's influence crosses (barriers.h); none by default. Every method honours
  /// them (see each method's header) except constant on cells, which is the data as it is.
  Barriers barriers;
};

/// Parses NAME=VALUE settings for `method`. Throws UserError naming `where` (the caller's
/// location of the settings, e.g. an option) and the parameter for an unknown parameter, a
/// malformed value or one out of range.
MethodParams parse_params(Method method, const std::vector<std::string>& settings, const std::string& where);

/// Why `k` is no patch size of the local multiquadric and thin-plate (their k=): 0 (one global
/// system) or an integer from kLeastRbfPatch to kMostRbfPatch samples; empty if it is one.
inline constexpr int kLeastRbfPatch = 3;
inline constexpr int kMostRbfPatch = 100000;
std::string rbf_patch_problem(double k);

/// A one-line description of the parameters in effect, for reports ("mu=4, k=all").
std::string describe_params(Method method, const MethodParams& params);

/// The factories: an interpolant, or the reason the method cannot be built from the data (a
/// Failure naming no file or option; the caller says where the data came from).
using InterpolantResult = Result<std::unique_ptr<Interpolant>>;

/// Grid data (cell values), as in the paper: constant uses the cells; bilinear and bicubic
/// interpolate nodal values (nodal_average()); the scattered methods use the cell centres.
InterpolantResult make_grid_interpolant(Method method, const GridCells& cells,
                                                   const MethodParams& params = {});

/// The cells of a piecewise-constant function (a quadtree's leaves): constant uses them as they
/// are; gouraud balances the quadtree they form and interpolates linearly over its triangles.
/// (The scattered methods take the cell centres: make_scattered_interpolant.)
InterpolantResult make_cell_interpolant(Method method, const CellSamples& cells, const MethodParams& params = {});

/// Values at the nodes of a regular grid: bilinear and bicubic interpolate them; the other
/// methods take the nodes as scattered samples.
InterpolantResult make_nodal_interpolant(Method method, const GridNodes& nodes,
                                                    const MethodParams& params = {});

/// Scattered samples: constant is the nearest sample's value (Voronoi cells); shepard,
/// multiquadric and natural-neighbour as documented. Fails when the method cannot be built from
/// them: a grid method, too few samples, duplicate points, too many for a global system, or
/// (natural-neighbour) all samples on one line.
InterpolantResult make_scattered_interpolant(Method method, const ScatteredSamples& samples,
                                                        const MethodParams& params = {});

/// Points with values, as `radrecon interpolate` and the Python module take them: the grid
/// methods (bilinear, bicubic, hermite) need them to form a regular grid (any order; the failure
/// says how far they are from one), the cell methods are refused, the others take them as
/// scattered samples (make_scattered_interpolant).
InterpolantResult make_point_interpolant(Method method, const ScatteredSamples& samples, const MethodParams& params = {});

/// `radrecon interpolate --border-samples` and Python's border_samples=True: border samples
/// (border_samples.h) on the border of the rectangle that holds `domain` (the raster's) and every
/// sample (so a window of a raster gets the values of the whole; without a domain, the samples'
/// bounding box),
/// and beside `params`' barriers (but for thin-plate and a multiquadric of a given r, whose fits
/// through two such samples 2e-6 apart swing past a barrier's free end), appended to `samples`; `params` then adds no barrier samples of
/// its own. Returns how many were added, or why none could be (the method takes none:
/// border_samples_problem(); the rule's own failures).
Result<size_t> add_border_samples(Method method, ScatteredSamples& samples, const std::optional<Rect>& domain,
                                  MethodParams& params);

/// A failure of make_point_interpolant() after add_border_samples() added `border_samples`: its
/// counts include them, which the user did not pass, so the reason says so (unchanged for 0).
std::string reason_with_border_samples(const std::string& reason, size_t border_samples);

}  // namespace radrecon
