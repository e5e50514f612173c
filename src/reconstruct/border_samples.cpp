#include "reconstruct/border_samples.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/QR>

#include "core/check.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/parse.h"
#include "core/tolerances.h"
#include "reconstruct/kdtree.h"
#include "reconstruct/sample_set.h"
#include "reconstruct/methods.h"

namespace radrecon {

namespace {

/// More added samples than this means a spacing far below the domain's size (a typo, or samples
/// crowded into a corner of a large domain): refused rather than filling memory.
constexpr double kMaxAddedSamples = 1e7;
/// The typical spacing looks for each sample's nearest other point among this many nearest.
constexpr int kSpacingNeighbours = 8;

/// The median distance from each sample to its nearest sample at another point (the lower
/// middle value of an even count); 0 when no sample has one among its kSpacingNeighbours nearest.
double typical_spacing(const KdTree2& tree, std::span<const Vec2> points) {
  const size_t n = points.size();
  if (n < 2) return 0;
  const int k = static_cast<int>(std::min<size_t>(n, kSpacingNeighbours));
  std::vector<double> nearest_sq(n, 0.0);
  struct Scratch {
    std::vector<unsigned> idx;
    std::vector<double> dist_sq;
  };
  parallel_for_with_scratch<Scratch>(0, static_cast<std::int64_t>(n), [&](std::int64_t i, Scratch& s) {
    s.idx.resize(static_cast<size_t>(k));
    s.dist_sq.resize(static_cast<size_t>(k));
    tree.nearest(points[static_cast<size_t>(i)], k, s.idx, s.dist_sq);
    double d = 0;
    for (int j = 0; j < k && d == 0; ++j) d = s.dist_sq[static_cast<size_t>(j)];
    nearest_sq[static_cast<size_t>(i)] = d;
  });
  std::erase(nearest_sq, 0.0);
  if (nearest_sq.empty()) return 0;
  const auto middle = nearest_sq.begin() + static_cast<std::ptrdiff_t>((nearest_sq.size() - 1) / 2);
  std::nth_element(nearest_sq.begin(), middle, nearest_sq.end());
  return std::sqrt(*middle);
}

/// Parts of at most h for a length L (>= 1; a whole number of spacings within
/// tol::kBorderSpacingRelative counts as whole). A double: the caller checks the total first.
double parts(double length, double h) {
  return std::max(1.0, std::ceil(length / h * (1 - tol::kBorderSpacingRelative)));
}

double distance_sq_to_segment(const Vec2& p, const BarrierSegment& s) {
  return (s.a + nearest_on_segment_t(p, s.a, s.b) * (s.b - s.a) - p).squaredNorm();
}

/// The part of segment s inside the closed rectangle (Liang-Barsky), as parameters t0 < t1 of
/// a + t (b - a); false when none of positive length is inside.
bool clip(const BarrierSegment& s, const Rect& r, double& t0, double& t1) {
  const Vec2 d = s.b - s.a;
  t0 = 0, t1 = 1;
  const double p[4] = {-d.x(), d.x(), -d.y(), d.y()};
  const double q[4] = {s.a.x() - r.x0, r.x1 - s.a.x(), s.a.y() - r.y0, r.y1 - s.a.y()};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0) {
      if (q[i] < 0) return false;  // parallel to this side and outside it
      continue;
    }
    const double t = q[i] / p[i];
    if (p[i] < 0) t0 = std::max(t0, t);
    else t1 = std::min(t1, t);
  }
  return t0 < t1;
}

bool inside(const Vec2& p, const Rect& r) { return p.x() >= r.x0 && p.x() <= r.x1 && p.y() >= r.y0 && p.y() <= r.y1; }

/// Per-thread buffers of the fits.
struct FitScratch {
  VisibleNeighbours visible;
  Eigen::Matrix<double, Eigen::Dynamic, 3> a;
  Eigen::MatrixXd b;
  Eigen::Vector3d x;
};

/// The value at p by the rule of border_samples.h into out[0, channels), and its plane's slope
/// into slope[0, 2 channels) (d/dx, d/dy per channel; 0 where the value is the nearest
/// sample's); false when p sees no interior sample.
bool fit_value(const Vec2& p, const ScatteredSamples& interior, const KdTree2& tree, const Barriers& barriers,
               size_t k, FitScratch& s, double* out, double* slope) {
  const int C = interior.channels;
  const size_t found = nearest_visible(tree, interior.points, barriers, p, k, s.visible);
  if (found == 0) return false;
  const std::vector<unsigned>& idx = s.visible.idx;
  const std::vector<double>& dist_sq = s.visible.dist_sq;
  const double* v0 = &interior.values[static_cast<size_t>(idx[0]) * C];
  for (int c = 0; c < C; ++c) out[c] = v0[c], slope[2 * c] = slope[2 * c + 1] = 0;
  if (found < 3) return true;
  // Collinear: every neighbour within tol::kFitCollinearRelative of the extent from the line
  // through the nearest and the one farthest from it.
  const Vec2 x0 = interior.points[idx[0]];
  size_t far = 0;
  double far_sq = 0;
  for (size_t j = 1; j < found; ++j) {
    const double d = (interior.points[idx[j]] - x0).squaredNorm();
    if (d > far_sq) far_sq = d, far = j;
  }
  if (far_sq == 0) return true;
  const double extent = std::sqrt(far_sq);
  const Vec2 u = (interior.points[idx[far]] - x0) / extent;
  double width = 0;
  for (size_t j = 1; j < found; ++j) {
    const Vec2 d = interior.points[idx[j]] - x0;
    width = std::max(width, std::abs(cross(u, d)));
  }
  if (width <= tol::kFitCollinearRelative * extent) return true;
  // Weighted least squares, rows scaled by sqrt(w_j) = d_0 / d_j (in (0, 1]) and coordinates
  // relative to p over the largest distance (in [-1, 1]): the plane's value at p is x(0).
  const Eigen::Index n = static_cast<Eigen::Index>(found);
  const double d0 = std::sqrt(dist_sq[0]), r = std::sqrt(dist_sq[found - 1]);
  s.a.resize(n, 3);
  s.b.resize(n, C);
  for (Eigen::Index j = 0; j < n; ++j) {
    const size_t i = idx[static_cast<size_t>(j)];
    const double w = d0 / std::sqrt(dist_sq[static_cast<size_t>(j)]);
    const Vec2 d = (interior.points[i] - p) / r;
    s.a(j, 0) = w;
    s.a(j, 1) = w * d.x();
    s.a(j, 2) = w * d.y();
    for (int c = 0; c < C; ++c) s.b(j, c) = w * (interior.values[i * C + c] - v0[c]);
  }
  // Channel by channel, so that a channel's arithmetic does not depend on how many there are
  // (Eigen solves several right-hand sides at once as a matrix product, summed in another order).
  const Eigen::HouseholderQR<Eigen::Matrix<double, Eigen::Dynamic, 3>> qr(s.a);
  for (int c = 0; c < C; ++c) {
    s.x = qr.solve(s.b.col(c));
    out[c] = v0[c] + s.x(0);
    slope[2 * c] = s.x(1) / r, slope[2 * c + 1] = s.x(2) / r;  // the plane in offsets over r
  }
  return true;
}

}  // namespace

double border_offset_m(const Rect& domain) {
  return tol::kBorderOffsetRelative * std::max(domain.x1 - domain.x0, domain.y1 - domain.y0);
}

Result<ScatteredSamples> with_border_samples(const ScatteredSamples& interior, const Rect& domain,
                                             const Barriers& barriers, const BorderSampleSettings& settings) {
  const size_t n = interior.points.size();
  const int C = interior.channels;
  RR_CHECK(C >= 1 && interior.values.size() == n * static_cast<size_t>(C), "sample values do not match the points");
  if (n == 0) return Failure{"no samples to extrapolate border samples from"};
  for (size_t i = 0; i < n; ++i) {
    const Vec2& p = interior.points[i];
    if (!p.allFinite() || p.cwiseAbs().maxCoeff() > tol::kMaxSampleCoordinate)
      return Failure{"sample " + std::to_string(i + 1) + ": coordinates must be finite numbers within " +
                     format_number(tol::kMaxSampleCoordinate)};
    for (int c = 0; c < C; ++c)
      if (!std::isfinite(interior.values[i * C + c]))
        return Failure{"sample " + std::to_string(i + 1) + " has a value that is not a finite number"};
  }
  const Vec2 corner0(domain.x0, domain.y0), corner1(domain.x1, domain.y1);
  if (!corner0.allFinite() || !corner1.allFinite() || corner0.cwiseAbs().maxCoeff() > tol::kMaxSampleCoordinate ||
      corner1.cwiseAbs().maxCoeff() > tol::kMaxSampleCoordinate)
    return Failure{"the domain's corners must be finite numbers within " + format_number(tol::kMaxSampleCoordinate)};
  if (!(domain.x0 < domain.x1 && domain.y0 < domain.y1))
    return Failure{"the domain [" + format_number(domain.x0) + ", " + format_number(domain.x1) + "] x [" +
                   format_number(domain.y0) + ", " + format_number(domain.y1) + "] has no area"};
  if (!(settings.spacing_m >= 0) || !std::isfinite(settings.spacing_m))
    return Failure{"the border sample spacing must be a finite number >= 0 (0: the samples' own), got " +
                   format_number(settings.spacing_m)};
  if (settings.fit_neighbours < 1)
    return Failure{"a border sample's fit needs at least 1 neighbour, got " + std::to_string(settings.fit_neighbours)};

  const KdTree2 tree(interior.points);
  const double width = domain.x1 - domain.x0, height = domain.y1 - domain.y0;
  const double delta = border_offset_m(domain), delta_sq = delta * delta;
  double h = settings.spacing_m;
  if (h == 0) h = typical_spacing(tree, interior.points);
  if (h == 0) h = std::max(width, height);

  // The clipped barrier segments and the sample count, checked before anything is placed.
  struct Clipped {
    Vec2 start, along, normal;  ///< clipped start; unit direction a -> b; its left normal
    double length;
    double positions;
  };
  std::vector<Clipped> clipped;
  const double mx = parts(width, h), my = parts(height, h);
  double total = 2 * (mx + my);
  for (const BarrierSegment& s : barriers.segments()) {
    if (!settings.beside_barriers) break;
    double t0 = 0, t1 = 1;
    if (!clip(s, domain, t0, t1)) continue;
    const Vec2 d = s.b - s.a;
    const Vec2 along = d.normalized();
    const Vec2 start = (s.a + t0 * d).cwiseMax(corner0).cwiseMin(corner1);
    const double length = (t1 - t0) * d.norm();
    const double positions = length > 2 * delta ? parts(length - 2 * delta, h) + 1 : 1;
    clipped.push_back({start, along, Vec2(-along.y(), along.x()), length, positions});
    total += 2 * positions;
  }
  if (!(total <= kMaxAddedSamples))
    return Failure{"a border sample spacing of " + format_number(h) + " m would place " + format_number(total) +
                   " samples (at most " + format_number(kMaxAddedSamples) + ")"};

  // Barrier segments that come within delta of the border: only these can drop a border sample.
  std::vector<size_t> near_border;
  for (size_t k = 0; k < barriers.segments().size(); ++k) {
    const BarrierSegment& s = barriers.segments()[k];
    const Vec2 lo = s.a.cwiseMin(s.b), hi = s.a.cwiseMax(s.b);
    const bool near_rect = hi.x() >= domain.x0 - delta && lo.x() <= domain.x1 + delta && hi.y() >= domain.y0 - delta &&
                           lo.y() <= domain.y1 + delta;
    const bool inside_strip = lo.x() > domain.x0 + delta && hi.x() < domain.x1 - delta && lo.y() > domain.y0 + delta &&
                              hi.y() < domain.y1 - delta;
    if (near_rect && !inside_strip) near_border.push_back(k);
  }

  // The candidates, without those outside the domain, too close to a barrier (border) or
  // hidden from their own segment (barrier), or at an interior sample.
  std::vector<Vec2> candidates;
  candidates.reserve(static_cast<size_t>(total));
  unsigned nearest_idx[1];
  double nearest_sq[1];
  const auto at_interior_sample = [&](const Vec2& p) {
    tree.nearest(p, 1, nearest_idx, nearest_sq);
    return nearest_sq[0] <= delta_sq;
  };
  const Vec2 corners[4] = {corner0, {domain.x1, domain.y0}, corner1, {domain.x0, domain.y1}};
  const double side_parts[4] = {mx, my, mx, my};
  for (int side = 0; side < (settings.on_domain_border ? 4 : 0); ++side) {
    const Vec2& from = corners[side];
    const Vec2& to = corners[(side + 1) % 4];
    const auto m = static_cast<std::int64_t>(side_parts[side]);
    for (std::int64_t i = 0; i < m; ++i) {
      // The border's own coordinate exactly (y0, x1, y1 or x0), the other one interpolated.
      Vec2 p = from + (to - from) * (static_cast<double>(i) / static_cast<double>(m));
      if (side % 2 == 0) p.y() = from.y();
      else p.x() = from.x();
      if (!inside(p, domain)) continue;
      bool near_barrier = false;
      for (size_t k : near_border) near_barrier = near_barrier || distance_sq_to_segment(p, barriers.segments()[k]) <= delta_sq;
      if (near_barrier || at_interior_sample(p)) continue;
      candidates.push_back(p);
    }
  }
  for (const Clipped& s : clipped) {
    const auto m = static_cast<std::int64_t>(s.positions);
    for (std::int64_t i = 0; i < m; ++i) {
      const double along = m == 1 ? 0.5 * s.length
                                  : delta + (s.length - 2 * delta) * (static_cast<double>(i) / static_cast<double>(m - 1));
      const Vec2 foot = s.start + along * s.along;
      for (const double sign : {1.0, -1.0}) {
        const Vec2 p = foot + sign * delta * s.normal;
        const Vec2 must_see = foot + sign * 0.5 * delta * s.normal;
        if (!inside(p, domain) || barriers.blocks(p, must_see) || at_interior_sample(p)) continue;
        candidates.push_back(p);
      }
    }
  }

  // Values, in parallel; then the candidates that see a sample, without those within delta of
  // an earlier one (a hash grid of delta cells: such a one is in the 3 x 3 cells around).
  const size_t k = std::min(n, static_cast<size_t>(settings.fit_neighbours));
  std::vector<double> values(candidates.size() * static_cast<size_t>(C)), slopes(2 * values.size());
  std::vector<char> has_value(candidates.size(), 0);
  parallel_for_with_scratch<FitScratch>(0, static_cast<std::int64_t>(candidates.size()), [&](std::int64_t i, FitScratch& s) {
    const size_t j = static_cast<size_t>(i);
    has_value[j] = fit_value(candidates[j], interior, tree, barriers, k, s, &values[j * C], &slopes[2 * j * C]);
  });
  ScatteredSamples out = interior;
  // The interior samples' slopes as given (unknown if not), then the border samples' planes'.
  if (out.slopes.size() != out.values.size() * 2) out.slopes.assign(out.values.size() * 2, std::numeric_limits<double>::quiet_NaN());
  const auto cell = [&](const Vec2& p) {
    return std::pair(static_cast<std::int64_t>(std::floor((p.x() - domain.x0) / delta)),
                     static_cast<std::int64_t>(std::floor((p.y() - domain.y0) / delta)));
  };
  const std::int64_t rows = static_cast<std::int64_t>(std::floor(height / delta)) + 3;
  std::unordered_map<std::int64_t, std::vector<size_t>> grid;  // cell -> indices into `out`
  for (size_t j = 0; j < candidates.size(); ++j) {
    if (!has_value[j]) continue;
    const Vec2& p = candidates[j];
    const auto [cx, cy] = cell(p);
    bool close = false;
    for (std::int64_t dx = -1; dx <= 1 && !close; ++dx)
      for (std::int64_t dy = -1; dy <= 1 && !close; ++dy) {
        const auto it = grid.find((cx + dx) * rows + cy + dy + 1);
        if (it == grid.end()) continue;
        for (size_t o : it->second) close = close || (out.points[o] - p).squaredNorm() <= delta_sq;
      }
    if (close) continue;
    grid[cx * rows + cy + 1].push_back(out.points.size());
    out.points.push_back(p);
    out.values.insert(out.values.end(), values.begin() + static_cast<std::ptrdiff_t>(j * C),
                      values.begin() + static_cast<std::ptrdiff_t>((j + 1) * C));
    out.slopes.insert(out.slopes.end(), slopes.begin() + static_cast<std::ptrdiff_t>(2 * j * C),
                      slopes.begin() + static_cast<std::ptrdiff_t>(2 * (j + 1) * C));
  }
  return out;
}

Result<size_t> add_border_samples(Method method, ScatteredSamples& samples, const std::optional<Rect>& domain,
                                  MethodParams& params) {
  if (const std::string problem = border_samples_problem(method); !problem.empty()) return Failure{problem};
  if (samples.points.empty()) return Failure{"no samples"};
  // The border of the rectangle holding the domain and every sample: a domain that cuts through
  // the samples (a raster's window) would put border samples among them, made-up values that
  // moved the real ones' interpolant (a window's cells differed from the whole raster's by 0.054
  // on data of range 2; an outside-in trial).
  const std::string apart = domain ? domain_apart(*domain, samples) : "";
  const Rect box = bounding_box(samples);
  Vec2 lo(box.x0, box.y0), hi(box.x1, box.y1);
  if (domain) lo = lo.cwiseMin(Vec2(domain->x0, domain->y0)), hi = hi.cwiseMax(Vec2(domain->x1, domain->y1));
  const Rect on{lo.x(), lo.y(), hi.x(), hi.y()};
  // The thin-plate spline takes none beside the barriers: past a barrier's free end a point sees
  // the two beside it, 2e-6 of the domain apart and of different values, and the spline through
  // both swung to -303..333 for data in [0, 1.04] (its system's reciprocal condition 1e-13).
  // Its fits over what each point sees keep influence from crossing a barrier without them. The
  // multiquadric of one radius r for every sample (a given `r`) does the same (-266..109 for data
  // in [-1, 2] at r = 0.1, -12..27 at r = 0.01; an outside-in trial); with its default radii,
  // Eck's, each sample's radius is its nearest neighbour's distance, and the two near ones are
  // cones of radius 2e-6 that disturb nothing beyond it (-1.002..2.015 on those data).
  BorderSampleSettings settings;
  settings.beside_barriers =
      method != Method::thin_plate && !(method == Method::multiquadric && params.multiquadric_r.has_value());
  Result<ScatteredSamples> bordered = with_border_samples(samples, on, params.barriers, settings);
  if (!bordered) return Failure{bordered.reason()};
  const size_t added = bordered.value().points.size() - samples.points.size();
  // A domain apart from every sample (another unit or CRS, a typo) still gets its border
  // samples, around both: say so, with how many (a 1 m domain 500 m from the samples took
  // 189,943 without a word: an outside-in trial).
  if (!apart.empty())
    warn(apart + ": the border samples go around both (" + std::to_string(added) + " added), and every value in the domain is "
         "extrapolated from them");
  samples = std::move(bordered).value();
  params.barrier_samples = false;  // added with the border's
  return added;
}

std::string reason_with_border_samples(const std::string& reason, size_t border_samples) {
  if (border_samples == 0) return reason;
  return reason + " (the samples counted include the " + std::to_string(border_samples) + " border samples added)";
}

}  // namespace radrecon
