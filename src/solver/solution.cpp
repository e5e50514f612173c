#include "solver/solution.h"

namespace radrecon {

const SurfaceSolution* Solution::find(const std::string& name) const {
  for (const SurfaceSolution& s : surfaces)
    if (s.name == name) return &s;
  return nullptr;
}

}  // namespace radrecon
