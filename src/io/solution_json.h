#pragma once
// The solution file format (docs/formats.md): JSON with per-surface elements and stats.

#include <filesystem>
#include <string>

#include "solver/solution.h"

namespace radrecon {

/// Writes the solution as JSON, atomically (streamed: reference solutions have 10^5+ elements).
void write_solution_json(const std::filesystem::path& path, const Solution& solution);

/// Reads a solution file written by write_solution_json(); a malformed file is refused with a
/// UserError naming the file and the field (or the line, for invalid JSON).
Solution read_solution_json(const std::filesystem::path& path);

}  // namespace radrecon
