#pragma once
// Files of `radrecon interpolate`: scattered samples and query points in (CSV), interpolated
// values out (CSV, PFM, PNG), and the raster of query points given by --raster/--domain.
//
// CSV input rules (samples and queries):
//   - the first line that is neither blank nor a comment is the header; its first two column
//     names are x and y (case-insensitive);
//   - lines whose first non-blank character is '#' and blank lines are ignored anywhere;
//   - fields are separated by ',' with optional spaces or tabs around them; no quoting;
//     a trailing '\r' (Windows line ends) is ignored;
//   - every data row has as many fields as the header; numbers are decimal floating point
//     ("1", "-2.5", "3e-4", a leading '+' allowed) and must be finite (no nan, no inf).
// A violation throws UserError naming "FILE:LINE" and the column.

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/vec.h"
#include "reconstruct/samples.h"

namespace radrecon {

/// Reads scattered samples: columns x, y, then one or more value columns (channels = number of
/// value columns). The names of the value columns go to `*value_names` when it is not null.
/// Samples at exactly the same point (x and y equal as numbers) are merged into one, whose
/// values are the mean of theirs, in the place of the first of them; one warning line on stderr
/// says how many were merged. Throws UserError ("FILE:LINE: ...") for a missing file, a missing
/// or short header (fewer than 3 columns), a header not starting with x,y, an unnamed column, a
/// row with the wrong number of fields, a field that is not a finite number, or no data rows.
ScatteredSamples read_samples_csv(const std::string& path, std::vector<std::string>* value_names);

/// Merges samples at exactly the same point into one with the mean of their values, keeping
/// the order of first appearance. Returns the number of samples removed (0: no duplicates).
std::size_t merge_duplicate_points(ScatteredSamples& samples);

/// The samples as the nodes of a regular grid, if they are one: the distinct x values (values
/// within 1e-9 of the x extent of each other count as one) are nx >= 2 equally spaced values,
/// each within 1e-9 of the x extent from x0 + i (x1 - x0) / (nx - 1); the same for y; and every
/// (x, y) combination is present exactly once (nx * ny samples, in any order). The nodes are
/// returned row by row from y0 upward (GridNodes' layout) with the samples' channels.
std::optional<GridNodes> as_regular_grid(const ScatteredSamples& samples);

/// Distinct-coordinate counts reported when samples are not a grid (same 1e-9 rule).
struct DistinctCoordinates {
  std::size_t x = 0, y = 0;
};
DistinctCoordinates count_distinct_coordinates(const ScatteredSamples& samples);

/// Reads query points: a header whose first two columns are x, y; further columns are allowed
/// and ignored (their fields are not checked, but every row needs the header's field count).
std::vector<Vec2> read_queries_csv(const std::string& path);

/// A raster of query points: width x height cell centres of `domain`,
/// point (i, j) = (x0 + (i + 0.5) (x1 - x0) / width, y0 + (j + 0.5) (y1 - y0) / height),
/// in the order row by row, the y0 row first (index j * width + i).
struct Raster {
  int width = 0, height = 0;
  Rect domain{0, 0, 1, 1};
};

/// Largest width or height accepted by parse_raster_size.
inline constexpr int kMaxRasterSide = 20000;
/// At most this many raster points (W x H): 10^8 points need about 6 GB.
inline constexpr long long kMaxRasterPoints = 100'000'000;

/// Parses "WxH" (or "WXH"), 1 <= W, H <= kMaxRasterSide; throws UserError naming `option`.
void parse_raster_size(const std::string& text, const std::string& option, int& width, int& height);
/// Parses "x0,y0,x1,y1" (finite, x1 > x0, y1 > y0); throws UserError naming `option`.
Rect parse_domain(const std::string& text, const std::string& option);
/// The query points of a raster, in raster order.
std::vector<Vec2> raster_points(const Raster& raster);

enum class OutputFormat { csv, pfm, png };
/// The format named by the extension of `path` (.csv, .pfm, .png, any case); throws UserError
/// naming `option` for any other.
OutputFormat output_format_of(const std::string& path, const std::string& option);

/// Writes "x,y,NAME..." then one row per point, in the given order; numbers in their shortest
/// form that reads back to the same double, NaN as "nan" (and infinities as "inf", "-inf").
/// `values` is point-major, value_names.size() per point. Atomic: the file appears whole or not.
void write_values_csv(const std::string& path, std::span<const Vec2> points, std::span<const double> values,
                      const std::vector<std::string>& value_names);

/// Writes raster values (raster order, `channels` per point, channels 1 or 3, else UserError)
/// as a little-endian PFM: "Pf" (greyscale) for 1 channel, "PF" (colour) for 3. PFM stores the
/// bottom row of the picture first, and the picture shows y upward, so the file's first row is
/// the raster's y0 row and the values are written exactly in raster order, as 32-bit floats.
void write_values_pfm(const std::string& path, const Raster& raster, std::span<const double> values,
                      int channels);

/// Writes raster values as an 8-bit RGB PNG for looking at, y upward (the picture's top row is
/// the raster's last row, largest y). With exactly 3 channels the pixels are RGB, mapped with
/// one common [min, max] of the finite values of all three; otherwise greyscale from the first
/// channel's finite [min, max]. The mapping is linear, display = (v - min) / (max - min), then
/// sRGB-encoded; NaN and -inf show black, +inf white; if max == min every finite value is 0.5.
void write_values_png(const std::string& path, const Raster& raster, std::span<const double> values,
                      int channels);

}  // namespace radrecon
