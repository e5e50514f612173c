#include "reconstruct/kdtree.h"

#include <algorithm>
#include <numeric>

#include <nanoflann.hpp>

#include "core/check.h"

namespace radrecon {

namespace {

struct PointCloud {
  std::span<const Vec2> pts;
  size_t kdtree_get_point_count() const { return pts.size(); }
  double kdtree_get_pt(size_t i, size_t dim) const { return pts[i][static_cast<Eigen::Index>(dim)]; }
  template <class BBox>
  bool kdtree_get_bbox(BBox&) const { return false; }
};

using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, PointCloud>, PointCloud, 2, unsigned>;

}  // namespace

struct KdTree2::Impl {
  PointCloud cloud;
  Tree tree;
  explicit Impl(std::span<const Vec2> p) : cloud{p}, tree(2, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {
    tree.buildIndex();
  }
};

KdTree2::KdTree2(std::span<const Vec2> points) : impl_(std::make_unique<Impl>(points)) {}
KdTree2::~KdTree2() = default;
size_t KdTree2::size() const { return impl_->cloud.pts.size(); }

void KdTree2::nearest(const Vec2& q, int k, std::vector<unsigned>& indices, std::vector<double>& dist_sq) const {
  RR_CHECK(k >= 1 && static_cast<size_t>(k) <= size(), "k must be in [1, number of points]");
  indices.resize(static_cast<size_t>(k));
  dist_sq.resize(static_cast<size_t>(k));
  const double query[2] = {q.x(), q.y()};
  const size_t found = impl_->tree.knnSearch(query, static_cast<size_t>(k), indices.data(), dist_sq.data());
  indices.resize(found);
  dist_sq.resize(found);
  // Deterministic order for equal distances (nanoflann's order among ties is unspecified).
  std::vector<size_t> order(found);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return dist_sq[a] < dist_sq[b] || (dist_sq[a] == dist_sq[b] && indices[a] < indices[b]);
  });
  std::vector<unsigned> idx(found);
  std::vector<double> d(found);
  for (size_t i = 0; i < found; ++i) {
    idx[i] = indices[order[i]];
    d[i] = dist_sq[order[i]];
  }
  indices.swap(idx);
  dist_sq.swap(d);
}

}  // namespace radrecon
