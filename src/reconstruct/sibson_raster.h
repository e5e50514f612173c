#pragma once
// Sibson's natural-neighbour interpolation at a raster's points, face by face instead of query by
// query (NaturalNeighbour::evaluate_raster(), natural_neighbour.h). Internal to reconstruct/.
//
// A query q's conflict zone is the set of Delaunay faces whose circumcircles hold it, and the
// area its Voronoi cell takes from sample a's is a sum over those faces: with T = (a, b, c)
// counter-clockwise, o_T its circumcentre, R_T its radius, D_T(q) = R_T^2 - |q - o_T|^2 (> 0 in
// the circle) and k_xy(q) = (x - q) x (y - q), face T gives a
//   D_T(q) / 8 * [ (b - q).(b - a) / k_ab(q) + (c - q).(c - a) / k_ca(q) ]
// (the stolen polygon of a, cut along the old Voronoi edges at a, is a fan of triangles
// (circumcentre of (q, a, j), o_T, circumcentre of (q, a, j')), whose corners lie on the
// bisector of q and a; the bisector's distance to o_T is D_T / (2 |a - q|)). So the
// interpolant's numerator and denominator are sums over faces, and each face can be scattered
// over the raster points inside its circle: some 4 faces a point, no walk, no conflict search.
//
// The terms of an edge (x, y) between two faces of the zone, T and N, add up to
// (D_T - D_N) / k_xy times (y - q).(y - x) (to x) and (x - q).(x - y) (to y). D_T - D_N and
// k_xy are both linear in q and vanish on the line through x and y (its points have the same
// power to both circles), so their ratio is a constant, 2 (o_T - o_N).g / |g|^2 with
// g = perp(x - y): such an edge is summed without dividing by k_xy, which vanishes on it. An
// edge on the zone's boundary keeps D_T / k_xy, which stays bounded (near its line, only next
// to x or y).
//
// The points the faces do not serve are left to the query-by-query path: those not inside the
// samples' hull by a margin (tol::kSibsonRasterHullMarginRelative), and those whose sum cancels
// (tol::kSibsonRasterCancellation: on or next to a sample, where the sums vanish, or under a
// sliver's huge circle by the hull).

#include <array>
#include <span>
#include <utility>
#include <vector>

#include "reconstruct/nn_delaunay.h"
#include "reconstruct/samples.h"

namespace radrecon {

class SibsonRaster {
 public:
  /// The triangulation's finite faces; `points` and `values` (channels per point) by sample
  /// index, as the triangulation's vertex info; `hull` the hull's edges (sample index pairs).
  /// The values are referred to, not copied: they must outlive this.
  SibsonRaster(const nn::Delaunay& dt, std::span<const Vec2> points, std::span<const double> values, int channels,
               std::span<const std::pair<unsigned, unsigned>> hull);

  /// Sibson's interpolant at the raster's points [first, first + count) into out (count *
  /// channels values, raster order). The indices k (0-based within the range) of the points it
  /// leaves unset go to `unserved`, in increasing order. A point's value depends on the point
  /// alone (the faces are summed in one fixed order), not on the range nor on the threads.
  /// Rows are shared among the threads, and a call of fewer rows than they want is cut into
  /// pieces of rows.
  void evaluate(const Raster& raster, size_t first, size_t count, std::span<double> out,
                std::vector<size_t>& unserved) const;
  /// False when some face's circumcircle is not finite (a face nearly flat in floating point):
  /// then evaluate() must not be used.
  bool usable() const { return usable_; }

 private:
  /// A circle: centre (shifted coordinates) and squared radius.
  struct Circle {
    Vec2 o = Vec2::Zero();
    double r2 = -1;  ///< < 0: none (the face across is infinite)
  };
  struct Face {
    std::array<unsigned, 3> v{};       ///< sample indices, counter-clockwise
    Circle circle;                     ///< the circumcircle
    std::array<Circle, 3> across{};    ///< the circumcircle of the face across edge k = (v[k], v[k+1])
    std::array<double, 3> half_c{};    ///< edge k inside the zone: half of (D_T - D_N) / k, constant
    std::array<double, 3> c_error{};   ///< a bound on half_c's magnitude and rounding, per edge
    double y_lo = 0, y_hi = 0;         ///< the circle's extent in y, widened
  };
  /// The circumcircle of a face, from its corners in CGAL's order: a face and its neighbours
  /// make it alike, to the bit.
  Circle circumcircle(const nn::Delaunay::Face_handle& f) const;
  /// The hull's x-extent at height y (shifted coordinates): [lo, hi], empty if lo > hi.
  std::pair<double, double> hull_span(double y) const;
  /// The faces whose circles may meet rows y in [y0, y1] (shifted coordinates), in the fixed order.
  void faces_near(double y0, double y1, std::vector<int>& out) const;

  std::vector<Face> faces_;
  std::vector<Vec2> p_;  ///< sample points less origin_
  std::span<const double> values_;
  int channels_;
  Vec2 origin_;            ///< the samples' box centre: coordinates relative to it
  double hull_margin_m_;   ///< points nearer the hull's boundary are left unserved
  std::vector<std::pair<Vec2, Vec2>> hull_;  ///< hull edges (shifted coordinates)
  // faces_ is stored in the fixed order of summation: the first ordinary_ faces (circles no
  // taller than kTallDiameters median diameters) by their circles' lowest y (y_lo_, ascending),
  // then by CGAL's order; the taller ones after them, in CGAL's order.
  size_t ordinary_ = 0;
  std::vector<double> y_lo_;
  double reach_m_ = 0;  ///< the tallest of the first ordinary_ faces' circles
  bool usable_ = true;
};

}  // namespace radrecon
