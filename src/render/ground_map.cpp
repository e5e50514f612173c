#include "render/ground_map.h"

#include <algorithm>

#include "core/check.h"

namespace radrecon {

double difference_tone(double error_w_m2, double white_w_m2) {
  return std::clamp(0.5 + 2.0 * error_w_m2 / white_w_m2, 0.0, 1.0);
}

Image radiosity_map(std::span<const double> values, int width, int height, double white_w_m2) {
  RR_CHECK(values.size() == static_cast<size_t>(width) * height * 3, "map values do not match the size");
  RR_CHECK(white_w_m2 > 0, "white point must be positive");
  Image img(width, height);
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i)
      for (int c = 0; c < 3; ++c)
        img.at(i, height - 1 - j)[c] = tone_map(values[(static_cast<size_t>(j) * width + i) * 3 + c], white_w_m2);
  return img;
}

Image difference_map(std::span<const double> approx, std::span<const double> reference, int width,
                     int height, double white_w_m2) {
  RR_CHECK(approx.size() == reference.size() && approx.size() == static_cast<size_t>(width) * height * 3,
           "difference map values do not match the size");
  RR_CHECK(white_w_m2 > 0, "white point must be positive");
  Image img(width, height);
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i)
      for (int c = 0; c < 3; ++c) {
        size_t k = (static_cast<size_t>(j) * width + i) * 3 + c;
        img.at(i, height - 1 - j)[c] = difference_tone(approx[k] - reference[k], white_w_m2);
      }
  return img;
}

}  // namespace radrecon
