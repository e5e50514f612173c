#pragma once
// The reconstruction interface: samples on a 2-D domain in, a function out, evaluated in batches
// (one virtual call per batch, none per point).

#include <span>
#include <stdexcept>
#include <vector>

#include "core/vec.h"
#include "reconstruct/samples.h"

namespace radrecon {

/// Thrown by an interpolant's constructor when it cannot be built from its samples (too few,
/// duplicates, all on one line, a singular system). The message says why in plain words, naming
/// no file or option. The factories of methods.h catch it and return it as a Failure
/// (core/result.h): callers outside reconstruct/ never see the exception.
class ReconstructionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Query points per evaluate() call for callers that evaluate many (interpolate, the Python
/// module, the lightmaps): large enough that a batch keeps both threads busy, small enough that
/// its working set stays in cache and that a slow method (global shepard on 10^6 samples)
/// reports progress often.
/// Each point is evaluated on its own, so values do not depend on the batches.
inline constexpr size_t kEvaluateBatch = size_t{1} << 14;

/// The query points of a raster, in raster order.
std::vector<Vec2> raster_points(const Raster& raster);
/// Points [first, first + count) of raster_points(raster), into `out` (resized): a batch of a
/// large raster without the whole raster's points in memory.
void raster_points(const Raster& raster, size_t first, size_t count, std::vector<Vec2>& out);

class Interpolant {
 public:
  virtual ~Interpolant() = default;

  /// Values per point.
  virtual int channels() const = 0;

  /// Writes the reconstructed values at `points` (metres) to `out`, point-major:
  /// out[k * channels() + c]. `out.size()` must be points.size() * channels(). A point where the
  /// method has no value (see each method's outside-the-domain rule) gets NaN.
  virtual void evaluate(std::span<const Vec2> points, std::span<double> out) const = 0;

  /// evaluate() at the raster's points [first, first + count) (raster order, Raster::point()),
  /// into `out` (count * channels() values). By default it makes those points and calls
  /// evaluate(); a method with a faster way over a raster's rows overrides it, giving the same
  /// values up to round-off (natural-neighbour: sibson_raster.h). Values do not depend on the
  /// number of threads; a point on a Delaunay edge may take other last bits when the raster is
  /// cut into other calls (as with evaluate()'s batches).
  virtual void evaluate_raster(const Raster& raster, size_t first, size_t count, std::span<double> out) const;
};

}  // namespace radrecon
