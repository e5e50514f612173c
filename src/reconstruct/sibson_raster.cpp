#include "reconstruct/sibson_raster.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include "core/check.h"
#include "core/parallel.h"
#include "core/tolerances.h"

namespace radrecon {

namespace {

using tol::kSibsonRasterChordSlack;

/// Faces whose circles are more than this many typical (median) diameters tall are searched
/// apart from the order by y (slivers by the hull), which is searched that far below a row.
constexpr double kTallDiameters = 8;

/// D(q) = r2 - |q - o|^2, positive inside the circle: the one formula of every in-circle
/// decision, so that a face and its neighbour decide alike (fma: no contraction can differ).
template <typename Circle>
double power(const Circle& c, double qx, double qy) {
  const double dx = qx - c.o.x(), dy = qy - c.o.y();
  return c.r2 - std::fma(dx, dx, dy * dy);
}

/// Buffers of one raster row.
struct RowScratch {
  std::vector<double> weight, error, numerator;
  std::vector<double> x;  ///< the row's points' x, shifted
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
  faces_.resize(handles.size());
  std::atomic<bool> unusable{false};
  parallel_for(0, static_cast<std::int64_t>(handles.size()), [&](std::int64_t index) {
    const nn::Delaunay::Face_handle f = handles[static_cast<size_t>(index)];
    Face& face = faces_[static_cast<size_t>(index)];
    for (int k = 0; k < 3; ++k) face.v[static_cast<size_t>(k)] = f->vertex(k)->info();
    face.circle = circumcircle(f);
    if (!std::isfinite(face.circle.r2) || !face.circle.o.allFinite()) unusable = true;
    const double r = std::sqrt(face.circle.r2);
    face.y_lo = face.circle.o.y() - r * (1 + kSibsonRasterChordSlack);
    face.y_hi = face.circle.o.y() + r * (1 + kSibsonRasterChordSlack);
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

  // A face whose circle rounds to infinity (nearly flat): no point is served at all.
  usable_ = !unusable;
  if (!usable_) return;
  // The fixed order: by the circles' lowest y (then index), circles far taller than typical
  // (slivers by the hull) apart, so that a row's search is a short range of the order.
  std::vector<double> diameters;
  diameters.reserve(faces_.size());
  for (const Face& f : faces_) diameters.push_back(f.y_hi - f.y_lo);
  std::nth_element(diameters.begin(), diameters.begin() + static_cast<std::ptrdiff_t>(diameters.size() / 2), diameters.end());
  tall_m_ = kTallDiameters * diameters[diameters.size() / 2];
  for (size_t i = 0; i < faces_.size(); ++i)
    (faces_[i].y_hi - faces_[i].y_lo <= tall_m_ ? by_y_lo_ : tall_).push_back(static_cast<int>(i));
  std::sort(by_y_lo_.begin(), by_y_lo_.end(), [&](int a, int b) {
    const double ya = faces_[static_cast<size_t>(a)].y_lo, yb = faces_[static_cast<size_t>(b)].y_lo;
    return ya < yb || (ya == yb && a < b);
  });
  y_lo_.reserve(by_y_lo_.size());
  for (const int i : by_y_lo_) y_lo_.push_back(faces_[static_cast<size_t>(i)].y_lo);
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
  // A face of the order whose circle reaches y0 starts at most tall_m_ below it (twice that:
  // clear of the rounding of its diameter).
  const auto from = std::lower_bound(y_lo_.begin(), y_lo_.end(), y0 - 2 * tall_m_);
  const auto to = std::upper_bound(from, y_lo_.end(), y1);
  for (auto it = from; it != to; ++it) {
    const int i = by_y_lo_[static_cast<size_t>(it - y_lo_.begin())];
    if (faces_[static_cast<size_t>(i)].y_hi >= y0) out.push_back(i);
  }
  for (const int i : tall_) {
    const Face& f = faces_[static_cast<size_t>(i)];
    if (f.y_hi >= y0 && f.y_lo <= y1) out.push_back(i);
  }
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
  std::vector<std::vector<size_t>> left(rows);
  const double m = hull_margin_m_;
  const double sx = (raster.domain.x1 - raster.domain.x0) / raster.width, sy = (raster.domain.y1 - raster.domain.y0) / raster.height;
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

  parallel_for_with_scratch<RowScratch>(0, static_cast<std::int64_t>(row1 - row0 + 1), 1, 2, [&](std::int64_t r, RowScratch& s) {
    const size_t j = row0 + static_cast<size_t>(r);
    const size_t i0 = j == row0 ? first % width : 0;
    const size_t i1 = j == row1 ? (first + count - 1) % width + 1 : width;  // points [i0, i1) of row j
    const size_t n = i1 - i0, offset = j * width + i0 - first;  // the row's first point in `out`
    const double qy = raster.y(j) - origin_.y();
    s.x.resize(n);
    for (size_t i = 0; i < n; ++i) s.x[i] = raster.x(i0 + i) - origin_.x();
    s.weight.assign(n, 0.0);
    s.error.assign(n, 0.0);
    s.numerator.assign(n * C, 0.0);
    // The points whose square of half-side m lies inside the hull: served, the rest left.
    const auto [lo_a, hi_a] = hull_span(qy - m);
    const auto [lo_b, hi_b] = hull_span(qy + m);
    const double inside_lo = std::max(lo_a, lo_b) + m, inside_hi = std::min(hi_a, hi_b) - m;
    size_t s0 = n, s1 = n;  // the served points [s0, s1)
    if (inside_lo < inside_hi) {
      s0 = static_cast<size_t>(std::upper_bound(s.x.begin(), s.x.end(), inside_lo) - s.x.begin());
      s1 = static_cast<size_t>(std::lower_bound(s.x.begin(), s.x.end(), inside_hi) - s.x.begin());
      s1 = std::max(s0, s1);
    }
    for (const int fi : row_faces[static_cast<size_t>(r)]) {
      const Face& f = faces_[static_cast<size_t>(fi)];
      const double dy = qy - f.circle.o.y();
      // The row's points within the circle's chord, widened beyond the power test's rounding
      // (a few units of 2^-53 of r2): that test decides, as it does for the faces around.
      const double h2 = f.circle.r2 - dy * dy;
      if (h2 < -kSibsonRasterChordSlack * f.circle.r2) continue;
      const double h = std::sqrt(std::max(h2, 0.0) + kSibsonRasterChordSlack * f.circle.r2);
      const double from_x = f.circle.o.x() - h, to_x = f.circle.o.x() + h;
      // The face's corners, edges (v[e] to v[e+1]) and values, for each of its points below.
      const std::array<Vec2, 3> corner = {p_[f.v[0]], p_[f.v[1]], p_[f.v[2]]};
      const std::array<Vec2, 3> edge = {corner[1] - corner[0], corner[2] - corner[1], corner[0] - corner[2]};
      const std::array<double, 3> edge2 = {edge[0].squaredNorm(), edge[1].squaredNorm(), edge[2].squaredNorm()};
      const std::array<const double*, 3> value = {&values_[f.v[0] * C], &values_[f.v[1] * C], &values_[f.v[2] * C]};
      const double guess = std::floor((from_x - s.x[0]) / sx) - 1;  // the first point's index, about
      size_t i = guess <= static_cast<double>(s0) ? s0 : static_cast<size_t>(std::min(guess, static_cast<double>(s1)));
      while (i < s1 && s.x[i] < from_x) ++i;
      while (i > s0 && s.x[i - 1] >= from_x) --i;
      for (; i < s1 && s.x[i] <= to_x; ++i) {
        const double qx = s.x[i];
        const double d = power(f.circle, qx, qy);
        if (!(d > 0)) continue;
        const Vec2 q(qx, qy);
        const double far2 = f.circle.r2 + (q - f.circle.o).squaredNorm();
        const std::array<Vec2, 3> to = {corner[0] - q, corner[1] - q, corner[2] - q};  // corners less q
        const std::array<double, 3> to2 = {to[0].squaredNorm(), to[1].squaredNorm(), to[2].squaredNorm()};
        std::array<double, 3> share{0, 0, 0};  // per corner: its stolen area's terms from this face
        double error = 0;
        for (size_t e = 0; e < 3; ++e) {
          const size_t ex = e, ey = e == 2 ? 0 : e + 1;
          const Vec2 &x = to[ex], &y = to[ey];
          const double px = y.dot(edge[e]), py = -x.dot(edge[e]);  // (y - q).(y - x), (x - q).(x - y)
          const double half_sum2 = 0.5 * (to2[ex] + to2[ey]);
          const double scale = half_sum2 + edge2[e];  // >= |px|, |py|
          if (f.across[e].r2 >= 0 && power(f.across[e], qx, qy) > 0) {
            share[ex] += f.half_c[e] * px, share[ey] += f.half_c[e] * py;
            error += f.c_error[e] * scale;
          } else {
            const double inverse = 1 / cross(x, y);
            const double ratio = d * inverse;
            share[ex] += ratio * px, share[ey] += ratio * py;
            error += (far2 + std::abs(ratio) * half_sum2) * scale * std::abs(inverse);
          }
        }
        const double weight = share[0] + share[1] + share[2];
        for (size_t c = 0; c < C; ++c)
          s.numerator[i * C + c] += share[0] * value[0][c] + share[1] * value[1][c] + share[2] * value[2][c];
        s.weight[i] += weight;
        s.error[i] += error;
      }
    }
    std::vector<size_t>& row_left = left[static_cast<size_t>(r)];
    row_left.clear();
    for (size_t i = 0; i < n; ++i) {
      const double w = s.weight[i];
      // Served: inside, a positive weight, and rounding far below it (NaN fails every test).
      if (i < s0 || i >= s1 || !(w > 0) || !(s.error[i] <= tol::kSibsonRasterCancellation * w)) {
        row_left.push_back(offset + i);
        continue;
      }
      for (size_t c = 0; c < C; ++c) out[(offset + i) * C + c] = s.numerator[i * C + c] / w;
    }
  });
  for (const auto& row_left : left) unserved.insert(unserved.end(), row_left.begin(), row_left.end());
}

}  // namespace radrecon
