#pragma once
// Figures beyond the norms (norms.h), which see what the eye sees: SSIM of the displayed images,
// the error of the gradients (Mach bands, ringing), and overshoot past the samples' range; and
// the one home of their JSON keys (errors.json, `radrecon compare --json`).
//
// Images here are `width` x `height` points, row by row (point (i, j) at j * width + i), with
// `channels` values per point (index (j * width + i) * channels + c). Whether row 0 is the top or
// the bottom of the picture does not matter to any figure.

#include <nlohmann/json_fwd.hpp>

#include <optional>
#include <span>
#include <vector>

#include "core/vec.h"
#include "evaluate/norms.h"
#include "reconstruct/barriers.h"
#include "reconstruct/samples.h"

namespace radrecon {

/// The shape of an image: width x height points, `channels` values per point.
struct ImageShape {
  int width = 0, height = 0, channels = 1;
  size_t size() const { return static_cast<size_t>(width) * height * channels; }
};

/// SSIM's window: kSsimWindow x kSsimWindow points, Gaussian with standard deviation kSsimSigma
/// points (Wang, Bovik, Sheikh, Simoncelli 2004).
inline constexpr int kSsimWindow = 11;
inline constexpr double kSsimSigma = 1.5;

/// The mean structural similarity of `a` and `reference` (Wang et al. 2004, as their
/// ssim_index.m: no downsampling first, unlike their later ssim.m):
/// display values in [0, 1] (dynamic range L = 1, C1 = (0.01 L)^2, C2 = (0.03 L)^2), local means,
/// variances and covariance under the 11 x 11 Gaussian window (sigma 1.5, weights summing to 1),
///   SSIM(x) = (2 mu_a mu_r + C1)(2 sigma_ar + C2) / ((mu_a^2 + mu_r^2 + C1)(sigma_a^2 + sigma_r^2 + C2)),
/// averaged over the window positions lying wholly inside the image ("valid": (W - 10) x (H - 10)
/// of them), then over the channels. 1 for identical images; dimensionless, in [-1, 1].
/// Not defined (nullopt) for an image narrower or lower than the window (11 points): a clipped
/// window would be another measure. NaN when a value is NaN. Both spans hold shape.size() values.
std::optional<double> ssim(std::span<const double> a, std::span<const double> reference, ImageShape shape);

/// The error of the gradients: with finite-difference gradients g of each channel on the grid
/// (point spacing dx, dy: metres on a surface, 1 for a picture's pixels) -- central differences
/// inside, one-sided at the first and last point of a row or column, 0 along a direction with a
/// single point --
///   gradient_L2 = mean over points and channels of |g(a) - g(reference)|^2,
/// the mean squared error of the gradients (as L2 is of the values), in (value unit / m)^2, e.g.
/// (W/m^2/m)^2. NaN when a value is NaN. Both spans hold shape.size() values; dx, dy > 0.
double gradient_l2(std::span<const double> a, std::span<const double> reference, ImageShape shape, double dx,
                   double dy);

/// Overshoot: the largest amount by which a reconstruction leaves the range of the data samples
/// around each query point. For a point q inside the samples' convex hull or on it the range is
/// [min, max] of the values of q's natural neighbours (every sample with a nonzero Sibson
/// coordinate, NaturalNeighbour::coordinates(): on a hull edge its two ends); outside the hull, of
/// the two samples of the hull edge nearest to q (hull edges join consecutive samples along the
/// hull, collinear ones included) and the 3 samples nearest to q. With barriers, the natural
/// neighbours are those over the samples q sees (natural_neighbour.h), and the nearest sample q
/// sees with them (on the hull of what q sees they may leave it out); outside the hull of what q
/// sees, the nearest hull edge of all samples (its ends that q sees) and the 3 nearest samples
/// that q sees (a point that sees none has no range). Per channel:
///   overshoot = max over points and channels of max(0, a - max, min - a),
/// in the values' unit (W/m^2). 0 for a method that stays within its neighbours' range (any
/// convex combination of them).
///
/// The ranges depend on the samples and points only: neighbour_ranges() finds them once for
/// every method judged on the same data. Nullopt when the samples have no natural neighbours
/// (fewer than 3, all on one line, or a point repeated: NaturalNeighbour refuses them). Parallel,
/// and the same for any number of threads.
struct NeighbourRanges {
  int channels = 1;
  std::vector<double> lo, hi;  ///< points.size() * channels each, point-major
};
std::optional<NeighbourRanges> neighbour_ranges(const ScatteredSamples& samples, std::span<const Vec2> points,
                                                const Barriers& barriers = {});

/// The overshoot of `approx` (the ranges' points.size() * channels values, point-major); NaN when
/// a value is NaN at a point with a range (a point that sees no sample has none, and may have no
/// value).
double overshoot(const NeighbourRanges& ranges, std::span<const double> approx);

/// Both steps at once.
std::optional<double> overshoot(const ScatteredSamples& samples, std::span<const Vec2> points,
                                std::span<const double> approx);

/// Display values of radiosity, as the figures show them: sRGB-encoded tone_map(v, white_w_m2)
/// (core/image.h): clamp(v / white, 0, 1) through the sRGB curve; NaN stays NaN. SSIM's input
/// for images of W/m^2 values.
std::vector<double> display_values(std::span<const double> values_w_m2, double white_w_m2);

/// Every figure of a reconstruction against its reference; a figure not defined for the inputs
/// is nullopt.
struct Figures {
  ErrorNorms norms;
  std::optional<double> ssim, gradient_l2, overshoot;
};

/// The figures as one JSON object with the keys L1, L2, RMSE, Linf, SSIM, gradient_L2, overshoot
/// (errors.json and `radrecon compare --json`): numbers, null where not defined or NaN (JSON has
/// no NaN).
nlohmann::json figures_json(const Figures& figures);

}  // namespace radrecon
