#pragma once
// A solved scene reconstructed: one interpolant per surface side of a solution, by one method,
// in the side's metric coordinates (s, t) (SurfaceFrame, scene/scene.h). The renderer and
// the exporters read radiosity from it.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "reconstruct/methods.h"
#include "scene/scene.h"
#include "scene/side.h"
#include "solver/solution.h"

namespace radrecon {

/// How a side's samples feed its reconstruction.
struct SideSampling {
  /// Honour the side's barriers (the solution's contact lines, scene/contacts.h): no sample's
  /// influence crosses them. Methods that take no barriers (takes_barriers(), methods.h)
  /// reconstruct across them, and across the outlines of excluded regions.
  bool barriers = true;
  /// Add border samples (reconstruct/border_samples.h) on the side's border and both sides of its
  /// barriers (on a quad's sides; a triangle's have none), for the methods that take points (all but constant, the grid methods and
  /// gouraud, which use the data as it is).
  bool border_samples = false;
  /// A point of an excluded region within this distance (metres) of its outline takes the value
  /// just outside it, where it would have none: the region's corners lie where the surfaces meet,
  /// but its edges are straight in (s, t), which bend away from the true ones on a quad that is no
  /// parallelogram (Surface::frame_bend_m()), and a sliver of the side in view beside a block's
  /// foot fell inside (black rays in every picture of `radrecon cornell`). 0: none.
  double outline_band_m = 0;
};

/// Whether the point (s, t) of a side, metres, lies in one of its excluded regions
/// (SurfaceSolution::excluded: under a surface lying on the side, or enclosed by surfaces standing
/// on it), where every reconstruction has no value.
bool in_excluded_region(const std::vector<Polyline>& regions, const Vec2& st);

/// One side's reconstruction by `method` from its solution: grid sides as grid data
/// (make_grid_interpolant), adaptive sides as scattered data (their leaves for constant, the leaf
/// centres otherwise), with the side's barriers if `sampling` says so. A Failure when the method
/// cannot serve the side (a grid method on an adaptive side, too few or collinear samples).
InterpolantResult reconstruct_side(const SurfaceSolution& side, Method method, const MethodParams& params,
                                   const SideSampling& sampling);

/// A side the method could not serve, drawn piecewise constant instead, and why.
struct Fallback {
  std::string side;    ///< the side's name
  std::string reason;  ///< e.g. "natural-neighbour interpolation needs at least 3 samples, got 1"
  /// All the side's elements hold one value (a lamp of one leaf): piecewise constant is what any
  /// method would draw, nothing to warn of.
  bool exact = false;
};

/// reconstruct_side(), or where the method cannot serve the side (too few samples, a grid
/// method on a triangle), the side piecewise constant without its barriers, as render draws it,
/// `fallback` then saying why. A Failure only if even that cannot be made.
InterpolantResult reconstruct_side_or_constant(const SurfaceSolution& side, Method method, const MethodParams& params,
                                               const SideSampling& sampling, std::optional<Fallback>& fallback);



class SolutionReconstruction {
 public:
  /// Every side by reconstruct_side(). A side the method cannot serve falls back to piecewise
  /// constant and is listed with the reason in fallbacks(). The solution's sides must be the
  /// sides of `scene`, every one, with its edge lengths: UserError naming `source` (the
  /// solution's file) otherwise.
  SolutionReconstruction(const Scene& scene, const Solution& solution, Method method, const MethodParams& params,
                         const std::string& source, const SideSampling& sampling = {});
  ~SolutionReconstruction();

  /// The side's reconstruction, or null if the solution has no such side.
  const Interpolant* side(SideRef side) const;
  const std::vector<Fallback>& fallbacks() const { return fallbacks_; }
  /// The fallbacks worth a warning: those not exact.
  std::vector<Fallback> notable_fallbacks() const;

 private:
  std::vector<std::unique_ptr<Interpolant>> sides_;  ///< by SideRef::slot()
  std::vector<Fallback> fallbacks_;
};

}  // namespace radrecon
