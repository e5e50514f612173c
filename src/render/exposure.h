#pragma once
// The white point of a rendered picture: the radiosity shown as white by the tone mapping of
// core/image.h. By default a high percentile of what the picture itself shows of its reflecting
// surfaces, so that a picture is well exposed whatever its lights: the lights (far brighter than
// anything they light) and the background do not count, and a few bright pixels (a hot spot under
// a lamp) may clip while the rest keeps its contrast.

#include <optional>
#include <vector>

#include "render/renderer.h"

namespace radrecon {

/// The percentile of the reflecting pixels' brightest channel that render's PNG shows as white
/// by default: 1% of them may clip.
inline constexpr double kDefaultWhitePercentile = 99.0;

/// The `percentile`-th percentile (in (0, 100], nearest rank: the smallest value that at least
/// that percentage of them do not exceed) of the brightest channel, W/m^2, of the pixels of
/// `rendering` marked reflecting; nullopt when no pixel is, or when that value is not positive
/// (a picture of unlit surfaces).
std::optional<double> percentile_white(const Rendering& rendering, double percentile);

/// The same percentile of `brightest` (each a value's brightest channel, W/m^2; reordered):
/// nullopt when it is empty or the percentile is not positive. The lightmaps' white
/// (radrecon export) is this over the texels of the sides that emit nothing.
std::optional<double> percentile_white(std::vector<double>& brightest, double percentile);

}  // namespace radrecon
