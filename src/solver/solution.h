#pragma once
// The solver's output: per mesh surface, its elements with their (u,v) cells and radiosity.

#include <optional>
#include <string>
#include <vector>

#include "core/vec.h"
#include "scene/param_cell.h"
#include "scene/scene.h"

namespace radrecon {

/// An element: a cell of its surface's parameter domain (a box, or a half-box on a triangle).
struct SolutionElement : ParamCell {
  Vec3 center;            ///< world-space point at the cell's (u,v) centroid, metres
  double area_m2;
  Rgb radiosity_w_m2;
};

struct SurfaceSolution {
  std::string name;  ///< "ground", or "wall1/front" and "wall1/back" for two-sided surfaces
  std::string scene_surface;
  bool back_side = false;
  /// Grid dimensions when the elements form a regular nu x nv grid stored row by row
  /// (element (i,j) at j * nu + i); 0 x 0 for an adaptive subdivision.
  int grid_nu = 0, grid_nv = 0;
  /// The surface's frame (scene/scene.h SurfaceFrame): (s, t) = (u length_u + v shear, v length_v).
  double length_u_m = 0, length_v_m = 0, shear_m = 0;
  /// Whether the surface is a triangle (its elements are half-boxes; no grid).
  bool triangle = false;
  std::vector<SolutionElement> elements;
  /// The side's discontinuity lines from the scene's geometry (scene/contacts.h), in its (s, t)
  /// metres: where other surfaces stand on it. Barriers of its reconstruction.
  std::vector<Polyline> barriers;
  /// The side's parts that are neither samples nor queries (scene/contacts.h excluded_regions()):
  /// closed polygons in its (s, t) metres, counter-clockwise, the first vertex not repeated at the
  /// end; under a surface lying flat on it, or enclosed by surfaces standing on it.
  std::vector<Polyline> excluded;

  SurfaceFrame frame() const { return {length_u_m, length_v_m, shear_m}; }
  /// An element's centroid in (s, t) metres.
  Vec2 centroid_st(const SolutionElement& e) const { return frame().st(e.centroid()); }
  /// The side's outline in (s, t) metres, counter-clockwise: a quad's rectangle (0, 0) to
  /// (length_u, length_v); a triangle's corners (0, 0), (length_u, 0), (shear, length_v).
  std::vector<Vec2> outline_st() const;
  /// Whether (s, t), metres, lies on the side: in its outline, or outside it by at most
  /// tol::kOnBorderParameter of its parameters (a point on its border, rounded).
  bool contains_st(const Vec2& st) const;
  /// The point of the side nearest to (s, t) through its parameters: (u, v) clamped to its
  /// domain (a triangle's onto its hypotenuse along u = v's normal), for a point contains_st()
  /// takes that lies outside the outline by rounding.
  Vec2 onto_side_st(const Vec2& st) const;
};

/// Solver statistics. Powers are per colour channel, in W.
struct SolveStats {
  std::string method;  ///< "progressive" or "hierarchical"
  size_t shots = 0;    ///< progressive refinement: patches shot
  size_t elements = 0;
  size_t patches = 0;
  size_t links = 0;        ///< hierarchical radiosity: links of the final hierarchy
  double epsilon_w = 0;    ///< hierarchical radiosity: the refinement threshold used, W
  Rgb emitted_w = Rgb::Zero();
  Rgb absorbed_w = Rgb::Zero();  ///< absorbed by the surfaces (1 - reflectance of what arrived)
  Rgb unshot_w = Rgb::Zero();    ///< reflected or emitted but not yet distributed
  Rgb escaped_w = Rgb::Zero();   ///< left an open scene (or lost to discretisation)
  double residual = 0;           ///< unshot / emitted, summed over channels
  /// Whether the solve met its tolerance: progressive refinement reached its residual (not its
  /// shot limit); hierarchical radiosity's final gathering settled (not its iteration limit).
  bool converged = true;
  double seconds = 0;
};

struct Solution {
  std::string scene;
  std::string mesh;  ///< the mesh specification, e.g. "grid:16"
  std::vector<SurfaceSolution> surfaces;
  SolveStats stats;

  const SurfaceSolution* find(const std::string& name) const;
};

/// Sets every negative radiosity value of the solution to 0, as a solution file requires
/// (radiosity is emitted plus reflected power per area). Only a far field's truncation can give
/// one (solver/far_field.h), none in the solves measured. Returns how many values were set and the
/// most negative of them (0 when none), W/m^2.
struct NegativeRadiosity {
  size_t count = 0;
  double most_negative_w_m2 = 0;
};
NegativeRadiosity clamp_negative_radiosity(Solution& solution);

}  // namespace radrecon
