#pragma once
// Operations on a set of scattered samples before reconstruction: merging samples at the same
// point, and recognising samples that are the nodes of a regular grid.

#include <cstddef>
#include <optional>
#include <string>

#include "core/result.h"
#include "reconstruct/barriers.h"
#include "reconstruct/samples.h"

namespace radrecon {

/// Merges samples at the same point, or within tol::kNearDuplicateRelative (1e-9) of the
/// samples' extent of each other (groups joined transitively), into one at the mean of their
/// points (the point itself when they all share it) with the mean of their values, keeping the
/// order of first appearance. Returns the number of samples removed (0: none).
///
/// Two such samples on either side of one of `barriers` (the segment between them crosses it)
/// are a Failure naming both, the samples unchanged: merged, their mean would lie on the barrier
/// and be seen from both sides, carrying each side's value across it (an outside-in trial: 0
/// and 100 on either side of a wall 2e-10 apart gave 19.9 and 74.4 beside the wall). The
/// samples are named "samples 5 and 6 (in the order read)", counted from 1, or with an
/// `array_name`, as Python indexes it: "points[4] and points[5]".
Result<std::size_t> merge_duplicate_points(ScatteredSamples& samples, const Barriers& barriers = {},
                                           const std::string& array_name = {});

/// The warning that reports merge_duplicate_points()'s work (the same words wherever samples
/// come from).
std::string merged_samples_message(std::size_t removed, std::size_t before, std::size_t after);

/// "[x0, y0, x1, y1]", for messages.
std::string rect_text(const Rect& r);

/// The samples' bounding box; samples must not be empty.
Rect bounding_box(const ScatteredSamples& samples);

/// "the domain [...] does not meet the samples' bounding box [...]" when it does not (a domain in
/// another unit or CRS, columns swapped: every value then comes from extrapolation, or is NaN);
/// "" when it does, or when there are no samples.
std::string domain_apart(const Rect& domain, const ScatteredSamples& samples);

/// Warns (core/error.h warn()) when a raster's domain does not meet the samples' bounding box
/// (domain_apart()): every value there is extrapolated, or none. Without border samples, which
/// say it themselves with their count (add_border_samples()).
void warn_if_domain_apart(const Rect& domain, const ScatteredSamples& samples);

/// The samples as the nodes of a regular grid, if they are one: the distinct x values (values
/// within the x tolerance of each other count as one) are nx >= 2 equally spaced values,
/// each within the x tolerance from x0 + i (x1 - x0) / (nx - 1); the same for y; and every
/// (x, y) combination is present exactly once (nx * ny samples, in any order). The nodes are
/// returned row by row from y0 upward (GridNodes' layout) with the samples' channels. An axis's
/// tolerance: tol::kGridCoordinateRelative (1e-9) of its extent, or tol::kCoordinateRounding
/// (64 ulps) of its coordinates' magnitude when that is more.
std::optional<GridNodes> as_regular_grid(const ScatteredSamples& samples);

/// Distinct-coordinate counts reported when samples are not a grid (the same tolerance), and
/// how far the distinct values of each axis stray from equal spacing: the largest distance of one
/// from its place x0 + i (x1 - x0) / (nx - 1), as a fraction of the extent (0 for fewer than 2),
/// and each axis's tolerance as such a fraction.
struct DistinctCoordinates {
  std::size_t x = 0, y = 0;
  double x_uneven = 0, y_uneven = 0;
  double x_tolerance = 0, y_tolerance = 0;
};
DistinctCoordinates count_distinct_coordinates(const ScatteredSamples& samples);

}  // namespace radrecon
