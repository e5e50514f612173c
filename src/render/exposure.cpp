#include "render/exposure.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/check.h"

namespace radrecon {

std::optional<double> percentile_white(const Rendering& rendering, double percentile) {
  RR_CHECK(percentile > 0 && percentile <= 100, "a percentile is in (0, 100]");
  const Image& img = rendering.image;
  RR_CHECK_EQ(rendering.reflecting.size(), static_cast<size_t>(img.width()) * img.height(), "mask size");
  std::vector<double> brightest;  // reserved exactly: 8 bytes a reflecting pixel, no more
  const auto& mask = rendering.reflecting;
  brightest.reserve(static_cast<size_t>(std::count_if(mask.begin(), mask.end(), [](std::uint8_t r) { return r != 0; })));
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x)
      if (mask[static_cast<size_t>(y) * img.width() + x]) brightest.push_back(img.at(x, y).maxCoeff());
  return percentile_white(brightest, percentile);
}

std::optional<double> percentile_white(std::vector<double>& brightest, double percentile) {
  RR_CHECK(percentile > 0 && percentile <= 100, "a percentile is in (0, 100]");
  if (brightest.empty()) return std::nullopt;
  // Nearest rank: the k-th smallest of n, k = ceil(p n / 100), 1 <= k <= n (p n is exact for a
  // whole p, so that k is the exact rank whenever p n / 100 is whole).
  const double n = static_cast<double>(brightest.size());
  const auto rank = static_cast<size_t>(std::clamp(std::ceil(percentile * n / 100), 1.0, n));
  const auto kth = brightest.begin() + static_cast<std::ptrdiff_t>(rank - 1);
  std::nth_element(brightest.begin(), kth, brightest.end());
  if (!(*kth > 0)) return std::nullopt;
  return *kth;
}

}  // namespace radrecon
