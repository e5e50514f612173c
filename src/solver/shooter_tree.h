#pragma once
// The shooting side of progressive refinement (solver/progressive.h): a patch of elements as a
// hierarchy of blocks that shoot as one when far from a receiver, and what a receiving point or
// element gathers from it in one shot.

#include <array>
#include <span>
#include <vector>

#include "mesh/grid_mesh.h"
#include "scene/contacts.h"
#include "scene/scene.h"
#include "solver/visibility.h"

namespace radrecon {

/// A node of the shooting hierarchy over one patch: the elements of the cells [i0,i1) x [j0,j1),
/// or a single element of a cell that holds two (a triangle's lower and upper halves).
struct Block {
  /// The block's outline, counter-clockwise seen from the front of the side: a box of cells, cut
  /// by a triangle's hypotenuse (5 corners at most).
  std::array<Vec3, 5> corners{Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  int corner_count = 0;
  Vec3 center;
  double diagonal_m = 0;          ///< the largest distance between two corners
  double area_m2 = 0;             ///< the sum of its elements' areas
  double radius_m = 0;            ///< the largest distance from `center` to a corner
  Rgb unshot_w_m2 = Rgb::Zero();  ///< area-weighted mean unshot radiosity of the block
  Rgb lowest_w_m2 = Rgb::Zero(), highest_w_m2 = Rgb::Zero();  ///< its elements' extremes
  /// The first moment of the unshot radiosity about the block's centroid, per channel (column),
  /// divided by the block's area: sum_k A_k (c_k - c) (B_k - B_mean) / A, W/m^2 times metres.
  Eigen::Matrix3d dipole = Eigen::Matrix3d::Zero();
  /// The block's second moment of area about its centroid over its area, int (y - c)(y - c)^T
  /// dA / A, m^2; and, per channel, that of the unshot radiosity's deviation from its mean,
  /// int (B(y) - B_mean)(y - c)(y - c)^T dA / A, W/m^2 times m^2 (B constant over each element).
  Eigen::Matrix3d area_moment = Eigen::Matrix3d::Zero();
  std::array<Eigen::Matrix3d, 3> quadrupole{Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero()};
  bool uniform = true;            ///< every element has the same unshot radiosity
  int first_child = -1;           ///< children are consecutive; -1 for a single element
  int child_count = 0;
};

/// Cell boundaries of a side at which its shooter trees split a block first: the lines u = i / nu
/// (in `u`) and v = j / nv (in `v`), ascending. See shooter_splits().
struct ShooterSplits {
  std::vector<int> u, v;
};

/// The splits of a side's shooter trees: the cell boundaries that lie on a contact line of the
/// side (scene/contacts.h: where a wall stands on the ground), extended across the side. A
/// receiver on that wall sees only what lies in front of its plane, so a block that straddles
/// the line is seen in part and splits (gather()) down to the elements along it, for every such
/// receiver; blocks split at the line are each seen whole or not at all. Lines farther than
/// tol::kSplitAlignRelative of a cell from a cell boundary, and triangles' sides, give none.
/// `contacts`: the scene's.
ShooterSplits shooter_splits(const Scene& scene, const MeshSurface& side, const ContactFinder& contacts);

/// The blocks over the cells [i0,i1) x [j0,j1) of a side (a shooting patch), from the whole
/// patch down to single elements, with their unshot radiosity when built. A block splits in
/// four at its middle cell boundaries, or at the split (`splits`) inside it nearest to them.
class ShooterTree {
 public:
  /// `storage`: the blocks of an earlier tree (release()) to build in, so that successive shots
  /// reuse their memory rather than fault in fresh pages each (tens of MB for a large patch).
  /// The subtrees of the whole patch's children are built side by side (core/parallel.h); the
  /// blocks are laid out depth first, each block's children consecutive, whatever the threads.
  ShooterTree(const Surface& surface, const MeshSurface& side, const std::vector<Rgb>& unshot,
              int i0, int j0, int i1, int j1, std::vector<Block> storage = {}, const ShooterSplits* splits = nullptr);
  /// The blocks' memory, for the next tree.
  std::vector<Block> release() && { return std::move(blocks_); }

  const Block& root() const { return blocks_[0]; }
  const Block& block(int k) const { return blocks_[static_cast<size_t>(k)]; }

 private:
  /// The outline of the (u,v) box [u0,u1] x [v0,v1] inside the side's parameter domain.
  void set_outline(Block& b, double u0, double v0, double u1, double v1) const;
  void set_corners(Block& b, const Vec2* uv, int n) const;
  /// The block's radiosity and moments from the side's elements [first, last) (a cell's).
  void set_radiosity(Block& b, size_t first, size_t last) const;
  /// The block's radiosity and moments from its children's: O(children), not O(elements).
  void aggregate(Block& b) const;
  /// The boxes of cells a block over [i0,i1) x [j0,j1) (more than one cell) splits into, those
  /// that hold elements, in order; returns their count.
  int child_boxes(int i0, int j0, int i1, int j1, std::array<std::array<int, 4>, 4>& boxes) const;
  /// The number of blocks of the subtree over a box of cells, its own included.
  size_t count(int i0, int j0, int i1, int j1) const;
  /// Builds block `index` over a box of cells, its descendants from block `next` on; returns the
  /// block after the last of them.
  size_t build(size_t index, int i0, int j0, int i1, int j1, size_t next);

  const Surface& surface_;
  const MeshSurface& side_;
  const std::vector<Rgb>& unshot_;
  const ShooterSplits* splits_;
  std::vector<Block> blocks_;
};

/// The radiosity a far block shoots with to the receiver point p (unit normal n), second order:
/// with k(y) = k(c) exp(g . t + t^T H t / 2 + ...) the point-to-point kernel (k = cos_y cos_x /
/// (pi r^2)) for y = c + t, g and H the gradient and Hessian of ln k over the source point at
/// the centroid c, M = H + g g^T, the block's form factor is F = k(c) A (1 + tr(M S) / 2) and
/// the sum over its elements sum_k F_k B_k = k(c) A (B_mean (1 + tr(M S) / 2) + g . dipole +
/// tr(M Q) / 2) (S: area_moment, Q: quadrupole), so the block shoots with
/// B_mean + (g . dipole + tr(M Q) / 2) / (1 + tr(M S) / 2), with an error of third order in
/// radius / distance whatever the radiosity over the block (first order only, B_mean +
/// g . dipole, where |tr(M S)| / 2 exceeds tol::kFarFieldCurvatureLimit). The mean alone errs to first order
/// wherever the radiosity varies (a wall lit at its top and dark at its foot), and that error
/// does not cancel over the receivers: it gains or loses power. Clamped to the block's range of
/// unshot radiosity.
Rgb far_field_radiosity(const Block& b, const Vec3& p, const Vec3& n, const Vec3& shooter_normal);
/// The same with the kernel's log-gradient at p already known: kernel_log_gradient()'s g, or
/// nullptr where it returned false (grazing: the block's mean).
Rgb far_field_radiosity(const Block& b, const Vec3& p, const Vec3& n, const Vec3& shooter_normal, const Vec3* gradient);

/// The gradient g over the source point y, at the block's centroid, of ln k(p, y) (see
/// far_field_radiosity()), 1/m; false at grazing angles (tol::kKernelCosine), where the far
/// field is the block's mean alone.
bool kernel_log_gradient(const Block& b, const Vec3& p, const Vec3& n, const Vec3& shooter_normal, Vec3& g);

/// The far field's error at p (unit normal n) per unit spread of the block's radiosity,
/// relative to its form factor, given g = kernel_log_gradient(): half the largest remainder of
/// the kernel's expansion over the block (relative to the kernel at its centroid), read off the
/// kernel at a box's corners and edge midpoints (other blocks: each edge's quarters) and scaled
/// by tol::kFarFieldRemainderSamplingBox (Other) for the points between them. Infinite where the
/// kernel is not positive at all of them (the block is cut by the receiver's plane), or where
/// its logarithm varies too much over the block for that (tol::kFarFieldCurvatureLimit). A block's
/// far field errs by about its spread times its form factor times this, or less.
double far_field_error(const Block& b, const Vec3& p, const Vec3& n, const Vec3& shooter_normal, const Vec3& g);

/// A receiving element as gather() sees it: its centre, and the points of a Gauss rule over it
/// for the blocks it is near to.
struct Receiver {
  Vec3 center, normal;
  double size_m = 0;  ///< the longer diagonal, metres
  std::array<Vec3, 4> gauss;
  int gauss_count = 0;
};

/// The Gauss rule's points over a cell, in (u, v), equal weights: exact for cubics on a box
/// (2 x 2 points), for quadratics on a triangle (3 points at barycentric (2/3, 1/6, 1/6) and its
/// permutations); the surface's Jacobian taken as constant over the cell (exact for
/// parallelograms and triangles).
struct GaussPoints {
  std::array<Vec2, 4> uv;
  int count = 0;
};
GaussPoints gauss_points(const ParamCell& cell);

/// The element as a receiver: its centre and its Gauss points on the surface.
Receiver make_receiver(const Surface& surface, const MeshElement& e, const Vec3& normal);

/// An upper bound of the unoccluded form factor from a differential area at p (unit normal n)
/// to the block: A cos_x cos_y / (pi r^2) with r no less than p's distance d to the block's
/// bounding sphere, cos_y = h / r (h: p's height over the shooter's plane) and cos_x no more
/// than the largest height of a corner over p's plane divided by d. Infinite when p is inside
/// the bounding sphere; 0 when p cannot see the block's front.
double form_factor_bound(const Block& b, const Vec3& p, const Vec3& n, const Vec3& shooter_normal);

/// Whether the receiving element gathers from the block at its centre alone (the midpoint rule):
/// its size is small against its distance to the block (tol::kMidpointReceiverRatio); else its
/// mean is gathered at its Gauss points. See gather().
bool gathers_at_centre(const Block& b, const Receiver& r);

/// What a receiving element gathers from one shot, W/m^2 per channel.
struct Gathered {
  Rgb at_center = Rgb::Zero();  ///< the irradiance at its centre: its radiosity's
  Rgb mean = Rgb::Zero();       ///< its mean irradiance: the power it absorbs and reflects
  Gathered& operator+=(const Gathered& o) {
    at_center += o.at_center;
    mean += o.mean;
    return *this;
  }
};

/// The occluders' shadow volumes (visibility.h) as a receiving element's centre (point 0) and
/// Gauss points (1 to gauss_count) see them: each point's made on first use and kept for every
/// polygon it looks at (the blocks of a shooting patch, the whole patch). The volumes live in
/// buffers of the calling thread: one at a time per thread. Receiver and occluders must outlive it.
class ReceiverShadows {
 public:
  ReceiverShadows(const Receiver& r, const std::vector<const Occluder*>& occluders) : r_(r), occluders_(occluders) {}
  /// The occluders found on first need: find() fills `occluders` before the first volume is
  /// made (a gather that needs no shadow, such as a late shot's patch shooting whole with its
  /// form factor known, then never searches for them). `find` is held by reference, as
  /// ThreadJob holds its callable: it must outlive this.
  template <typename Find>
  ReceiverShadows(const Receiver& r, const std::vector<const Occluder*>& occluders, const Find& find)
      : r_(r), occluders_(occluders), find_(&find), call_find_([](const void* f) { (*static_cast<const Find*>(f))(); }) {}
  std::span<const ShadowVolume> at(int point) const;

 private:
  const Receiver& r_;
  const std::vector<const Occluder*>& occluders_;
  const void* find_ = nullptr;  ///< null: the occluders are given
  void (*call_find_)(const void*) = nullptr;
  mutable bool found_ = false;
  mutable std::array<bool, 5> made_{};
  static thread_local std::array<std::vector<ShadowVolume>, 5> volumes_;
};

/// A polygon's visible form factor at a receiving element's centre, and whether the centre sees
/// it in part (visible_form_factor_past()'s value and `partly_seen`); and, if `gauss` is given,
/// its visible form factors at the element's Gauss points: NaN in gauss[0] until gather()
/// computes them (it then stores them there), else used as they are.
struct SeenFromCentre {
  double form_factor;
  bool partly;
  double* gauss = nullptr;  ///< Receiver::gauss_count values
};

/// Irradiance on the receiving element from the shooter's unshot radiosity: the block as a whole
/// when it is uniform or a single element, or when it may shoot as one; else the sum over its
/// children. With `budget_w_m2` <= 0 a block may shoot as one beyond tol::kFarFieldDiagonals of
/// its diagonal from the element's centre. With a budget, while its error estimate at the
/// centre is at most the budget's share in proportion to its area (the shares of the blocks that
/// shoot as one add up to the budget):
/// - its form factor times the spread of its unshot radiosity (channels summed), a strict bound:
///   the far field and the children's sum both lie in [lowest, highest] times the visible form
///   factor. The form factor is form_factor_bound(), or the visible form factor itself when the
///   element gathers at its centre alone and sees all of the block; or, when smaller,
/// - the same form factor times the spread times far_field_error(): the far field errs to third
///   order for any radiosity over the block; used only if the centre sees the whole block (a
///   block cut by the receiver's horizon or a shadow is seen through part of it only) and the
///   estimate is finite.
/// The element's radiosity is its value at its centre (what reconstructions sample); its power
/// is its mean, the midpoint rule's (the centre's value, relative error of order
/// (size / distance)^2) unless the element is large against its distance to the block
/// (tol::kMidpointReceiverRatio): then by the Gauss rule, so that no power is gained or lost by
/// point collocation next to the shooter.
///
/// `seen`, if given, holds what visible_form_factor_past() gives for the block's outline at the
/// element's centre with shadows.at(0): gather() then does not compute it again. If its `gauss`
/// is given too, gather() takes the block's form factors at the Gauss points from there, or
/// computes them and stores them there (NaN in gauss[0]) when it first needs them.
Gathered gather(const ShooterTree& tree, const Block& b, const Receiver& r, const Vec3& shooter_normal,
                const ReceiverShadows& shadows, double budget_w_m2, const SeenFromCentre* seen = nullptr);

}  // namespace radrecon
