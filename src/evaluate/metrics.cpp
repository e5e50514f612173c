#include "evaluate/metrics.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cmath>
#include <limits>
#include <vector>

#include "core/check.h"
#include "core/image.h"
#include "core/parallel.h"

namespace radrecon {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// SSIM's constants for display values in [0, 1] (L = 1): C1 = (0.01 L)^2, C2 = (0.03 L)^2.
constexpr double kSsimC1 = 0.01 * 0.01, kSsimC2 = 0.03 * 0.03;

/// The 1-D Gaussian of SSIM's window, normalised to sum 1; the 2-D window is its outer product
/// (exp(-(x^2 + y^2) / 2 sigma^2) factors, so normalising each factor normalises the product).
std::array<double, kSsimWindow> ssim_weights() {
  std::array<double, kSsimWindow> w{};
  double sum = 0;
  for (int k = 0; k < kSsimWindow; ++k) {
    const double x = k - kSsimWindow / 2;
    w[k] = std::exp(-x * x / (2 * kSsimSigma * kSsimSigma));
    sum += w[k];
  }
  for (double& v : w) v /= sum;
  return w;
}

bool any_nan(std::span<const double> v) {
  for (const double x : v)
    if (std::isnan(x)) return true;
  return false;
}

/// Whether every pixel of the interleaved image has all `channels` values equal (bitwise).
bool grey(std::span<const double> image, int channels) {
  if (channels < 2) return false;
  for (size_t k = 0; k < image.size(); k += static_cast<size_t>(channels))
    for (int c = 1; c < channels; ++c)
      if (!(image[k + c] == image[k])) return false;
  return true;
}

/// Per-thread buffers of ssim(): the five windowed column sums of one output row.
struct SsimScratch {
  std::vector<double> a, r, aa, rr, ar;
};

}  // namespace

std::optional<double> ssim(std::span<const double> a, std::span<const double> reference, ImageShape shape) {
  RR_CHECK(shape.width > 0 && shape.height > 0 && shape.channels > 0, "SSIM needs a non-empty image");
  RR_CHECK_EQ(a.size(), shape.size(), "SSIM: the image does not match its shape");
  RR_CHECK_EQ(reference.size(), shape.size(), "SSIM: the reference does not match its shape");
  if (shape.width < kSsimWindow || shape.height < kSsimWindow) return std::nullopt;
  if (any_nan(a) || any_nan(reference)) return kNaN;
  const std::array<double, kSsimWindow> w = ssim_weights();
  const int W = shape.width;
  // Grey images (every pixel's channels equal in both, as the paper scene's are): each channel
  // has the same index, so channel 0's is the mean.
  const int C = shape.channels, channels = grey(a, C) && grey(reference, C) ? 1 : C;
  const int out_w = W - kSsimWindow + 1, out_h = shape.height - kSsimWindow + 1;
  // One output row a task: the window's column sums (vertical pass) for all W columns, then the
  // horizontal pass; rows are independent, so each row's sum is the same on any thread, and
  // the rows are added in order afterwards.
  std::vector<double> row_sum(static_cast<size_t>(out_h) * channels);
  parallel_for_with_scratch<SsimScratch>(0, out_h, [&](std::int64_t j, SsimScratch& s) {
    s.a.assign(W, 0), s.r.assign(W, 0), s.aa.assign(W, 0), s.rr.assign(W, 0), s.ar.assign(W, 0);
    for (int c = 0; c < channels; ++c) {
      for (int i = 0; i < W; ++i) {
        double sa = 0, sr = 0, saa = 0, srr = 0, sar = 0;
        for (int k = 0; k < kSsimWindow; ++k) {
          const size_t at = ((static_cast<size_t>(j) + k) * W + i) * C + c;
          const double x = a[at], y = reference[at];
          sa += w[k] * x, sr += w[k] * y, saa += w[k] * x * x, srr += w[k] * y * y, sar += w[k] * x * y;
        }
        s.a[i] = sa, s.r[i] = sr, s.aa[i] = saa, s.rr[i] = srr, s.ar[i] = sar;
      }
      double sum = 0;
      for (int i = 0; i < out_w; ++i) {
        double mu_a = 0, mu_r = 0, e_aa = 0, e_rr = 0, e_ar = 0;
        for (int k = 0; k < kSsimWindow; ++k) {
          mu_a += w[k] * s.a[i + k], mu_r += w[k] * s.r[i + k];
          e_aa += w[k] * s.aa[i + k], e_rr += w[k] * s.rr[i + k], e_ar += w[k] * s.ar[i + k];
        }
        const double var_a = e_aa - mu_a * mu_a, var_r = e_rr - mu_r * mu_r, cov = e_ar - mu_a * mu_r;
        sum += (2 * mu_a * mu_r + kSsimC1) * (2 * cov + kSsimC2) /
               ((mu_a * mu_a + mu_r * mu_r + kSsimC1) * (var_a + var_r + kSsimC2));
      }
      row_sum[static_cast<size_t>(j) * channels + c] = sum;
    }
  });
  long double total = 0;
  for (const double v : row_sum) total += v;
  return static_cast<double>(total / (static_cast<long double>(out_w) * out_h * channels));
}

double gradient_l2(std::span<const double> a, std::span<const double> reference, ImageShape shape, double dx,
                   double dy) {
  RR_CHECK(shape.width > 0 && shape.height > 0 && shape.channels > 0, "gradient error needs a non-empty image");
  RR_CHECK_EQ(a.size(), shape.size(), "gradient error: the image does not match its shape");
  RR_CHECK_EQ(reference.size(), shape.size(), "gradient error: the reference does not match its shape");
  RR_CHECK(dx > 0 && dy > 0, "gradient error needs positive spacings");
  if (any_nan(a) || any_nan(reference)) return kNaN;
  const int W = shape.width, H = shape.height, C = shape.channels;
  auto at = [&](int i, int j, int c) { return (static_cast<size_t>(j) * W + i) * C + c; };
  // The derivative along one direction of channel c at index `mid`, from the values at `lo` and
  // `hi` (the neighbours, or the point itself at a border) `steps` spacings apart.
  auto diff = [&](std::span<const double> v, size_t lo, size_t hi, int steps, double h) {
    return steps == 0 ? 0.0 : (v[hi] - v[lo]) / (steps * h);
  };
  long double sum = 0;
  for (int j = 0; j < H; ++j) {
    const int j0 = std::max(j - 1, 0), j1 = std::min(j + 1, H - 1);
    for (int i = 0; i < W; ++i) {
      const int i0 = std::max(i - 1, 0), i1 = std::min(i + 1, W - 1);
      for (int c = 0; c < C; ++c) {
        const double gx = diff(a, at(i0, j, c), at(i1, j, c), i1 - i0, dx) -
                          diff(reference, at(i0, j, c), at(i1, j, c), i1 - i0, dx);
        const double gy = diff(a, at(i, j0, c), at(i, j1, c), j1 - j0, dy) -
                          diff(reference, at(i, j0, c), at(i, j1, c), j1 - j0, dy);
        sum += static_cast<long double>(gx) * gx + static_cast<long double>(gy) * gy;
      }
    }
  }
  return static_cast<double>(sum / shape.size());
}

std::vector<double> display_values(std::span<const double> values_w_m2, double white_w_m2) {
  RR_CHECK_GT(white_w_m2, 0.0, "display values need a positive white");
  // By runs of 3 (a pixel's channels): a value equal to the one before it in its run takes that
  // one's display value (the same bits in, the same out; a grey image needs a third of the sRGB
  // curve's pow()s).
  const size_t n = values_w_m2.size();
  std::vector<double> out(n);
  parallel_for(0, static_cast<std::int64_t>((n + 2) / 3), [&](std::int64_t run) {
    const size_t first = 3 * static_cast<size_t>(run), end = std::min(n, first + 3);
    for (size_t k = first; k < end; ++k) {
      const double v = values_w_m2[k];
      const bool same = k > first && std::bit_cast<std::uint64_t>(v) == std::bit_cast<std::uint64_t>(values_w_m2[k - 1]);
      out[k] = same ? out[k - 1] : std::isnan(v) ? kNaN : srgb_encode(tone_map(v, white_w_m2));
    }
  });
  return out;
}

nlohmann::json figures_json(const Figures& f) {
  auto number = [](std::optional<double> v) -> nlohmann::json {
    if (!v || !std::isfinite(*v)) return nullptr;
    return *v;
  };
  nlohmann::json j = nlohmann::json::object();
  j["L1"] = number(f.norms.l1);
  j["L2"] = number(f.norms.l2);
  j["RMSE"] = number(f.norms.rmse);
  j["Linf"] = number(f.norms.linf);
  j["SSIM"] = number(f.ssim);
  j["gradient_L2"] = number(f.gradient_l2);
  j["overshoot"] = number(f.overshoot);
  return j;
}

}  // namespace radrecon
