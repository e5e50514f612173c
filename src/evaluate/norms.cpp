#include "evaluate/norms.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/check.h"

namespace radrecon {

ErrorNorms error_norms(std::span<const double> approx, std::span<const double> reference) {
  RR_CHECK(approx.size() == reference.size() && !approx.empty(), "error norms need equal, non-empty inputs");
  ErrorNorms n;
  n.count = approx.size();
  // Sums in long double: 10^5..10^6 terms of similar size.
  long double sum_abs = 0, sum_sq = 0;
  double max_abs = 0;
  bool nan = false;
  for (size_t k = 0; k < approx.size(); ++k) {
    double e = approx[k] - reference[k];
    if (std::isnan(e)) nan = true;
    sum_abs += std::abs(e);
    sum_sq += static_cast<long double>(e) * e;
    max_abs = std::max(max_abs, std::abs(e));
  }
  if (nan) {
    double q = std::numeric_limits<double>::quiet_NaN();
    n.l1 = n.l2 = n.rmse = n.linf = q;
    return n;
  }
  n.l1 = static_cast<double>(sum_abs / n.count);
  n.l2 = static_cast<double>(sum_sq / n.count);
  n.rmse = std::sqrt(n.l2);
  n.linf = max_abs;
  return n;
}

}  // namespace radrecon
