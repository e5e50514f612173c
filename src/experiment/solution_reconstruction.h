#pragma once
// A reconstruction of every surface side of a solution by one method, for the renderer.

#include <memory>
#include <string>
#include <vector>

#include "reconstruct/methods.h"
#include "scene/scene.h"
#include "solver/solution.h"

namespace radrecon {

class SolutionReconstruction {
 public:
  /// Grid sides are reconstructed as grid data (make_grid_interpolant), adaptive sides as
  /// scattered data: their leaves for constant, the leaf centres otherwise. A side the method
  /// cannot serve (a grid method on an adaptive side, too few or collinear samples) falls back
  /// to constant and is listed in fallbacks(). The solution's sides must belong to `scene`
  /// (UserError naming `source` otherwise).
  SolutionReconstruction(const Scene& scene, const Solution& solution, Method method, const MethodParams& params,
                         const std::string& source);
  ~SolutionReconstruction();

  /// The side's reconstruction (in its metric (s, t) coordinates), or null if the solution has
  /// no such side.
  const Interpolant* side(size_t surface, bool back_side) const;
  const std::vector<std::string>& fallbacks() const { return fallbacks_; }

 private:
  std::vector<std::unique_ptr<Interpolant>> sides_;  ///< 2 per surface: front, back
  std::vector<std::string> fallbacks_;
};

}  // namespace radrecon
