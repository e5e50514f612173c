#pragma once
// The one home of image and raster files: PNG (8-bit, for looking at), PFM (32-bit floats) and
// OpenEXR (32-bit floats), and the choice of a format by file extension. Every writer is
// atomic (atomic_file.h): the file appears whole or not at all.

#include <filesystem>
#include <functional>
#include <cstdint>
#include <initializer_list>
#include <span>
#include <string>
#include <vector>

#include "core/image.h"

namespace radrecon {

enum class FileFormat { csv, pfm, png, exr };

/// ".csv", ".pfm", ".png", ".exr".
std::string extension_of(FileFormat format);

/// The format named by the extension of `path` (any case), if it is one of `allowed`; else
/// UserError naming `where` (the option or field that gave the path) and the allowed ones.
FileFormat file_format(const std::string& path, std::initializer_list<FileFormat> allowed, const std::string& where);

/// Writes display values in [0,1] (clamped; NaN as 0) as an 8-bit RGB PNG. With
/// `srgb_encode_values` the values are taken as linear and encoded with the sRGB transfer curve;
/// without, written as they are.
void write_png(const std::filesystem::path& path, const Image& image, bool srgb_encode_values);

/// The PNG file write_png() would write, in memory (for embedding, e.g. in a glTF binary).
std::vector<std::uint8_t> encode_png(const Image& image, bool srgb_encode_values);

/// encode_png(tone_mapped(linear_w_m2, white_w_m2), true), byte for byte, without the display
/// image between (24 bytes a pixel: a lightmap atlas of 16384 x 16384 would need 6 GiB more).
std::vector<std::uint8_t> encode_png_tone_mapped(const Image& linear_w_m2, double white_w_m2);

/// Writes an image's linear values as a colour PFM (little endian, bottom row first as PFM
/// requires).
void write_pfm(const std::filesystem::path& path, const Image& image);

/// Writes `channels` (1: "Pf" greyscale, 3: "PF" colour) values per pixel as a little-endian
/// PFM, whatever the machine's byte order. `values_bottom_up` holds the rows in PFM's order, the
/// bottom row of the picture first, width * height * channels values.
void write_pfm(const std::filesystem::path& path, int width, int height, int channels,
               std::span<const double> values_bottom_up);

/// Produces values [first, first + out.size()) of a PFM in write_pfm()'s order into `out`.
using PfmValues = std::function<void(size_t first, std::span<double> out)>;

/// write_pfm() with the values made batch by batch, at most `batch_values` at a time, by
/// `produce`, and written as they come: a large raster never held whole (W3's 4,000,000 values
/// would take 32 MB, and each of their pages a fault). `produce` may throw; the file is then
/// not written (write_file_atomically()). Values too small for 32-bit floats are refused
/// (Float32Range, core/float32_range.h) with `underflow_advice`.
void write_pfm(const std::filesystem::path& path, int width, int height, int channels, size_t batch_values,
               const PfmValues& produce, const std::string& underflow_advice = "write .csv instead, or scale the values");

/// Writes an image's linear values as OpenEXR (RGB, 32-bit floats).
void write_exr(const std::filesystem::path& path, const Image& image);

}  // namespace radrecon
