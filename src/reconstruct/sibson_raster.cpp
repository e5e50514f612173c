#include "reconstruct/sibson_raster.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>

#if defined(__FMA__)
#include <immintrin.h>
#endif

#include "core/check.h"
#include "core/parallel.h"
#include "core/tolerances.h"

namespace radrecon {

namespace {

using tol::kSibsonRasterChordSlack;

/// Faces whose circles are more than this many typical (median) diameters tall are searched
/// apart from the order by y (slivers by the hull): the order is searched below a row by the
/// tallest of the others.
constexpr double kTallDiameters = 8;

/// The fewest points of a row that evaluate() hands a thread as a piece of their own.
constexpr size_t kLeastPiecePoints = 1024;

/// Four doubles, and four lanes' masks (all bits set where true), as GCC and Clang's vector
/// extensions make them: the chord's points go through the kernel four at a time, every point
/// (the last ones padded) by the same instructions, so that its value does not depend on where
/// its chord starts.
// (Internal functions: the ABI note GCC gives for them without AVX concerns no caller outside.)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
using D4 = double __attribute__((vector_size(32)));
using M4 = long long __attribute__((vector_size(32)));
constexpr size_t kLanes = 4;

D4 blend4(M4 mask, D4 a, D4 b) { return reinterpret_cast<D4>((reinterpret_cast<M4>(a) & mask) | (reinterpret_cast<M4>(b) & ~mask)); }
D4 abs4(D4 a) { return reinterpret_cast<D4>(reinterpret_cast<M4>(a) & 0x7fffffffffffffffLL); }
D4 fma4(D4 a, D4 b, D4 c) {
#if defined(__FMA__)
  return _mm256_fmadd_pd(a, b, c);
#else
  return D4{std::fma(a[0], b[0], c[0]), std::fma(a[1], b[1], c[1]), std::fma(a[2], b[2], c[2]), std::fma(a[3], b[3], c[3])};
#endif
}
D4 load4(const double* p) {
  D4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
void store4(double* p, D4 v) { std::memcpy(p, &v, sizeof v); }

/// D(q) = r2 - |q - o|^2 at four points of one row, positive inside the circle: the one formula
/// of every in-circle decision, so that a face and its neighbour decide alike (fused explicitly:
/// no contraction can differ).
template <typename Circle>
D4 power4(const Circle& c, D4 qx, double qy) {
  const D4 dx = qx - c.o.x();
  const double dy = qy - c.o.y();
  return c.r2 - fma4(dx, dx, D4{} + dy * dy);
}

/// Buffers of one piece of a raster row, each padded by a vector's lanes past its end.
struct PieceScratch {
  std::vector<double> weight, error;
  std::vector<double> numerator;  ///< channel c's sums at [c * stride, c * stride + n)
  std::vector<double> x;          ///< the piece's points' x, shifted
};

}  // namespace

SibsonRaster::SibsonRaster(const nn::Delaunay& dt, std::span<const Vec2> points, std::span<const double> values,
                           int channels, std::span<const std::pair<unsigned, unsigned>> hull)
    : values_(values), channels_(channels) {
  Vec2 lo = points.front(), hi = points.front();
  for (const Vec2& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  origin_ = 0.5 * (lo + hi);
  hull_margin_m_ = tol::kSibsonRasterHullMarginRelative * (hi - lo).maxCoeff();
  p_.reserve(points.size());
  for (const Vec2& p : points) p_.push_back(p - origin_);
  for (const auto& [a, b] : hull) hull_.emplace_back(p_[a], p_[b]);

  std::vector<nn::Delaunay::Face_handle> handles;
  handles.reserve(dt.number_of_faces());
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) handles.push_back(f);
  // Each face's circle and its extent in y, in CGAL's order.
  const size_t count = handles.size();
  std::vector<Circle> circles(count);
  std::vector<double> y_lo(count), y_hi(count);
  std::atomic<bool> unusable{false};
  parallel_for(0, static_cast<std::int64_t>(count), [&](std::int64_t index) {
    const size_t i = static_cast<size_t>(index);
    circles[i] = circumcircle(handles[i]);
    if (!std::isfinite(circles[i].r2) || !circles[i].o.allFinite()) unusable = true;
    const double r = std::sqrt(circles[i].r2);
    y_lo[i] = circles[i].o.y() - r * (1 + kSibsonRasterChordSlack);
    y_hi[i] = circles[i].o.y() + r * (1 + kSibsonRasterChordSlack);
  });
  // A face whose circle rounds to infinity (nearly flat): no point is served at all.
  usable_ = !unusable;
  if (!usable_) return;

  // The fixed order: by the circles' lowest y (then CGAL's order), circles far taller than
  // typical (slivers by the hull) apart, so that a row's search is a short range of the order.
  double tall_m = 0;
  {
    std::vector<double> diameters(count);
    for (size_t i = 0; i < count; ++i) diameters[i] = y_hi[i] - y_lo[i];
    std::nth_element(diameters.begin(), diameters.begin() + static_cast<std::ptrdiff_t>(count / 2), diameters.end());
    tall_m = kTallDiameters * diameters[count / 2];
  }
  std::vector<size_t> order, tall;
  for (size_t i = 0; i < count; ++i) {
    const double diameter = y_hi[i] - y_lo[i];
    if (diameter <= tall_m) order.push_back(i), reach_m_ = std::max(reach_m_, diameter);
    else tall.push_back(i);
  }
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return y_lo[a] < y_lo[b] || (y_lo[a] == y_lo[b] && a < b); });
  ordinary_ = order.size();
  order.insert(order.end(), tall.begin(), tall.end());
  y_lo_.reserve(ordinary_);
  for (size_t k = 0; k < ordinary_; ++k) y_lo_.push_back(y_lo[order[k]]);

  // The faces stored in that order, so that a row's faces are read in the order of memory
  // (made in CGAL's order, in which a face's neighbours lie near it).
  faces_.resize(count);
  parallel_for(0, static_cast<std::int64_t>(count), [&](std::int64_t k) {
    const size_t index = order[static_cast<size_t>(k)];
    const nn::Delaunay::Face_handle f = handles[index];
    Face& face = faces_[static_cast<size_t>(k)];
    for (int v = 0; v < 3; ++v) face.v[static_cast<size_t>(v)] = f->vertex(v)->info();
    face.circle = circles[index];
    face.y_lo = y_lo[index], face.y_hi = y_hi[index];
    const double r = std::sqrt(face.circle.r2);
    for (size_t e = 0; e < 3; ++e) {
      // CGAL's neighbour i lies across the edge opposite vertex i: edge (v[e], v[e+1]) is
      // opposite vertex e + 2.
      const nn::Delaunay::Face_handle n = f->neighbor(static_cast<int>(e + 2) % 3);
      if (dt.is_infinite(n)) {
        face.across[e] = Circle{};
        continue;
      }
      // Made again rather than looked up (a face's index from its handle would need a map of
      // them all): the same corners in the same order give the neighbour's own circle, bit for bit.
      const Circle c = circumcircle(n);
      face.across[e] = c;
      const Vec2 w = p_[face.v[e]] - p_[face.v[(e + 1) % 3]];
      const Vec2 g(w.y(), -w.x());
      face.half_c[e] = (face.circle.o - c.o).dot(g) / g.squaredNorm();
      // half_c's rounding: the circumcentres' (some 2^-53 of R^2 / |edge| for a sliver) over |g|.
      face.c_error[e] = std::abs(face.half_c[e]) +
                        (r + std::sqrt(c.r2) + face.circle.o.norm() + c.o.norm()) / g.norm() +
                        (face.circle.r2 + c.r2) / g.squaredNorm();
    }
  });
}

SibsonRaster::Circle SibsonRaster::circumcircle(const nn::Delaunay::Face_handle& f) const {
  const Vec2 a = p_[f->vertex(0)->info()], b = p_[f->vertex(1)->info()], c = p_[f->vertex(2)->info()];
  Circle out;
  out.o = a + nn::circumcentre_from(a, b, c);
  out.r2 = std::max({(a - out.o).squaredNorm(), (b - out.o).squaredNorm(), (c - out.o).squaredNorm()});
  return out;
}

std::pair<double, double> SibsonRaster::hull_span(double y) const {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& [a, b] : hull_) {
    if ((a.y() - y) * (b.y() - y) > 0) continue;  // wholly above or below
    if (a.y() == b.y()) {
      lo = std::min({lo, a.x(), b.x()}), hi = std::max({hi, a.x(), b.x()});
      continue;
    }
    const double x = a.x() + (y - a.y()) / (b.y() - a.y()) * (b.x() - a.x());
    lo = std::min(lo, x), hi = std::max(hi, x);
  }
  return {lo, hi};
}

void SibsonRaster::faces_near(double y0, double y1, std::vector<int>& out) const {
  out.clear();
  // A face of the order whose circle reaches y0 starts at most reach_m_ below it (twice that:
  // clear of the rounding of its diameter).
  const auto from = std::lower_bound(y_lo_.begin(), y_lo_.end(), y0 - 2 * reach_m_);
  const auto to = std::upper_bound(from, y_lo_.end(), y1);
  for (auto it = from; it != to; ++it) {
    const size_t i = static_cast<size_t>(it - y_lo_.begin());
    if (faces_[i].y_hi >= y0) out.push_back(static_cast<int>(i));
  }
  for (size_t i = ordinary_; i < faces_.size(); ++i)
    if (faces_[i].y_hi >= y0 && faces_[i].y_lo <= y1) out.push_back(static_cast<int>(i));
}

void SibsonRaster::evaluate(const Raster& raster, size_t first, size_t count, std::span<double> out,
                            std::vector<size_t>& unserved) const {
  const size_t C = static_cast<size_t>(channels_);
  RR_CHECK(out.size() == count * C, "output size does not match the raster points");
  RR_CHECK(raster.width > 0 && raster.height > 0, "raster size must be positive");
  RR_CHECK(first + count <= static_cast<size_t>(raster.width) * static_cast<size_t>(raster.height),
           "raster points out of range");
  unserved.clear();
  if (count == 0) return;
  const size_t width = static_cast<size_t>(raster.width);
  const size_t row0 = first / width, row1 = (first + count - 1) / width;  // rows [row0, row1]
  const double y0 = raster.y(row0) - origin_.y(), y1 = raster.y(row1) - origin_.y();
  std::vector<int> near;
  faces_near(std::min(y0, y1), std::max(y0, y1), near);
  const size_t rows = row1 - row0 + 1;
  const double sx = raster.dx(), sy = raster.dy();
  // Each row's faces, in the fixed order: those whose circles may reach it (a row more either
  // side; the power test decides).
  std::vector<std::vector<int>> row_faces(rows);
  for (const int fi : near) {
    const Face& f = faces_[static_cast<size_t>(fi)];
    const double a = std::floor((f.y_lo - y0) / sy) - 1, b = std::ceil((f.y_hi - y0) / sy) + 1;
    const size_t ra = a <= 0 ? 0 : static_cast<size_t>(std::min(a, static_cast<double>(rows)));
    const size_t rb = b < 0 ? 0 : static_cast<size_t>(std::min(b + 1, static_cast<double>(rows)));
    for (size_t r = ra; r < rb; ++r) row_faces[r].push_back(fi);
  }
  // The work in pieces of rows: whole rows, or, when there are fewer rows than the threads can
  // share (a raster wider than a call's points), pieces of at least kLeastPiecePoints points.
  struct Piece {
    size_t row;     ///< 0-based within the call
    size_t i0, i1;  ///< the row's points [i0, i1)
  };
  std::vector<Piece> pieces;
  const size_t threads = static_cast<size_t>(worker_thread_count());
  const size_t wanted = threads > 1 ? 2 * threads : 1;
  for (size_t r = 0; r < rows; ++r) {
    const size_t j = row0 + r;
    const size_t i0 = j == row0 ? first % width : 0;
    const size_t i1 = j == row1 ? (first + count - 1) % width + 1 : width;  // points [i0, i1) of row j
    const size_t split = std::clamp<size_t>((wanted + rows - 1) / rows, 1, std::max<size_t>((i1 - i0) / kLeastPiecePoints, 1));
    const size_t length = (i1 - i0 + split - 1) / split;
    for (size_t a = i0; a < i1; a += length) pieces.push_back({r, a, std::min(i1, a + length)});
  }
  std::vector<std::vector<size_t>> left(pieces.size());
  // Each row's points whose square of half-side hull_margin_m_ lies inside the hull: served, the
  // rest left; one x-interval (shifted coordinates), empty when lo >= hi.
  std::vector<std::pair<double, double>> inside(rows);
  for (size_t r = 0; r < rows; ++r) {
    const double qy = raster.y(row0 + r) - origin_.y(), m = hull_margin_m_;
    const auto [lo_a, hi_a] = hull_span(qy - m);
    const auto [lo_b, hi_b] = hull_span(qy + m);
    inside[r] = {std::max(lo_a, lo_b) + m, std::min(hi_a, hi_b) - m};
  }

  parallel_for_with_scratch<PieceScratch>(0, static_cast<std::int64_t>(pieces.size()), 1, 2, [&](std::int64_t k, PieceScratch& s) {
    const Piece& piece = pieces[static_cast<size_t>(k)];
    const size_t r = piece.row, j = row0 + r, i0 = piece.i0;
    const size_t n = piece.i1 - i0, offset = j * width + i0 - first;  // the piece's first point in `out`
    const double qy = raster.y(j) - origin_.y();
    const size_t stride = n + kLanes;  // padded: a chord's last four points may pass the piece's end
    s.x.resize(stride);
    for (size_t i = 0; i < n; ++i) s.x[i] = raster.x(i0 + i) - origin_.x();
    std::fill(s.x.begin() + static_cast<std::ptrdiff_t>(n), s.x.end(), s.x[n - 1]);
    s.weight.assign(stride, 0.0);
    s.error.assign(stride, 0.0);
    s.numerator.assign(stride * C, 0.0);
    const auto [inside_lo, inside_hi] = inside[r];
    size_t s0 = n, s1 = n;  // the served points [s0, s1)
    if (inside_lo < inside_hi) {
      s0 = static_cast<size_t>(std::upper_bound(s.x.begin(), s.x.begin() + static_cast<std::ptrdiff_t>(n), inside_lo) - s.x.begin());
      s1 = static_cast<size_t>(std::lower_bound(s.x.begin(), s.x.begin() + static_cast<std::ptrdiff_t>(n), inside_hi) - s.x.begin());
      s1 = std::max(s0, s1);
    }
    const D4 lane{0, 1, 2, 3};
    for (const int fi : row_faces[r]) {
      const Face& f = faces_[static_cast<size_t>(fi)];
      const double dy = qy - f.circle.o.y();
      // The piece's points within the circle's chord, widened beyond the power test's rounding
      // (a few units of 2^-53 of r2): that test decides, as it does for the faces around.
      const double h2 = f.circle.r2 - dy * dy;
      if (h2 < -kSibsonRasterChordSlack * f.circle.r2) continue;
      const double h = std::sqrt(std::max(h2, 0.0) + kSibsonRasterChordSlack * f.circle.r2);
      const double from_x = f.circle.o.x() - h, to_x = f.circle.o.x() + h;
      const double guess = std::floor((from_x - s.x[0]) / sx) - 1;  // the first point's index, about
      size_t begin = guess <= static_cast<double>(s0) ? s0 : static_cast<size_t>(std::min(guess, static_cast<double>(s1)));
      while (begin < s1 && s.x[begin] < from_x) ++begin;
      while (begin > s0 && s.x[begin - 1] >= from_x) --begin;
      size_t end = begin;  // the chord's served points [begin, end)
      while (end < s1 && s.x[end] <= to_x) ++end;
      if (begin == end) continue;
      // The face's corners, edges (v[e] to v[e+1]) and values, for each of its points below.
      const std::array<Vec2, 3> corner = {p_[f.v[0]], p_[f.v[1]], p_[f.v[2]]};
      const std::array<Vec2, 3> edge = {corner[1] - corner[0], corner[2] - corner[1], corner[0] - corner[2]};
      const std::array<double, 3> edge2 = {edge[0].squaredNorm(), edge[1].squaredNorm(), edge[2].squaredNorm()};
      const std::array<const double*, 3> value = {&values_[f.v[0] * C], &values_[f.v[1] * C], &values_[f.v[2] * C]};
      const double far_y2 = dy * dy;
      for (size_t i = begin; i < end; i += kLanes) {
        const D4 qx = load4(&s.x[i]);
        const D4 d = power4(f.circle, qx, qy);
        // Inside the circle and the chord.
        const M4 in = (d > 0) & (static_cast<double>(i) + lane < static_cast<double>(end));
        const D4 dx = qx - f.circle.o.x();
        const D4 far2 = f.circle.r2 + (dx * dx + far_y2);
        std::array<D4, 3> tx, ty, to2;  // corners less q, and their squared lengths
        for (size_t k = 0; k < 3; ++k) {
          tx[k] = corner[k].x() - qx;
          ty[k] = D4{} + (corner[k].y() - qy);
          to2[k] = tx[k] * tx[k] + ty[k] * ty[k];
        }
        std::array<D4, 3> share{};  // per corner: its stolen area's terms from this face
        D4 error{};
        for (size_t e = 0; e < 3; ++e) {
          const size_t ex = e, ey = e == 2 ? 0 : e + 1;
          const D4 px = tx[ey] * edge[e].x() + ty[ey] * edge[e].y();     // (y - q).(y - x)
          const D4 py = -(tx[ex] * edge[e].x() + ty[ex] * edge[e].y());  // (x - q).(x - y)
          const D4 half_sum2 = 0.5 * (to2[ex] + to2[ey]);
          const D4 scale = half_sum2 + edge2[e];  // >= |px|, |py|
          // (A face across that is infinite has no circle: r2 < 0, never inside.)
          const M4 across = power4(f.across[e], qx, qy) > 0;
          // Across the edge inside the zone: the constant; on the zone's boundary: D_T / k_xy.
          const D4 inverse = 1 / (tx[ex] * ty[ey] - ty[ex] * tx[ey]);
          const D4 ratio = d * inverse;
          const D4 coefficient = blend4(across, D4{} + f.half_c[e], ratio);
          share[ex] += coefficient * px, share[ey] += coefficient * py;
          error += blend4(across, f.c_error[e] * scale, (far2 + abs4(ratio) * half_sum2) * scale * abs4(inverse));
        }
        store4(&s.weight[i], load4(&s.weight[i]) + blend4(in, share[0] + share[1] + share[2], D4{}));
        store4(&s.error[i], load4(&s.error[i]) + blend4(in, error, D4{}));
        for (size_t c = 0; c < C; ++c) {
          double* sum = &s.numerator[c * stride + i];
          store4(sum, load4(sum) + blend4(in, share[0] * value[0][c] + share[1] * value[1][c] + share[2] * value[2][c], D4{}));
        }
      }
    }
    std::vector<size_t>& piece_left = left[static_cast<size_t>(k)];
    piece_left.clear();
    for (size_t i = 0; i < n; ++i) {
      const double w = s.weight[i];
      // Served: inside, a positive finite weight, and rounding far below it (NaN fails every
      // test). A point within rounding of a sample divides by a near-zero cross product: its
      // weight and error can both be infinite (their test then passes, and inf / inf was
      // written as NaN: an outside-in trial); it goes query by query.
      if (i < s0 || i >= s1 || !(w > 0) || !(w < std::numeric_limits<double>::infinity()) ||
          !(s.error[i] <= tol::kSibsonRasterCancellation * w)) {
        piece_left.push_back(offset + i);
        continue;
      }
      for (size_t c = 0; c < C; ++c) out[(offset + i) * C + c] = s.numerator[c * stride + i] / w;
    }
  });
  for (const auto& piece_left : left) unserved.insert(unserved.end(), piece_left.begin(), piece_left.end());
}

}  // namespace radrecon

#pragma GCC diagnostic pop
