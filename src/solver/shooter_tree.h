#pragma once
// The shooting side of progressive refinement (solver/progressive.h): a patch of elements as a
// hierarchy of blocks that shoot as one when far from a receiver (solver/far_field.h); what a
// receiving element gathers from it in one shot is solver/gather.h.

#include <array>
#include <span>
#include <vector>

#include "mesh/grid_mesh.h"
#include "scene/contacts.h"
#include "scene/scene.h"

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
/// The same from the side's contacts, found already (ContactFinder::at()).
ShooterSplits shooter_splits(const Scene& scene, const MeshSurface& side, const SideContactSet& contacts);

/// The blocks over the cells [i0,i1) x [j0,j1) of a side (a shooting patch), from the whole
/// patch down to single elements, with their unshot radiosity when built. A block splits in
/// four at its middle cell boundaries, or at the split (`splits`) inside it nearest to them.
class ShooterTree {
 public:
  /// `storage`: the blocks of an earlier tree (release()) to build in, so that successive shots
  /// reuse their memory rather than fault in fresh pages each (tens of MB for a large patch). It
  /// grows when it holds fewer blocks than the tree needs, and never shrinks: its blocks past the
  /// tree's are left as they are (block_count() of the largest patch sizes it once).
  /// The subtrees of the whole patch's children are built side by side (core/parallel.h); the
  /// blocks are laid out depth first, each block's children consecutive, whatever the threads.
  ShooterTree(const Surface& surface, const MeshSurface& side, const std::vector<Rgb>& unshot,
              int i0, int j0, int i1, int j1, std::vector<Block> storage = {}, const ShooterSplits* splits = nullptr);
  /// The blocks' memory, for the next tree.
  std::vector<Block> release() && { return std::move(blocks_); }
  /// The number of blocks of the tree over the cells [i0,i1) x [j0,j1) of `side`.
  static size_t block_count(const MeshSurface& side, const ShooterSplits* splits, int i0, int j0, int i1, int j1);

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
  /// The boxes of cells a block over [i0,i1) x [j0,j1) (more than one cell) of `side` splits
  /// into, those that hold elements, in order; returns their count.
  static int child_boxes(const MeshSurface& side, const ShooterSplits* splits, int i0, int j0, int i1, int j1,
                         std::array<std::array<int, 4>, 4>& boxes);
  /// Builds block `index` over a box of cells, its descendants from block `next` on; returns the
  /// block after the last of them.
  size_t build(size_t index, int i0, int j0, int i1, int j1, size_t next);

  const Surface& surface_;
  const MeshSurface& side_;
  const std::vector<Rgb>& unshot_;
  const ShooterSplits* splits_;
  std::vector<Block> blocks_;
};

}  // namespace radrecon
