#include "scene/param_cell.h"

namespace radrecon {

const char* cell_shape_name(CellShape shape) {
  switch (shape) {
    case CellShape::box: return "box";
    case CellShape::lower: return "lower";
    case CellShape::upper: return "upper";
  }
  return "box";
}

std::optional<CellShape> parse_cell_shape(const std::string& name) {
  for (CellShape s : {CellShape::box, CellShape::lower, CellShape::upper})
    if (name == cell_shape_name(s)) return s;
  return std::nullopt;
}

std::array<Vec2, 4> ParamCell::vertices() const {
  switch (shape) {
    case CellShape::lower: return {Vec2(u0, v0), Vec2(u1, v0), Vec2(u0, v1), Vec2(u0, v1)};
    case CellShape::upper: return {Vec2(u1, v0), Vec2(u1, v1), Vec2(u0, v1), Vec2(u0, v1)};
    case CellShape::box: break;
  }
  return {Vec2(u0, v0), Vec2(u1, v0), Vec2(u1, v1), Vec2(u0, v1)};
}

Vec2 ParamCell::centroid() const {
  const auto v = vertices();
  if (!is_triangle()) return 0.5 * Vec2(u0 + u1, v0 + v1);
  return (v[0] + v[1] + v[2]) / 3.0;
}

std::array<ParamCell, 4> ParamCell::quarters() const {
  const double um = 0.5 * (u0 + u1), vm = 0.5 * (v0 + v1);
  using S = CellShape;
  switch (shape) {
    case S::box: return {{{u0, v0, um, vm, S::box}, {um, v0, u1, vm, S::box}, {u0, vm, um, v1, S::box}, {um, vm, u1, v1, S::box}}};
    case S::lower:
      return {{{u0, v0, um, vm, S::lower}, {um, v0, u1, vm, S::lower}, {u0, vm, um, v1, S::lower}, {u0, v0, um, vm, S::upper}}};
    case S::upper:
      return {{{um, v0, u1, vm, S::upper}, {um, vm, u1, v1, S::upper}, {u0, vm, um, v1, S::upper}, {um, vm, u1, v1, S::lower}}};
  }
  return {};
}

int ParamCell::quarter_of(double u, double v) const {
  const double um = 0.5 * (u0 + u1), vm = 0.5 * (v0 + v1);
  switch (shape) {
    case CellShape::box: return (u >= um ? 1 : 0) + (v >= vm ? 2 : 0);
    case CellShape::lower:
      if (u >= um) return 1;
      if (v >= vm) return 2;
      // In the box [u0,um] x [v0,vm]: its lower half is quarter 0, its upper half the middle.
      return (u - u0) / (um - u0) + (v - v0) / (vm - v0) < 1 ? 0 : 3;
    case CellShape::upper:
      if (u < um) return 2;
      if (v < vm) return 0;
      // In the box [um,u1] x [vm,v1]: its upper half is quarter 1, its lower half the middle.
      return (u - um) / (u1 - um) + (v - vm) / (v1 - vm) >= 1 ? 1 : 3;
  }
  return 0;
}

}  // namespace radrecon
