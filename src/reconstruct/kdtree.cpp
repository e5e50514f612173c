#include "reconstruct/kdtree.h"

#include <nanoflann.hpp>

#include "core/check.h"

namespace radrecon {

namespace kdtree_detail {

struct PointCloud {
  std::span<const Vec2> pts;
  size_t kdtree_get_point_count() const { return pts.size(); }
  double kdtree_get_pt(size_t i, size_t dim) const { return pts[i][static_cast<Eigen::Index>(dim)]; }
  template <class BBox>
  bool kdtree_get_bbox(BBox&) const { return false; }
};

using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, PointCloud>, PointCloud, 2, unsigned>;

}  // namespace kdtree_detail

struct KdTree2::Impl {
  kdtree_detail::PointCloud cloud;
  kdtree_detail::Tree tree;
  explicit Impl(std::span<const Vec2> p) : cloud{p}, tree(2, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {
    tree.buildIndex();
  }
};

KdTree2::KdTree2(std::span<const Vec2> points) : impl_(std::make_unique<Impl>(points)) {}
KdTree2::~KdTree2() = default;
size_t KdTree2::size() const { return impl_->cloud.pts.size(); }

size_t KdTree2::nearest(const Vec2& q, int k, std::span<unsigned> indices, std::span<double> dist_sq) const {
  RR_CHECK(k >= 1 && static_cast<size_t>(k) <= size(), "k must be in [1, number of points]");
  RR_CHECK(indices.size() >= static_cast<size_t>(k) && dist_sq.size() >= static_cast<size_t>(k),
           "the result buffers must hold k entries");
  const double query[2] = {q.x(), q.y()};
  // nanoflann's KNNResultSet keeps its k best sorted by distance alone, in the caller's buffers.
  const size_t found = impl_->tree.knnSearch(query, static_cast<size_t>(k), indices.data(), dist_sq.data());
  // Only an overflowing squared distance (coordinates beyond tol::kMaxSampleCoordinate, which the
  // readers refuse) can make nanoflann keep fewer than k.
  RR_CHECK_EQ(found, static_cast<size_t>(k), "neighbour search lost points (coordinates too large?)");
  // Equal distances by index (nanoflann's order among ties is unspecified). Insertion sort: the
  // entries are already sorted by distance, so only runs of ties move.
  for (size_t i = 1; i < found; ++i) {
    const double d = dist_sq[i];
    const unsigned index = indices[i];
    size_t j = i;
    for (; j > 0 && (dist_sq[j - 1] > d || (dist_sq[j - 1] == d && indices[j - 1] > index)); --j) {
      dist_sq[j] = dist_sq[j - 1];
      indices[j] = indices[j - 1];
    }
    dist_sq[j] = d;
    indices[j] = index;
  }
  return found;
}

}  // namespace radrecon
