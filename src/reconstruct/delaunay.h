#pragma once
// The Delaunay triangulation of scattered samples as the piecewise methods (linear,
// clough-tocher) use it: faces with their samples and neighbours, point location with
// barycentric coordinates, and the outside-the-hull rule, all deterministic. The triangulation is
// CGAL's (exact predicates), built by CGAL's range insertion, whose spatial sort shuffles with a
// fixed-seed generator: co-circular samples (a lattice) are triangulated the same way in every
// run and for every thread count (the diagonal of a co-circular quadrilateral is CGAL's choice
// for the samples in their given order). A query's location depends on the query alone, never
// on where a walk started (see locate()). An outside query walks along the hull from where
// CGAL's walk left it to the edge nearest it (hull_chain.h, nearest_hull_face()).

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/check.h"
#include "core/parallel.h"
#include "core/vec.h"
#include "reconstruct/methods.h"

namespace radrecon {

/// Whether q lies on the hull edge ab up to rounding: within tol::kHullEdgeBandRelative of the
/// edge's length (or of `height_m`, the height over ab of the hull triangle on it, if smaller),
/// plus tol::kCoordinateRounding of the coordinates' magnitude. A point computed on a
/// hull edge as a + t (b - a) lands within that of it, a little inside or outside the hull; the
/// triangulation methods give it the value on the edge (never NaN, never a far-off value from
/// catastrophic cancellation). `slack_m` widens the band by the depth of the samples the edge was
/// split at (hull_chain.h): a point between the edge and them is on the hull too. Returns the
/// distance in units of that band (<= 1: on the edge) and the parameter t in [0, 1] of q's
/// nearest point a + t (b - a).
struct HullEdgeDistance {
  double in_bands = 0;
  double t = 0;
};
HullEdgeDistance hull_edge_distance(const Vec2& a, const Vec2& b, const Vec2& q,
                                    double height_m = std::numeric_limits<double>::infinity(), double slack_m = 0);

class DelaunayMesh {
 public:
  /// Triangulates `points` (metres). Throws ReconstructionError, naming `method`, for fewer than 3
  /// points, duplicate points or points all on one line.
  DelaunayMesh(std::span<const Vec2> points, const std::string& method);
  ~DelaunayMesh();
  DelaunayMesh(const DelaunayMesh&) = delete;
  DelaunayMesh& operator=(const DelaunayMesh&) = delete;

  const std::vector<Vec2>& points() const { return points_; }
  size_t faces() const { return vertices_.size(); }
  /// The sample indices of face f's corners, counter-clockwise.
  const std::array<unsigned, 3>& face(size_t f) const { return vertices_[f]; }
  /// The face across the edge opposite corner k of face f, or -1 when that edge is on the hull.
  std::int64_t neighbour(size_t f, int k) const { return neighbours_[f][k]; }
  /// Barycentric coordinates of p with respect to face f (any p, inside the face or not). On a
  /// sliver, p's projection onto the short edge on its side of the middle corner (the sliver as
  /// the polyline along its longest edge), as on_edge() gives it: the inverse of a sliver's
  /// matrix cancels catastrophically (linear's value on the edge of a face 3e-17 thick erred by
  /// 0.02 for a linear function), and the longest edge would blend two samples across the
  /// middle one.
  std::array<double, 3> barycentric(size_t f, const Vec2& p) const;

  /// Where a query lands: a face and its barycentric coordinates there (summing to one).
  struct Location {
    std::int64_t face = -1;
    std::array<double, 3> b{};
  };

  /// Locates q: inside the hull, the face holding it; on a vertex, coordinates (1, 0, 0) in some
  /// order (exactly: the value there is the sample's); on an edge shared by two faces, the face
  /// of smaller index, with coordinate 0 opposite the edge and the others linear along it (from
  /// the end of smaller sample index). On a hull edge up to rounding (hull_edge_distance()), inside
  /// or outside: the nearest piece of that edge split at the samples on it up to rounding
  /// (hull_chain.h), as an edge. Outside the hull: with OutsideHull::nearest, the point of the
  /// hull (through those samples) nearest to q, located the same way on its piece (ties: the
  /// piece of smaller sample indices); with OutsideHull::none, or for a non-finite q, false. `hint` is a face
  /// index to start the walk from (-1: anywhere), updated to the face found: it changes the
  /// speed only, never the result.
  bool locate(const Vec2& q, OutsideHull outside, std::int64_t& hint, Location& out) const;

  /// A face near q (one at q's nearest sample), to start walks from.
  std::int64_t face_near(const Vec2& q) const;

  /// Evaluates `value(location, o)` (o: `channels` doubles to write) at every query located by
  /// locate(), NaN elsewhere, in parallel over fixed chunks of queries whose walks start near
  /// their first query; results do not depend on the thread count.
  template <typename Value>
  void evaluate(std::span<const Vec2> queries, std::span<double> out, int channels, OutsideHull outside,
                const Value& value) const {
    RR_CHECK(out.size() == queries.size() * static_cast<size_t>(channels), "output size does not match the query points");
    constexpr std::int64_t kChunk = 64;
    const std::int64_t n = static_cast<std::int64_t>(queries.size());
    parallel_for(0, (n + kChunk - 1) / kChunk, [&](std::int64_t chunk) {
      const std::int64_t first = chunk * kChunk, last = std::min(n, first + kChunk);
      std::int64_t hint = queries[static_cast<size_t>(first)].allFinite() ? face_near(queries[static_cast<size_t>(first)]) : -1;
      Location loc;
      for (std::int64_t k = first; k < last; ++k) {
        double* o = &out[static_cast<size_t>(k) * static_cast<size_t>(channels)];
        if (locate(queries[static_cast<size_t>(k)], outside, hint, loc)) {
          value(loc, o);
        } else {
          for (int c = 0; c < channels; ++c) o[c] = std::numeric_limits<double>::quiet_NaN();
        }
      }
    });
  }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::vector<Vec2> points_;
  std::vector<std::array<unsigned, 3>> vertices_;
  std::vector<std::array<std::int64_t, 3>> neighbours_;
  /// Per face: corner 0 and the inverse of the matrix [p1 - p0, p2 - p0], row-major, so that
  /// (b1, b2) = inverse (q - p0); for a sliver (tol::kDelaunaySliverRelative), the corner
  /// opposite its longest edge, onto which queries are projected instead (-1: none).
  struct Affine {
    double x0, y0, m00, m01, m10, m11;
    int sliver_corner = -1;
  };
  std::vector<Affine> affine_;
};

}  // namespace radrecon
