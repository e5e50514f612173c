#pragma once
// Images of a function over a surface patch: the radiosity map and the difference image of the
// paper's figures. Input values are sampled at the cell centres of a width x height grid over
// the patch, stored row by row from the patch's v = 0 edge upward, 3 channels per point; the
// image shows v = 1 at the top, so the patch appears as seen from its front with u to the right.

#include <span>

#include "core/image.h"

namespace radrecon {

/// The radiosity over the patch under tone_map() (core/image.h) with `white_w_m2` (> 0), the
/// radiosity shown as white; every image of a figure uses the same one. Encode with sRGB.
Image radiosity_map(std::span<const double> values, int width, int height, double white_w_m2);

/// The paper's difference image: display = clamp(0.5 + 2 (approx - reference) / white_w_m2, 0, 1),
/// written linearly (no sRGB curve), so zero is mid-grey (128), brighter is positive, and an
/// error of +-white/4 reaches white or black.
Image difference_map(std::span<const double> approx, std::span<const double> reference, int width,
                     int height, double white_w_m2);

/// Display value of an error under difference_map's mapping.
double difference_tone(double error_w_m2, double white_w_m2);

}  // namespace radrecon
