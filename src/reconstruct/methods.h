#pragma once
// The closed set of reconstruction methods, by name.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "reconstruct/interpolant.h"
#include "reconstruct/samples.h"

namespace radrecon {

enum class Method { constant, bilinear };

/// The command-line name of a method ("constant", "bilinear", ...).
std::string method_name(Method m);
std::optional<Method> parse_method(const std::string& name);
/// Every method, in the order of the paper's tables.
std::vector<Method> all_methods();

/// The reconstruction of grid data (cell values) by `method`: constant uses the cells as they
/// are; bilinear works on nodal values (nodal_average()).
std::unique_ptr<Interpolant> make_grid_interpolant(Method method, const GridCells& cells);

}  // namespace radrecon
