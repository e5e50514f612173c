#include "reconstruct/keys_cubic.h"

namespace radrecon {

AxisWeights keys_weights(int n, int k, double t) {
  const double t2 = t * t, t3 = t2 * t;
  const double c0 = 0.5 * (-t + 2 * t2 - t3), c1 = 0.5 * (2 - 5 * t2 + 3 * t3), c2 = 0.5 * (t + 4 * t2 - 3 * t3),
               c3 = 0.5 * (t3 - t2);  // nodes k-1, k, k+1, k+2
  if (n == 2) return {0, 2, {c1 + 2 * c0 - c3, c2 - c0 + 2 * c3, 0, 0}};
  if (k == 0) return {0, 3, {c1 + 3 * c0, c2 - 3 * c0, c3 + c0, 0}};
  if (k == n - 2) return {k - 1, 3, {c0 + c3, c1 - 3 * c3, c2 + 3 * c3, 0}};
  return {k - 1, 4, {c0, c1, c2, c3}};
}

}  // namespace radrecon
