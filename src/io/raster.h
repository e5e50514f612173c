#pragma once
// Rasters of query points (the W x H cell centres of a rectangle) and their files: PFM with the
// raw values, PNG for looking at.

#include <span>
#include <string>
#include <vector>

#include "core/vec.h"
#include "io/image_io.h"
#include "reconstruct/interpolant.h"  // Raster, raster_points()
#include "reconstruct/samples.h"

namespace radrecon {

/// Largest width or height of a raster (parse_size(), core/parse.h).
inline constexpr int kMaxRasterSide = 20000;
/// The raster's points (W x H) are bounded by Limit::raster_points (core/limits.h).

/// Parses "x0,y0,x1,y1" (finite, x1 > x0, y1 > y0); throws UserError naming `where`.
Rect parse_domain(const std::string& text, const std::string& where);
/// Writes raster values (raster order, `channels` per point, channels 1 or 3) as a little-endian
/// PFM: "Pf" (greyscale) for 1 channel, "PF" (colour) for 3. PFM stores the
/// bottom row of the picture first, and the picture shows y upward, so the file's first row is
/// the raster's y0 row and the values are written exactly in raster order, as 32-bit floats.
/// The caller checks the channel count first (a broken check otherwise).
void write_raster_pfm(const std::string& path, const Raster& raster, std::span<const double> values,
                      int channels);
/// The same with the values made batch by batch, at most `batch_points` points at a time, by
/// `produce(first_value, out)` (image_io.h's write_pfm()), and written as they come.
void write_raster_pfm(const std::string& path, const Raster& raster, int channels, size_t batch_points,
                      const PfmValues& produce);

/// Writes raster values as an 8-bit RGB PNG for looking at, y upward (the picture's top row is
/// the raster's last row, largest y). With exactly 3 channels the pixels are RGB, mapped with
/// one common [min, max] of the finite values of all three; otherwise greyscale from the first
/// channel's finite [min, max]. The mapping is linear, display = (v - min) / (max - min), then
/// sRGB-encoded; NaN and -inf show black, +inf white; if max == min every finite value is 0.5.
void write_raster_png(const std::string& path, const Raster& raster, std::span<const double> values,
                      int channels);

}  // namespace radrecon
