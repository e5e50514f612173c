#include "io/image_io.h"

#include <png.h>

#include <algorithm>
#include <array>
#include <csetjmp>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <limits>
#include <optional>
#include <vector>

#include "core/check.h"
#include "core/error.h"
#include "core/parse.h"
#include "core/float32_range.h"
#include "core/tolerances.h"
#include "io/atomic_file.h"
#include "io/openexr_io.h"
#include "io/plugin.h"

namespace radrecon {

namespace {
/// zlib's level for PNG figures (1 fastest .. 9 smallest).
constexpr int kPngCompressionLevel = 2;
}  // namespace

std::string extension_of(FileFormat format) {
  switch (format) {
    case FileFormat::csv: return ".csv";
    case FileFormat::pfm: return ".pfm";
    case FileFormat::png: return ".png";
    case FileFormat::exr: return ".exr";
  }
  return "";
}

FileFormat file_format(const std::string& path, std::initializer_list<FileFormat> allowed, const std::string& where) {
  const std::string ext = lower_extension(path);
  std::string names;
  for (FileFormat f : allowed) {
    if (ext == extension_of(f)) return f;
    names += (names.empty() ? "" : ", ") + extension_of(f);
  }
  throw UserError(where, (ext.empty() ? std::string("no file extension") : "unknown file extension " + in_quotes(ext)) +
                             " in '" + path + "'; expected " + names);
}

namespace {

/// The 8-bit sRGB code of a linear value in [0, 1], lround(255 srgb_encode(v)), by thresholds
/// rather than a power per value: code k from the least v whose encoding rounds to k (found by
/// bisection down to neighbouring doubles, so the codes are exactly the formula's), and a table
/// of 4096 buckets for where to start.
class SrgbCodes {
 public:
  SrgbCodes() {
    threshold_[0] = 0;
    for (int k = 1; k < 256; ++k) {
      const auto rounds_up = [k](double v) { return std::lround(255.0 * srgb_encode(v)) >= k; };
      double v = (k - 0.5) / 255.0;  // a guess, then exact by bisection over [0, 1]
      double lo = 0, hi = 1;
      (rounds_up(v) ? hi : lo) = v;
      while (std::nextafter(lo, 1.0) < hi) {
        const double mid = 0.5 * (lo + hi);
        (rounds_up(mid) ? hi : lo) = mid;
      }
      threshold_[k] = hi;
    }
    threshold_[256] = 2.0;  // beyond every value
    int code = 0;
    for (int b = 0; b < kBuckets; ++b) {
      while (threshold_[code + 1] <= static_cast<double>(b) / kBuckets) ++code;
      start_[b] = static_cast<std::uint8_t>(code);
    }
  }
  std::uint8_t operator()(double v) const {  // v in [0, 1]
    int code = start_[std::min(kBuckets - 1, static_cast<int>(v * kBuckets))];
    while (v >= threshold_[code + 1]) ++code;
    return static_cast<std::uint8_t>(code);
  }

 private:
  static constexpr int kBuckets = 4096;
  std::array<double, 257> threshold_;
  std::array<std::uint8_t, kBuckets> start_;
};

/// Display values as 8-bit RGB, row by row (write_png()'s conversion); with `white_w_m2`, the
/// image's values are radiosity, tone-mapped first (tone_map()).
std::vector<std::uint8_t> png_bytes(const Image& image, bool srgb_encode_values, std::optional<double> white_w_m2 = {}) {
  static const SrgbCodes srgb_codes;
  std::vector<std::uint8_t> bytes(static_cast<size_t>(image.width()) * image.height() * 3);
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x)
      for (int c = 0; c < 3; ++c) {
        const double display = white_w_m2 ? tone_map(image.at(x, y)[c], *white_w_m2) : image.at(x, y)[c];
        double v = std::clamp(display, 0.0, 1.0);
        if (std::isnan(v)) v = 0.0;
        bytes[(static_cast<size_t>(y) * image.width() + x) * 3 + c] =
            srgb_encode_values ? srgb_codes(v) : static_cast<std::uint8_t>(std::lround(v * 255.0));
      }
  return bytes;
}

/// Where encode_rgb8() collects libpng's output and its error message.
struct PngSink {
  std::vector<std::uint8_t>* bytes;
  char message[256] = "";
};

/// libpng's output into the sink; an allocation failure becomes libpng's error (raised outside
/// the handler: longjmp must not leave a catch block).
void append_to_sink(png_structp png, png_bytep data, size_t size) {
  auto* sink = static_cast<PngSink*>(png_get_io_ptr(png));
  bool failed = false;
  try {
    sink->bytes->insert(sink->bytes->end(), data, data + size);
  } catch (const std::bad_alloc&) {
    failed = true;
  }
  if (failed) png_error(png, "out of memory");
}
void flush_nothing(png_structp) {}
/// libpng's error message kept for the caller, then back to setjmp.
void keep_message(png_structp png, png_const_charp message) {
  auto* sink = static_cast<PngSink*>(png_get_error_ptr(png));
  std::snprintf(sink->message, sizeof sink->message, "%s", message);
  png_longjmp(png, 1);
}

/// 8-bit RGB rows as a PNG file (sRGB, zlib level kPngCompressionLevel with the Sub filter:
/// a fifth of the default's time for files 10-20% larger) into sink.bytes; false on a libpng
/// error, its message in sink.message. No C++ object lives in this frame across setjmp.
bool encode_rgb8(const std::uint8_t* rgb, int width, int height, PngSink& sink) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink, keep_message, nullptr);
  if (png == nullptr) return false;
  png_infop info = png_create_info_struct(png);
  if (info == nullptr) {
    png_destroy_write_struct(&png, nullptr);
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_set_write_fn(png, &sink, append_to_sink, flush_nothing);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8, PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  png_set_compression_level(png, kPngCompressionLevel);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
  png_write_info(png, info);
  for (int y = 0; y < height; ++y) png_write_row(png, rgb + static_cast<size_t>(y) * width * 3);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

void write_png(const std::filesystem::path& path, const Image& image, bool srgb_encode_values) {
  std::vector<std::uint8_t> encoded;
  try {
    encoded = encode_png(image, srgb_encode_values);
  } catch (const UserError& e) {
    const std::string reason = e.what();
    throw UserError(path.string(), "cannot write PNG: " + reason);
  }
  write_binary_file(path, encoded);
}

namespace {

std::vector<std::uint8_t> encode_rgb8_bytes(const std::vector<std::uint8_t>& bytes, const Image& image) {
  std::vector<std::uint8_t> encoded;
  encoded.reserve(bytes.size() / 4);
  PngSink sink{&encoded};
  if (!encode_rgb8(bytes.data(), image.width(), image.height(), sink)) {
    const std::string reason = sink.message[0] != 0 ? sink.message : "out of memory";
    throw UserError("PNG", "cannot encode: " + reason);
  }
  return encoded;
}

}  // namespace

std::vector<std::uint8_t> encode_png(const Image& image, bool srgb_encode_values) {
  return encode_rgb8_bytes(png_bytes(image, srgb_encode_values), image);
}

std::vector<std::uint8_t> encode_png_tone_mapped(const Image& linear_w_m2, double white_w_m2) {
  return encode_rgb8_bytes(png_bytes(linear_w_m2, true, white_w_m2), linear_w_m2);
}

namespace {
/// Values converted and written at a time by the PFM writers that hold their values already.
constexpr size_t kPfmBatchValues = size_t{1} << 16;
}  // namespace

void write_pfm(const std::filesystem::path& path, int width, int height, int channels,
               std::span<const double> values) {
  RR_CHECK_EQ(values.size(), static_cast<size_t>(width) * height * channels, "PFM values do not match the size");
  write_pfm(path, width, height, channels, std::min(values.size(), kPfmBatchValues), [&](size_t first, std::span<double> out) {
    std::copy_n(values.begin() + static_cast<std::ptrdiff_t>(first), out.size(), out.begin());
  });
}

void write_pfm(const std::filesystem::path& path, int width, int height, int channels, size_t batch_values,
               const PfmValues& produce, const std::string& underflow_advice) {
  RR_CHECK(channels == 1 || channels == 3, "PFM holds 1 or 3 channels");
  RR_CHECK(width > 0 && height > 0 && batch_values > 0, "a PFM needs pixels, made in batches of some");
  const size_t total = static_cast<size_t>(width) * height * channels;
  write_file_atomically(path, [&](const std::filesystem::path& tmp) {
    OutputFile out(tmp, path.string());
    // The scale -1.0 declares little-endian floats; they are swapped on a big-endian machine.
    out.write(std::string(channels == 1 ? "Pf" : "PF") + "\n" + std::to_string(width) + " " + std::to_string(height) +
              "\n-1.0\n");
    std::vector<double> values(std::min(batch_values, total));
    std::vector<std::uint32_t> bits(values.size());
    Float32Range range;
    for (size_t first = 0; first < total; first += values.size()) {
      const size_t count = std::min(values.size(), total - first);
      produce(first, std::span(values.data(), count));
      for (size_t k = 0; k < count; ++k) {
        const double v = values[k];
        if (std::isfinite(v) && std::abs(v) > std::numeric_limits<float>::max())
          throw UserError(path.string(), "a value, " + format_number(v) +
                                             ", is beyond the range of PFM's 32-bit floats (3.4e38); write .csv instead");
        range.add(v);
        std::uint32_t b = std::bit_cast<std::uint32_t>(static_cast<float>(v));
        if constexpr (std::endian::native == std::endian::big)
          b = (b >> 24) | ((b >> 8) & 0xff00u) | ((b << 8) & 0xff0000u) | (b << 24);
        bits[k] = b;
      }
      out.write(bits.data(), count * sizeof(std::uint32_t));  // a full disk shows now, not after all the rest
    }
    range.refuse_underflow(path.string(), underflow_advice);
    out.close();
  });
}

void write_pfm(const std::filesystem::path& path, const Image& image) {
  const int W = image.width(), H = image.height();
  // Straight from the image, batch by batch: no copy of it. PFM's row j is the picture's row
  // H - 1 - j.
  write_pfm(path, W, H, 3, std::min(static_cast<size_t>(W) * H * 3, kPfmBatchValues), [&](size_t first, std::span<double> out) {
    // The batch's first value's pixel and channel, then stepped along (a batch may begin
    // inside a pixel).
    const size_t pixel = first / 3;
    int c = static_cast<int>(first % 3), x = static_cast<int>(pixel % static_cast<size_t>(W));
    int j = static_cast<int>(pixel / static_cast<size_t>(W));
    for (double& value : out) {
      value = image.at(x, H - 1 - j)[c];
      if (++c == 3) {
        c = 0;
        if (++x == W) x = 0, ++j;
      }
    }
  }, kImageFloat32Advice);
}

const OpenExrFunctions& openexr_functions(const std::string& what) {
  static const PluginSpec kPlugin{"libradrecon_openexr.so", kOpenExrPluginEntry, "RADRECON_OPENEXR_PLUGIN",
                                  "OpenEXR support"};
  return *static_cast<const OpenExrFunctions*>(plugin_table(kPlugin, what));
}

void write_exr(const std::filesystem::path& path, const Image& image) {
  const OpenExrFunctions& exr = openexr_functions(path.string());
  write_file_atomically(path, [&](const std::filesystem::path& tmp) { exr.write(tmp, path.string(), image); });
}

}  // namespace radrecon
