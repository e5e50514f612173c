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

enum class Method { constant, bilinear, bicubic, shepard, multiquadric, natural_neighbour };

/// The command-line name of a method: constant, bilinear, bicubic, shepard, multiquadric,
/// natural-neighbour.
std::string method_name(Method m);
std::optional<Method> parse_method(const std::string& name);
/// Every method, in the order of the paper's Table 1.
std::vector<Method> all_methods();
/// The methods the paper applies to scattered (quadtree) data, in the order of its Table 2.
std::vector<Method> scattered_methods();
/// Methods that need their samples on a regular grid (bilinear, bicubic).
bool is_grid_method(Method m);

/// What natural-neighbour interpolation returns outside the convex hull of the samples (the
/// other methods are defined everywhere).
enum class OutsideHull {
  nearest,  ///< the value at the nearest point of the hull (continuous extension)
  none,     ///< no value (NaN)
};

/// Method parameters, as NAME=VALUE settings (parse_params()):
///   shepard:           mu (> 0, default 4): weights 1 / d^mu;
///                      k (integer >= 0, default 0): use the k nearest samples, 0 = all.
///   multiquadric:      mu (nonzero, not a positive integer; default 0.5): basis (d^2 + r^2)^mu;
///                      r (> 0, metres; default: Eck's rule, r_i = distance from sample i to
///                      its nearest other sample);
///                      k (integer, 0 or >= 3, default 0): 0 solves one global system; k > 0
///                      blends local multiquadrics on patches of about k samples (a partition
///                      of unity, local_multiquadric.h), for large sample sets.
///   natural-neighbour: outside (nearest | none, default nearest);
///                      barrier-samples (on | off, default on): with barriers, also samples along
///                      both sides of each barrier (border_samples.h), so that a query next to a
///                      barrier has natural neighbours of its own side there.
/// and, for every method, the barriers (not a NAME=VALUE setting: they come from a file or the
/// scene).
struct MethodParams {
  double shepard_mu = 4.0;
  int shepard_k = 0;
  double multiquadric_mu = 0.5;
  std::optional<double> multiquadric_r;
  int multiquadric_k = 0;
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

/// A one-line description of the parameters in effect, for reports ("mu=4, k=all").
std::string describe_params(Method method, const MethodParams& params);

/// The factories: an interpolant, or the reason the method cannot be built from the data (a
/// Failure naming no file or option; the caller says where the data came from).
using InterpolantResult = Result<std::unique_ptr<Interpolant>>;

/// Grid data (cell values), as in the paper: constant uses the cells; bilinear and bicubic
/// interpolate nodal values (nodal_average()); the scattered methods use the cell centres.
InterpolantResult make_grid_interpolant(Method method, const GridCells& cells,
                                                   const MethodParams& params = {});

/// The cells of a piecewise-constant function (a quadtree's leaves) as they are: constant only.
InterpolantResult make_cell_interpolant(const CellSamples& cells);

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

}  // namespace radrecon
