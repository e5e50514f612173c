#pragma once
// Clough-Tocher interpolation on the Delaunay triangulation of the samples, as scipy's
// CloughTocher2DInterpolator builds it [CT65; Farin 1986; Alfeld 1984]: each triangle is split
// at its centroid into three sub-triangles, each carrying a cubic Bezier patch; the patches
// interpolate the values and gradients at the samples and join with continuous first derivatives
// (C1) across the split and across the triangles' edges. The element is the reduced one: along
// each edge the derivative in a chosen cross direction is linear (not quadratic), the direction
// being the line from this triangle's centroid to its neighbour's (from the edge's midpoint to
// the centroid on the hull), which both triangles share and which transforms with the data under
// affine maps. So it reproduces quadratics given their gradients (not cubics).
//
// Gradients at the samples: Nielson's minimum-norm network [Nielson 1983; Renka & Cline 1984],
// as scipy's estimate_gradients_2d_global: they minimise the sum over the Delaunay edges E of
// int_E |d^2 W / ds^2|^2 ds, W the cubic along E that the element has there (fixed by the two
// values and the gradients' components along E). scipy minimises by Gauss-Seidel sweeps until
// the largest relative change is below tol = 1e-6 (its answer can then be 5e-6 off on data in
// metres, where gradients are small); here the 2n x 2n normal equations are solved to the
// rounding floor (conjugate gradients preconditioned by their 2 x 2 diagonal blocks, which bound
// the condition number by 3: some 30 iterations, tol::kNielsonResidualRelative), each channel
// on its own.
//
// Exact at the samples, C1 inside the convex hull, reproduces linear functions (their gradients
// are found exactly). Outside the hull: OutsideHull::nearest (the surface's value at the nearest
// hull point: the cubic of the hull edge) or OutsideHull::none (NaN).

#include <span>
#include <vector>

#include "reconstruct/delaunay.h"
#include "reconstruct/interpolant.h"
#include "reconstruct/methods.h"
#include "reconstruct/samples.h"

namespace radrecon {

class CloughTocher final : public Interpolant {
 public:
  /// Needs 3 samples not all on one line; duplicate points and non-finite values are refused
  /// (ReconstructionError). The result is linear in the values at any magnitude (the gradient
  /// estimate works in values scaled by a power of two). `gradients` (for tests): the gradients at the samples, (d/dx, d/dy) per sample and channel,
  /// index (i * channels + c) * 2 + d, instead of Nielson's estimate; empty: estimated.
  CloughTocher(const ScatteredSamples& samples, OutsideHull outside, std::span<const double> gradients = {});
  int channels() const override { return channels_; }
  void evaluate(std::span<const Vec2> points, std::span<double> out) const override;

  /// The gradients at the samples (per metre), laid out as the constructor's `gradients`.
  const std::vector<double>& gradients() const { return gradients_; }
  const DelaunayMesh& mesh() const { return mesh_; }

  /// Bezier control points per sub-triangle: the sub-triangle opposite corner k of a face has
  /// corners (i, j, centroid), i = k + 1, j = k + 2 (mod 3), and control points indexed by the
  /// powers of (b_i, b_j, b_centroid): 300, 210, 120, 030, 201, 111, 021, 102, 012, 003.
  static constexpr int kPerSubTriangle = 10;
  static constexpr int kPerFace = 3 * kPerSubTriangle;

 private:
  /// Nielson's gradients for every channel into gradients_.
  void estimate_gradients(const std::vector<double>& values);
  /// The control points of every face and channel into net_.
  void build_nets(const std::vector<double>& values);

  DelaunayMesh mesh_;
  int channels_;
  OutsideHull outside_;
  std::vector<double> gradients_;
  std::vector<double> net_;  ///< (face * channels + c) * kPerFace + sub-triangle * 10 + point
};

}  // namespace radrecon
