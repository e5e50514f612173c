#pragma once
// Reading pictures back: PFM, PNG and OpenEXR files into one in-memory form (the writers are in
// image_io.h). For comparing images (`radrecon compare`), not for editing them.

#include <filesystem>
#include <string>
#include <vector>

#include "core/error.h"
#include "io/image_io.h"

namespace radrecon {

/// A picture as read from a file: width x height pixels, `channels` values a pixel (1: grey,
/// 3: RGB), the top row of the picture first (value (y * width + x) * channels + c).
struct PictureValues {
  int width = 0, height = 0, channels = 0;
  std::vector<double> values;
  FileFormat format = FileFormat::pfm;
};

/// Largest width or height of a picture read, and largest pixel count: beyond them the file is
/// refused rather than read (a 20000 x 20000 3-channel picture takes 9.6 GB as doubles).
inline constexpr int kMaxPictureSide = 65536;
inline constexpr long long kMaxPicturePixels = 100'000'000;

/// Refuses a picture's declared size when it is not positive or beyond the limits.
inline void check_picture_size(long long width, long long height, const std::string& file) {
  if (width < 1 || height < 1)
    throw UserError(file, "the picture's size is " + std::to_string(width) + " x " + std::to_string(height) +
                              "; width and height must be at least 1");
  if (width > kMaxPictureSide || height > kMaxPictureSide || width * height > kMaxPicturePixels)
    throw UserError(file, "the picture is too large: " + std::to_string(width) + " x " + std::to_string(height) +
                              " (at most " + std::to_string(kMaxPictureSide) + " a side and " +
                              std::to_string(kMaxPicturePixels) + " pixels)");
}

/// Reads a picture, the format by the extension (file_format(): .pfm, .png, .exr; `where` names
/// the option or argument that gave the path):
///   - PFM: "PF" (RGB) or "Pf" (grey), either byte order (by the sign of the scale; its magnitude
///     is ignored), rows stored bottom-up as PFM does (turned top-first here); the file must
///     hold exactly the pixels its header declares.
///   - PNG: 8 or 16 bits (1, 2 and 4-bit grey and palettes expanded to 8), grey, grey + alpha,
///     RGB, RGBA or palette; values / 255 or / 65535 as stored: the sRGB curve (and any gAMA) is
///     NOT undone, so the values are display values. Alpha (and tRNS) is dropped: grey gives
///     1 channel, colour 3.
///   - OpenEXR: R, G, B (3 channels) or Y (1 channel), half, float or uint, over the data window;
///     other channels (A, ...) are ignored; a file with neither R, G, B nor Y is refused.
/// A missing, unreadable, truncated or malformed file is refused with a UserError naming the
/// file and what is wrong.
PictureValues read_picture(const std::filesystem::path& path, const std::string& where);

}  // namespace radrecon
