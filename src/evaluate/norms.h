#pragma once
// Error norms of a reconstruction against reference values (the paper's sec. 2.3).

#include <span>

namespace radrecon {

/// Norms of e = approx - reference over all values (every point and channel), in W/m^2:
/// L1 = mean |e|, L2 = mean e^2 (the paper's "mean squared error", in (W/m^2)^2),
/// RMSE = sqrt(L2), Linf = max |e|.
struct ErrorNorms {
  double l1 = 0, l2 = 0, rmse = 0, linf = 0;
  size_t count = 0;
};

/// Both spans have the same size, at least 1; a NaN in `approx` makes every norm NaN.
ErrorNorms error_norms(std::span<const double> approx, std::span<const double> reference);

}  // namespace radrecon
