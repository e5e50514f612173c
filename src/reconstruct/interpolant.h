#pragma once
// The reconstruction interface: samples on a 2-D domain in, a function out, evaluated in batches
// (one virtual call per batch, none per point).

#include <span>

#include "core/vec.h"

namespace radrecon {

class Interpolant {
 public:
  virtual ~Interpolant() = default;

  /// Values per point.
  virtual int channels() const = 0;

  /// Writes the reconstructed values at `points` (metres) to `out`, point-major:
  /// out[k * channels() + c]. `out.size()` must be points.size() * channels(). A point where the
  /// method has no value (see each method's outside-the-domain rule) gets NaN.
  virtual void evaluate(std::span<const Vec2> points, std::span<double> out) const = 0;
};

}  // namespace radrecon
