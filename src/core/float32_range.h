#pragma once
// What 32-bit floats (PFM, OpenEXR, a float32 GDAL band) cannot hold of a file's values, found
// before it is written: one home for every writer of float32 values.

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"
#include "core/parse.h"

namespace radrecon {

/// The largest finite magnitude of values about to be stored as 32-bit floats, gathered as they
/// are made, and the refusal of those a float holds as zeros or coarse steps.
struct Float32Range {
  double largest = 0;  ///< the largest finite |value| seen

  void add(double v) {
    if (std::isfinite(v)) largest = std::max(largest, std::abs(v));
  }

  /// Refuses (UserError naming `where`) values whose largest magnitude is positive and below
  /// FLT_MIN (1.2e-38): then every value is a subnormal float, whose spacing (1.4e-45) is coarser
  /// than a float's relative precision at the largest value, and below 1.4e-45 every value is 0
  /// (an outside-in trial: values of 1e-50 written as a raster of zeros, exit 0). At FLT_MIN and
  /// above, every value keeps its error within FLT_EPSILON of the largest. `advice`: what to do
  /// instead.
  void refuse_underflow(const std::string& where, const std::string& advice) const {
    constexpr double kLeast = std::numeric_limits<float>::min();
    if (!(largest > 0 && largest < kLeast)) return;
    throw UserError(where, "the values' largest magnitude, " + format_number(largest) +
                               ", is below a 32-bit float's normal range (1.2e-38), where the values lose their "
                               "precision (and below 1.4e-45 are 0); " + advice);
  }
};

/// What an image of radiances too small for 32-bit floats is to do (PFM and OpenEXR alike).
inline constexpr const char* kImageFloat32Advice = "scale the scene's emission (PFM and OpenEXR hold 32-bit floats)";

}  // namespace radrecon
