#include "reconstruct/methods.h"

#include "core/check.h"
#include "reconstruct/bilinear.h"
#include "reconstruct/constant.h"
#include "reconstruct/nodal.h"

namespace radrecon {

std::string method_name(Method m) {
  switch (m) {
    case Method::constant: return "constant";
    case Method::bilinear: return "bilinear";
  }
  return "?";
}

std::optional<Method> parse_method(const std::string& name) {
  for (Method m : all_methods())
    if (method_name(m) == name) return m;
  return std::nullopt;
}

std::vector<Method> all_methods() { return {Method::constant, Method::bilinear}; }

std::unique_ptr<Interpolant> make_grid_interpolant(Method method, const GridCells& cells) {
  switch (method) {
    case Method::constant: return std::make_unique<PiecewiseConstant>(to_cells(cells));
    case Method::bilinear: return std::make_unique<Bilinear>(nodal_average(cells));
  }
  RR_CHECK(false, "unknown method");
  return nullptr;
}

}  // namespace radrecon
