#include "io/raster.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/check.h"
#include "core/error.h"
#include "core/image.h"
#include "core/parse.h"
#include "core/tolerances.h"
#include "io/image_io.h"

namespace radrecon {

namespace {

void check_raster_values(const Raster& raster, std::span<const double> values, int channels) {
  RR_CHECK(channels >= 1 && values.size() == static_cast<size_t>(raster.width) * raster.height * channels,
           "raster values do not match the raster size");
}

}  // namespace

Rect parse_domain(const std::string& text, const std::string& where) {
  std::vector<std::string_view> f;
  split_fields(text, f);
  if (f.size() != 4) throw UserError(where, "expected x0,y0,x1,y1 (four numbers), got " + in_quotes(text));
  double v[4];
  static const char* const names[4] = {"x0", "y0", "x1", "y1"};
  for (int k = 0; k < 4; ++k) {
    if (parse_double(f[static_cast<size_t>(k)], v[k]) != NumberStatus::ok)
      throw UserError(where, std::string(names[k]) + ": expected a finite number, got " + in_quotes(f[static_cast<size_t>(k)]));
  }
  if (!(v[2] > v[0])) throw UserError(where, "x1 must be greater than x0, got " + in_quotes(text));
  if (!(v[3] > v[1])) throw UserError(where, "y1 must be greater than y0, got " + in_quotes(text));
  for (int k = 0; k < 4; ++k)
    if (std::abs(v[k]) > tol::kMaxSampleCoordinate)
      throw UserError(where, std::string(names[k]) + ": beyond the largest coordinate, " + format_number(tol::kMaxSampleCoordinate) + ", got " + in_quotes(text));
  return Rect{v[0], v[1], v[2], v[3]};
}

void write_raster_pfm(const std::string& path, const Raster& raster, std::span<const double> values, int channels) {
  // PFM's rows go bottom to top, raster rows y0 upward: the same order (write_pfm checks the
  // channels and the size).
  write_pfm(path, raster.width, raster.height, channels, values);
}

void write_raster_pfm(const std::string& path, const Raster& raster, int channels, size_t batch_points,
                      const PfmValues& produce) {
  write_pfm(path, raster.width, raster.height, channels, batch_points * static_cast<size_t>(channels), produce);
}

void write_raster_png(const std::string& path, const Raster& raster, std::span<const double> values, int channels) {
  check_raster_values(raster, values, channels);
  const bool rgb = channels == 3;
  const size_t ch = static_cast<size_t>(channels), shown = rgb ? 3 : 1;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (size_t k = 0; k < values.size(); k += ch)
    for (size_t c = 0; c < shown; ++c)
      if (std::isfinite(values[k + c])) {
        lo = std::min(lo, values[k + c]);
        hi = std::max(hi, values[k + c]);
      }
  const auto display = [&](double v) -> double {
    if (std::isnan(v)) return 0.0;
    if (std::isinf(v)) return v > 0 ? 1.0 : 0.0;
    if (!(hi - lo > tol::kPngFlatRangeRelative * std::max(std::abs(lo), std::abs(hi)))) return 0.5;
    return tone_map(v - lo, hi - lo);
  };
  Image img(raster.width, raster.height);
  for (int j = 0; j < raster.height; ++j)
    for (int i = 0; i < raster.width; ++i) {
      const size_t k = (static_cast<size_t>(j) * raster.width + i) * ch;
      Rgb& px = img.at(i, raster.height - 1 - j);
      if (rgb) px = Rgb(display(values[k]), display(values[k + 1]), display(values[k + 2]));
      else px = Rgb::Constant(display(values[k]));
    }
  write_png(path, img, true);
}

}  // namespace radrecon
