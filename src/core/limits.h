#pragma once
// Resource limits (docs/hostile.md, "Limits"): how much one command may ask for. Each is checked
// before the work it bounds starts, and refused with a UserError (exit 2) that names the limit and
// the command-line option raising it. One process-wide table: the commands' --max-* options set
// it (cli/limit_options.cpp); everything else only reads it.

#include <string>

namespace radrecon {

enum class Limit {
  samples,        ///< scattered samples read from one file
  raster_points,  ///< points of an output raster (W x H)
  render_rays,    ///< rays of one rendering (W x H x rays per pixel)
  elements,       ///< elements of a grid mesh (grid:N)
  leaves,         ///< leaves asked of a quadtree (quadtree:LEAVES)
  links,          ///< links of a hierarchical solve
  file_bytes,     ///< bytes of one input file
};

struct LimitSpec {
  const char* option;       ///< the option that raises it, e.g. "--max-samples"
  const char* unit;         ///< what is counted, plural: "samples", "bytes"
  long long default_value;  ///< the limit unless raised
  const char* why;          ///< what the default stands for, for --help and the docs
};

/// Every limit, in the order of the enum.
inline constexpr Limit kAllLimits[] = {Limit::samples, Limit::raster_points, Limit::render_rays, Limit::elements,
                                       Limit::leaves,  Limit::links,         Limit::file_bytes};

const LimitSpec& limit_spec(Limit which);

/// The limit now in force (its default unless set_limit() raised or lowered it).
long long limit_value(Limit which);

/// Sets a limit for the rest of the process (the --max-* options); `value` >= 1.
void set_limit(Limit which, long long value);

/// Throws UserError(where, ...) when `amount` exceeds the limit: "<what> N <unit>, beyond the limit
/// of M; <advice>, or --max-x raises it". `what` ends in a verb ("'grid:64' makes", "holds").
void check_limit(Limit which, long long amount, const std::string& where, const std::string& what,
                 const std::string& advice = "");

/// Refuses an input file larger than the file_bytes limit (UserError naming the file); a path
/// that is no regular file (a pipe, a device, missing) is left to its reader.
void check_input_file_size(const std::string& path);

}  // namespace radrecon
