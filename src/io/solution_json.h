#pragma once
// The solution file format (docs/formats.md): JSON with per-surface elements and stats.

#include <filesystem>
#include <string>

#include "solver/solution.h"

namespace radrecon {

/// Writes the solution as JSON, atomically (streamed: reference solutions have 10^5+ elements).
void write_solution_json(const std::filesystem::path& path, const Solution& solution);

/// Reads a solution file written by write_solution_json(); a malformed file is refused with a
/// UserError naming the file and the field (or the line, for invalid JSON). Its "stats" are not
/// read into the solution (no command uses them, and a file whose statistics a tool rewrote, 408
/// shots as 408.0, must still draw): `stats_json`, if given, gets them as the file has them,
/// JSON text ("" if it has none), for the Python module to hand on unchanged.
Solution read_solution_json(const std::filesystem::path& path, std::string* stats_json = nullptr);

}  // namespace radrecon
