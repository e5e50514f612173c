#pragma once
// Files of `radrecon interpolate`: scattered samples and query points in (CSV), interpolated
// values out (CSV). Rasters of query points and their files: raster.h.
//
// CSV input rules (samples and queries):
//   - the first line that is neither blank nor a comment is the header, unless all its fields
//     are numbers: then the file has no header, its columns are x, y, then z (one value) or
//     value1, value2, ... (nnbathy's and GMT's XYZ files);
//   - x and y are the columns --x and --y name (CsvColumns), else the first pair of x and y,
//     lon (long, lng) and lat, longitude and latitude, easting and northing, east and north
//     found in the header (case-insensitive; "lat,lon,elev" has its x second), else the first
//     two; the values are those --value names, else every other column;
//   - lines whose first non-blank character is '#' and blank lines are ignored anywhere; a UTF-8
//     byte order mark is skipped;
//   - fields are separated by ',' (with optional spaces or tabs around them) when the header line
//     has a comma, else by runs of spaces or tabs; a field in double quotes ("x", as R writes
//     headers) loses them (no commas or quotes inside); a trailing '\r' (Windows line ends) is
//     ignored;
//   - every data row has as many fields as the header; numbers are decimal floating point
//     ("1", "-2.5", "3e-4", a leading '+' allowed) and must be finite (no nan, no inf).
// A violation throws UserError naming "FILE:LINE" and the column.

#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/vec.h"
#include "reconstruct/barriers.h"
#include "reconstruct/samples.h"

namespace radrecon {

/// Reads scattered samples: columns x, y and one or more value columns (channels = number of
/// value columns). The names of the value columns go to `*value_names` when it is not null.
/// Samples at exactly the same point (x and y equal as numbers) are merged into one, whose
/// values are the mean of theirs, in the place of the first of them; one warning line on stderr
/// says how many were merged (merge_duplicate_points(), reconstruct/sample_set.h). Throws UserError ("FILE:LINE: ...") for a missing file, a missing
/// or short header (fewer than 3 columns), a column --x, --y or --value names that is not there, an unnamed column, a
/// row with the wrong number of fields, a field that is not a finite number, or no data rows.
/// Which columns hold x, y and the values (interpolate's --x, --y, --value); empty: the defaults
/// above. Names are matched case-insensitively.
struct CsvColumns {
  std::string x, y;
  std::vector<std::string> values;
};

/// Whether a column (or a vector source's field) that is not the coordinates' own is left out of
/// the default value columns (no --value): one named x or y, any case, whose values would be
/// written under the output's own x and y (a header "x,y,x,v", which radrecon refuses to read).
inline bool repeats_a_coordinate_name(std::string_view name) {
  return name.size() == 1 && (name[0] == 'x' || name[0] == 'X' || name[0] == 'y' || name[0] == 'Y');
}

/// Names of the x and y columns, in the order they are looked for when --x and --y name none
/// (lower case): a pair whose both names are in a table's header decides ("lat,lon,elev" has
/// its x second).
inline constexpr std::array<std::pair<std::string_view, std::string_view>, 7> kCoordinateNames = {{
    {"x", "y"}, {"lon", "lat"}, {"long", "lat"}, {"lng", "lat"}, {"longitude", "latitude"}, {"easting", "northing"},
    {"east", "north"}}};

/// Whether a vector source's field (lower case) is named as a coordinate (kCoordinateNames):
/// beside a point geometry it repeats the point (the columns a VRT makes its points of), and is
/// left out of the default value fields.
inline bool names_a_coordinate(std::string_view lower_name) {
  for (const auto& [x, y] : kCoordinateNames)
    if (lower_name == x || lower_name == y) return true;
  return false;
}

/// Samples to be merged that `barriers` part are refused (merge_duplicate_points()).
ScatteredSamples read_samples_csv(const std::string& path, std::vector<std::string>* value_names,
                                  const CsvColumns& columns = {}, const Barriers& barriers = {});

/// Reads query points: columns x and y as above; further columns are allowed and ignored (their
/// fields are not checked, but every row needs the header's field count).
std::vector<Vec2> read_queries_csv(const std::string& path, const CsvColumns& columns = {});

/// Writes "x,y,NAME..." then one row per point, in the given order; numbers in their shortest
/// form that reads back to the same double, NaN as "nan" (and infinities as "inf", "-inf").
/// `values` is point-major, value_names.size() per point. Atomic: the file appears whole or not.
void write_values_csv(const std::string& path, std::span<const Vec2> points, std::span<const double> values,
                      const std::vector<std::string>& value_names);

}  // namespace radrecon
