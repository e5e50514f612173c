#pragma once
// The solution file format (docs/formats.md): JSON with per-surface elements and stats.

#include <filesystem>
#include <string>

#include "solver/solution.h"

namespace radrecon {

/// Writes the solution as JSON, atomically (streamed: reference solutions have 10^5+ elements).
void write_solution_json(const std::filesystem::path& path, const Solution& solution);

}  // namespace radrecon
