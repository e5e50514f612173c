#pragma once
// The rules a barrier line read from a file obeys, in one place: the GeoJSON reader
// (io/geojson.h) and the GDAL vector reader (io/gdal_vector.h, in the GDAL plugin, which links
// core alone) refuse the same lines in the same words, each naming where the line is in its own
// terms (a field path; a layer, feature and part).

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "core/vec.h"

namespace radrecon {

/// What a barrier line was read as: a LineString's points, or a Polygon ring's (which must close).
enum class BarrierLineKind { line_string, polygon_ring };

/// Why a barrier line cannot be used.
struct BarrierLineDefect {
  std::optional<size_t> point;  ///< the point at fault (from 0), or none: the line as a whole
  std::string what;             ///< e.g. "a Polygon ring must be closed: its last point ..."
};

/// The first defect of `line`, or none; `noun` names its points in the message ("position" in
/// GeoJSON, "point" elsewhere). In this order: a point repeating the one before it in x and y (a
/// segment of zero length, at the second of the two); a LineString of fewer than 2 points; a
/// Polygon ring of fewer than 4 (a closed triangle), or whose last point is not its first (GDAL
/// reads an unclosed ring with a warning only: as a line, it would leave the region open).
/// Coordinates are not checked here (each reader bounds them as it reads them), so a line
/// without defects passes Barriers::from_polylines() once they are finite.
std::optional<BarrierLineDefect> barrier_line_defect(std::span<const Vec2> line, BarrierLineKind kind,
                                                     std::string_view noun);

}  // namespace radrecon
