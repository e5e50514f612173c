#pragma once
// Solutions for Python: the Solution class (a solve's or a file's, its sides as arrays, each side
// reconstructed as `radrecon render` reconstructs it), load_solution() and solve(). Defined into
// the module by radrecon_module.cpp. docs/python.md.

#include <pybind11/pybind11.h>

namespace radrecon::python {

/// Adds Solution, load_solution() and solve() to the module.
void bind_solutions(pybind11::module_& m);

}  // namespace radrecon::python
