#include "reconstruct/kdtree.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <nanoflann.hpp>

#include "core/check.h"
#include "reconstruct/samples.h"

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

namespace {
/// within() searches this much (relative) beyond its radius before cutting at it (below).
constexpr double kRadiusSlack = 1e-12;
}  // namespace

void KdTree2::within(const Vec2& q, double radius_sq, std::vector<std::pair<unsigned, double>>& found) const {
  const double query[2] = {q.x(), q.y()};
  found.clear();
  nanoflann::SearchParams unsorted;
  unsorted.sorted = false;  // sorted below, ties by index
  // The tree prunes a cell by a distance to it that it sums step by step, which may round above
  // the distance of a point inside: searched a little wider, then cut at radius_sq exactly.
  impl_->tree.radiusSearch(query, radius_sq * (1 + kRadiusSlack), found, unsorted);
  std::erase_if(found, [&](const std::pair<unsigned, double>& f) { return !(f.second < radius_sq); });
  std::sort(found.begin(), found.end(), [](const std::pair<unsigned, double>& a, const std::pair<unsigned, double>& b) {
    return a.second < b.second || (a.second == b.second && a.first < b.first);
  });
}

namespace {

/// A tile of queries (and a bucket of points) is made to hold about this fraction of k points:
/// smaller tiles have fewer candidates per query, larger ones fewer tiles to set up (a tree
/// search and a gathering of candidates each).
constexpr double kTilePointsPerK = 0.125;
/// A tile gives up on candidates, and its queries search the tree, when its candidate disc
/// covers more buckets than this (queries far from the points, whose discs hold a large part
/// of them).
constexpr long kMaxTileBuckets = 4096;
/// The distance bounds are widened by this relative amount against the rounding of the
/// distances they add: a wider bound only ranks a few more candidates.
constexpr double kBoundSlack = 1e-9;
/// Up to this many candidates more than k within a query's radius are dropped one at a time
/// (the farthest each time); more (a tile's first query) go through a selection.
constexpr size_t kFewTooMany = 6;
/// A query first ranks the candidates within the last query's k-th distance, its square widened
/// by this factor: enough most of the time (a raster's next pixel is a small step away), and a
/// few too many otherwise.
constexpr double kFirstRadiusSqGrowth = 1.05;

struct Box {
  Vec2 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  Vec2 hi{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  void add(const Vec2& p) { lo = lo.cwiseMin(p), hi = hi.cwiseMax(p); }
  bool empty() const { return !(lo.x() <= hi.x()); }
};

/// A grid over a box (lower corner `origin`, `extent` wide) of square cells of at least `side`,
/// doubled until there are at most `most` cells; one cell for a box of no finite extent.
struct CellGrid {
  Vec2 origin;
  double side;
  long nx = 1, ny = 1;
  CellGrid(const Vec2& lower, const Vec2& extent, double least_side, long most) : origin(lower), side(least_side) {
    if (!extent.allFinite() || !(side > 0)) return;
    const auto count = [&](double span) -> long {
      const double c = span / side;
      return c < 1e9 ? static_cast<long>(c) + 1 : 1000000001L;
    };
    for (nx = count(extent.x()), ny = count(extent.y()); nx * ny > most; nx = count(extent.x()), ny = count(extent.y()))
      side *= 2;
  }
  /// The cell's index along one axis of a coordinate's offset from the origin, clamped.
  static long index(double offset, double side, long n) {
    const double c = offset / side;
    if (!(c < static_cast<double>(n))) return c >= static_cast<double>(n) ? n - 1 : 0;  // beyond, or NaN
    return c > 0 ? static_cast<long>(c) : 0;
  }
  size_t cell(const Vec2& p) const {
    return static_cast<size_t>(index(p.y() - origin.y(), side, ny) * nx + index(p.x() - origin.x(), side, nx));
  }
  size_t count() const { return static_cast<size_t>(nx * ny); }
};

/// Squared distance as nanoflann's L2_Simple_Adaptor forms it (0 + dx^2 + dy^2), bit for bit.
inline double distance_sq(double qx, double qy, double px, double py) {
  const double dx = qx - px, dy = qy - py;
  return dx * dx + dy * dy;
}

/// Sorts the items 0 .. count - 1 by cell, increasing within a cell: `cell_of(i)` is item i's
/// cell in [0, cells), or kNoCell to leave it out. Returns the items cell by cell, and sets
/// `first` to the cells + 1 offsets into them (a counting sort).
constexpr size_t kNoCell = static_cast<size_t>(-1);
template <typename CellOf>
std::vector<std::uint32_t> sort_by_cell(size_t count, size_t cells, CellOf&& cell_of, std::vector<std::uint32_t>& first) {
  first.assign(cells + 1, 0);
  for (size_t i = 0; i < count; ++i)
    if (const size_t c = cell_of(i); c != kNoCell) ++first[c + 1];
  for (size_t c = 1; c <= cells; ++c) first[c] += first[c - 1];
  std::vector<std::uint32_t> order(first.back());
  std::vector<std::uint32_t> next(first.begin(), first.end() - 1);
  for (size_t i = 0; i < count; ++i)
    if (const size_t c = cell_of(i); c != kNoCell) order[next[c]++] = static_cast<std::uint32_t>(i);
  return order;
}

}  // namespace

CoherentNearest::CoherentNearest(const KdTree2& tree, std::span<const Vec2> points, int k) : tree_(tree), k_(k) {
  RR_CHECK(k >= 1 && static_cast<size_t>(k) <= points.size() && points.size() == tree.size(),
           "k must be in [1, number of points], and the tree over the points");
  RR_CHECK(points.size() < (size_t{1} << 31), "too many points");
  const PointSpread spread = point_spread(points);
  tile_m_ = std::sqrt(kTilePointsPerK * k * spread.area_m2 / static_cast<double>(points.size()));
  const CellGrid buckets(spread.lo, spread.extent, tile_m_, 2 * static_cast<long>(points.size()) + 16);
  bucket_origin_ = buckets.origin, bucket_m_ = buckets.side;
  buckets_x_ = static_cast<int>(buckets.nx), buckets_y_ = static_cast<int>(buckets.ny);
  bucket_index_ = sort_by_cell(points.size(), buckets.count(), [&](size_t i) { return buckets.cell(points[i]); }, bucket_first_);
  bucket_x_.resize(points.size()), bucket_y_.resize(points.size()), bucket_slot_.resize(points.size());
  for (size_t e = 0; e < points.size(); ++e) {
    const Vec2& p = points[bucket_index_[e]];
    bucket_x_[e] = p.x(), bucket_y_[e] = p.y(), bucket_slot_[bucket_index_[e]] = static_cast<std::uint32_t>(e);
  }
}

CoherentNearest::Tiles CoherentNearest::tile(std::span<const Vec2> queries) const {
  RR_CHECK(queries.size() < (size_t{1} << 32), "too many queries");
  Tiles tiles;
  Box box;
  for (const Vec2& q : queries)
    if (q.allFinite()) box.add(q);
  if (box.empty()) return tiles;
  const Vec2 extent = box.hi - box.lo;
  const CellGrid grid(box.lo, extent, tile_m_, 4 * static_cast<long>(queries.size()) + 64);
  std::vector<std::uint32_t> first;
  tiles.order = sort_by_cell(
      queries.size(), grid.count(), [&](size_t q) { return queries[q].allFinite() ? grid.cell(queries[q]) : kNoCell; },
      first);
  // The non-empty tiles, with their queries' boxes.
  for (size_t t = 0; t + 1 < first.size(); ++t) {
    if (first[t] == first[t + 1]) continue;
    Box b;
    for (std::uint32_t k = first[t]; k < first[t + 1]; ++k) b.add(queries[tiles.order[k]]);
    tiles.first.push_back(first[t]);
    tiles.centre.push_back(0.5 * (b.lo + b.hi));
    tiles.half_diagonal_m.push_back(0.5 * (b.hi - b.lo).norm());
  }
  tiles.first.push_back(first.back());
  return tiles;
}

bool CoherentNearest::gather_candidates(const Vec2& c, double h, Scratch& s) const {
  const size_t k = static_cast<size_t>(k_);
  s.indices.resize(k), s.dist_sq.resize(k);
  tree_.nearest(c, k_, s.indices, s.dist_sq);
  s.centre_kth_m = std::sqrt(s.dist_sq[k - 1]);
  const double reach = (s.centre_kth_m + 2 * h) * (1 + kBoundSlack), reach_sq = reach * reach;
  if (!std::isfinite(reach)) return false;
  const auto range = [&](double lo, double hi, double origin, int n, long& a0, long& a1) {
    a0 = static_cast<long>(std::floor(std::max((lo - origin) / bucket_m_, -1.0)));
    a1 = static_cast<long>(std::floor(std::min((hi - origin) / bucket_m_, static_cast<double>(n))));
    a0 = std::max(a0, 0L), a1 = std::min(a1, static_cast<long>(n) - 1);
  };
  long a0, a1, b0, b1;
  range(c.x() - reach, c.x() + reach, bucket_origin_.x(), buckets_x_, a0, a1);
  range(c.y() - reach, c.y() + reach, bucket_origin_.y(), buckets_y_, b0, b1);
  if ((a1 - a0 + 1) * (b1 - b0 + 1) > kMaxTileBuckets) return false;
  s.cx.clear(), s.cy.clear(), s.ci.clear();
  for (long b = b0; b <= b1; ++b) {
    const size_t row = static_cast<size_t>(b) * static_cast<size_t>(buckets_x_);
    for (std::uint32_t e = bucket_first_[row + static_cast<size_t>(a0)]; e < bucket_first_[row + static_cast<size_t>(a1) + 1]; ++e)
      if (distance_sq(c.x(), c.y(), bucket_x_[e], bucket_y_[e]) <= reach_sq)
        s.cx.push_back(bucket_x_[e]), s.cy.push_back(bucket_y_[e]), s.ci.push_back(bucket_index_[e]);
  }
  s.d2.resize(s.cx.size());
  return s.cx.size() >= k;  // always (c's k nearest are within reach), unless rounding says otherwise
}

size_t CoherentNearest::in_bucket_order(const Vec2& q, Scratch& s) const {
  const size_t k = static_cast<size_t>(k_);
  const unsigned nearest_index = s.indices[0];  // the tree's first: the nearest, ties to the lowest index
  s.pos.resize(k);
  for (size_t j = 0; j < k; ++j) s.pos[j] = bucket_slot_[s.indices[j]];
  std::sort(s.pos.begin(), s.pos.end());
  size_t nearest = 0;
  for (size_t j = 0; j < k; ++j) {
    const std::uint32_t e = s.pos[j];
    s.indices[j] = bucket_index_[e];
    s.dist_sq[j] = distance_sq(q.x(), q.y(), bucket_x_[e], bucket_y_[e]);  // the tree's, bit for bit
    if (s.indices[j] == nearest_index) nearest = j;
  }
  return nearest;
}

double CoherentNearest::select(const Vec2& q, const Vec2& centre, const Vec2& last, double last_kth_m,
                               Scratch& s, size_t& nearest) const {
  const size_t k = static_cast<size_t>(k_), n = s.cx.size();
  const double qx = q.x(), qy = q.y();
  double* d2 = s.d2.data();
  const unsigned* ci = s.ci.data();
  const double *cx = s.cx.data(), *cy = s.cy.data();
  for (size_t i = 0; i < n; ++i) d2[i] = distance_sq(qx, qy, cx[i], cy[i]);
  // The candidates within a radius that holds at least k of them hold the k nearest. Tried
  // first: the last query's k-th distance, a little widened (the next query's is about the
  // same); then a bound: that distance plus the step between the two queries (or the tile
  // centre's k-th distance plus q's distance to it); then all of them, should rounding defeat
  // the slack. Kept as squared distances and indices, in the candidates' order.
  s.dist_sq.resize(n + 1), s.indices.resize(n + 1);
  double* sd = s.dist_sq.data();
  unsigned* si = s.indices.data();
  const auto within = [&](double radius_sq) {
    size_t m = 0;
    for (size_t i = 0; i < n; ++i) {  // without branches: the test's outcome is random
      sd[m] = d2[i], si[m] = ci[i];
      m += d2[i] <= radius_sq;
    }
    return m;
  };
  const double bound = (last_kth_m >= 0 ? last_kth_m + (q - last).norm() : s.centre_kth_m + (q - centre).norm()) *
                       (1 + kBoundSlack);
  size_t m = last_kth_m >= 0 ? within(std::min(last_kth_m * last_kth_m * kFirstRadiusSqGrowth, bound * bound)) : 0;
  if (m < k) m = within(bound * bound);
  if (m < k) m = within(std::numeric_limits<double>::infinity());
  if (m - k <= kFewTooMany) {
    // Drop the farthest (the highest index among equally far), one at a time, keeping the
    // others' order.
    for (; m > k; --m) {
      double far = sd[0];
      for (size_t j = 1; j < m; ++j) far = std::max(far, sd[j]);
      size_t worst = m;
      for (size_t j = 0; j < m; ++j)
        if (sd[j] == far && (worst == m || si[j] > si[worst])) worst = j;
      std::copy(sd + worst + 1, sd + m, sd + worst);
      std::copy(si + worst + 1, si + m, si + worst);
    }
  } else {
    // Select the k-th (by distance, then index) in a copy, then keep those not after it.
    s.pos.resize(m);
    for (size_t j = 0; j < m; ++j) s.pos[j] = static_cast<std::uint32_t>(j);
    const auto before = [&](std::uint32_t a, std::uint32_t b) { return sd[a] < sd[b] || (sd[a] == sd[b] && si[a] < si[b]); };
    std::nth_element(s.pos.begin(), s.pos.begin() + static_cast<std::ptrdiff_t>(k - 1), s.pos.end(), before);
    const double kth_sq = sd[s.pos[k - 1]];
    const unsigned kth_index = si[s.pos[k - 1]];
    size_t kept = 0;
    for (size_t j = 0; j < m; ++j)
      if (sd[j] < kth_sq || (sd[j] == kth_sq && si[j] <= kth_index)) sd[kept] = sd[j], si[kept] = si[j], ++kept;
  }
  double near = sd[0], far = sd[0];
  for (size_t j = 1; j < k; ++j) near = std::min(near, sd[j]), far = std::max(far, sd[j]);
  nearest = k;
  for (size_t j = 0; j < k; ++j)
    if (sd[j] == near && (nearest == k || si[j] < si[nearest])) nearest = j;
  return std::sqrt(far);
}

}  // namespace radrecon
