#include "solver/solution.h"

#include <algorithm>

#include "core/tolerances.h"

namespace radrecon {

const SurfaceSolution* Solution::find(const std::string& name) const {
  for (const SurfaceSolution& s : surfaces)
    if (s.name == name) return &s;
  return nullptr;
}

std::vector<Vec2> SurfaceSolution::outline_st() const {
  if (triangle) return {Vec2(0, 0), Vec2(length_u_m, 0), Vec2(shear_m, length_v_m)};
  return {Vec2(0, 0), Vec2(length_u_m, 0), Vec2(length_u_m, length_v_m), Vec2(0, length_v_m)};
}

bool SurfaceSolution::contains_st(const Vec2& st) const {
  const Vec2 uv = frame().uv(st);  // a quad's unit square, a triangle's unit right triangle
  const double slack = tol::kOnBorderParameter;
  if (!(uv.x() >= -slack && uv.y() >= -slack)) return false;  // NaN: not on it
  return triangle ? uv.x() + uv.y() <= 1 + slack : uv.x() <= 1 + slack && uv.y() <= 1 + slack;
}

Vec2 SurfaceSolution::onto_side_st(const Vec2& st) const {
  Vec2 uv = frame().uv(st).cwiseMax(Vec2(0, 0)).cwiseMin(Vec2(1, 1));
  if (triangle && uv.x() + uv.y() > 1) uv -= Vec2::Constant(0.5 * (uv.x() + uv.y() - 1));
  return frame().st(uv.cwiseMax(Vec2(0, 0)));
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
