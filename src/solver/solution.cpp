#include "solver/solution.h"

#include <algorithm>

namespace radrecon {

const SurfaceSolution* Solution::find(const std::string& name) const {
  for (const SurfaceSolution& s : surfaces)
    if (s.name == name) return &s;
  return nullptr;
}

NegativeRadiosity clamp_negative_radiosity(Solution& solution) {
  NegativeRadiosity found;
  for (SurfaceSolution& side : solution.surfaces)
    for (SolutionElement& e : side.elements)
      for (int c = 0; c < 3; ++c)
        if (double& b = e.radiosity_w_m2[c]; b < 0) {
          ++found.count;
          found.most_negative_w_m2 = std::min(found.most_negative_w_m2, b);
          b = 0;
        }
  return found;
}

}  // namespace radrecon
