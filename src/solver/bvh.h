#pragma once
// Candidate occluders for exact visibility, found through a bounding volume hierarchy and a
// shaft (Haines and Wallace 1991, "Shaft culling for efficient ray-traced radiosity").
//
// The light that leaves a shooter polygon S and reaches a receiver region R travels along
// segments from points of R to points of S, all inside the convex hull of R and S: the shaft.
// An occluder that does not meet the shaft cannot hide any part of S from any point of R, so
// visible_form_factor() gives the same value without it (a conservative cull changes no
// shadow). The shaft here is the convex hull of R's and S's corners, kept as the half-spaces
// of its faces plus its bounding box; any half-space that contains all the corners is a valid
// separating test, so round-off in finding the hull's faces can only make the cull weaker,
// never wrong. A BVH node (or an occluder) entirely outside one of these half-spaces, by more
// than tol::kShaftSlack_m, is skipped; so is an occluder whose own plane has all the shaft's
// corners on one closed side (a segment between them can only touch the plane at an end, or run
// in it, where it carries no light).
//
// Why a BVH of our own rather than Embree: Embree answers ray queries (the first hit, or any
// hit, along a ray), while exact visibility needs the whole set of polygons that can meet a
// volume between two polygons, to clip the shooter against each. A shaft query over a small
// BVH (median split, a few occluders per leaf) is that set directly.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/box_hierarchy.h"
#include "solver/visibility.h"

namespace radrecon {

/// The convex hull of two sets of points (at most kMaxPoints in all), as half-spaces
/// {x : dot(normal, x) <= offset} each containing every point, the first six the bounding box.
class Shaft {
 public:
  static constexpr int kMaxPoints = 16;
  static constexpr int kMaxPlanes = 6 + 64;

  /// The hull of the points of `a` and `b` (e.g. a receiver point and a shooter polygon's
  /// corners, or the corners of two quads), widened by `margin_m` metres on every side: with
  /// `a` one point c, a margin of r holds every segment from a point within r of c to the hull
  /// of `b` (such a segment stays within r of the one from c).
  Shaft(std::span<const Vec3> a, std::span<const Vec3> b, double margin_m = 0);

  /// False when the axis-aligned box [lo, hi] lies wholly outside the shaft (by more than
  /// tol::kShaftSlack_m): nothing inside it can meet the shaft.
  bool may_meet_box(const Vec3& lo, const Vec3& hi) const;

  /// False when the occluder's polygon cannot shade the shaft: its corners all lie outside one of
  /// the shaft's half-spaces, or the shaft's points (the first set's widened by the margin) all
  /// lie on one closed side of its plane.
  bool may_meet(const Occluder& o) const;

  int plane_count() const { return plane_count_; }

 private:
  void add_plane(const Vec3& unit_normal);

  std::array<Vec3, kMaxPoints> points_;
  int point_count_ = 0;
  std::array<Vec3, kMaxPlanes> normal_;
  std::array<double, kMaxPlanes> offset_;
  int plane_count_ = 0;
  /// The hull's widening: kShaftSlack_m plus the caller's margin.
  double margin_m() const { return tol::kShaftSlack_m + reach_m_; }

  double reach_m_ = 0;   ///< the caller's margin, around the first set's points
  int a_count_ = 0;      ///< points_[0, a_count_) are the first set's
  Vec3 lo_, hi_;
};

/// A bounding volume hierarchy over a scene's occluders (median split along the longest axis
/// of the centroids' box, at most kLeafSize occluders per leaf). Keeps pointers into the vector
/// it was built from, which must outlive it and not change.
class OccluderBvh {
 public:
  static constexpr int kLeafSize = 4;

  OccluderBvh() = default;  ///< empty: finds nothing
  explicit OccluderBvh(const std::vector<Occluder>& occluders);

  /// Appends to `out` (not cleared) the occluders that may meet the shaft, other than the
  /// surfaces `skip_a` and `skip_b` (the receiver's and the shooter's), in the order of the
  /// hierarchy's leaves.
  void collect(const Shaft& shaft, size_t skip_a, size_t skip_b, std::vector<const Occluder*>& out) const;

  /// The occluders that may stand between two polygons (corners in order; a triangle may repeat
  /// its last corner): the BVH counterpart of occluders_between(), never larger than it
  /// (up to the slack of the box test).
  std::vector<const Occluder*> between(std::span<const Vec3> a, std::span<const Vec3> b, size_t surface_a,
                                       size_t surface_b) const;

  /// Whether an occluder crosses the segment from p to q farther than `ignore_m` from q: p and
  /// q strictly on either side of its plane (beyond tol::kPlaneDistance_m) and the crossing
  /// inside its polygon; the surface `skip` and those flagged in `skip_surfaces` (by scene
  /// surface; empty: none) aside. The shadow ray of a point source (solver/shooter_clusters.h).
  bool blocks_segment(const Vec3& p, const Vec3& q, double ignore_m, size_t skip,
                      std::span<const std::uint8_t> skip_surfaces) const;

  size_t node_count() const { return nodes_.size(); }

 private:
  std::vector<const Occluder*> order_;  ///< the occluders, leaf by leaf
  std::vector<BoxNode> nodes_;  ///< core/box_hierarchy.h
};

}  // namespace radrecon
