#include "io/image_read.h"

#include <png.h>

#include <bit>
#include <cctype>
#include <cerrno>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>

#include "core/error.h"
#include "core/limits.h"
#include "core/parse.h"
#include "io/json_reader.h"
#include "io/openexr_io.h"

namespace radrecon {

namespace {

std::vector<unsigned char> read_bytes(const std::filesystem::path& path) {
  const std::string text = read_text_file(path.string(), "picture");  // chunked, under the file-size limit
  return std::vector<unsigned char>(text.begin(), text.end());
}

// --- PFM -----------------------------------------------------------------------------------

PictureValues read_pfm(const std::filesystem::path& path) {
  const std::string file = path.string();
  const std::vector<unsigned char> bytes = read_bytes(path);
  size_t pos = 0;
  // A header token: non-blank characters after blanks (at most 32 of them: a number's text).
  auto token = [&](const char* what) {
    while (pos < bytes.size() && std::isspace(bytes[pos])) ++pos;
    std::string t;
    while (pos < bytes.size() && !std::isspace(bytes[pos]) && t.size() < 32) t += static_cast<char>(bytes[pos++]);
    if (t.empty()) throw UserError(file, std::string("not a PFM file: the header ends before the ") + what);
    return t;
  };
  const std::string magic = token("format");
  if (magic != "PF" && magic != "Pf")
    throw UserError(file, "not a PFM file: it starts with " + in_quotes(magic.substr(0, 8)) + ", not PF or Pf");
  const std::string w_text = token("width"), h_text = token("height"), s_text = token("scale");
  const std::optional<long long> width = parse_integer(w_text), height = parse_integer(h_text);
  const std::optional<double> scale = parse_finite(s_text);
  if (!width || !height) throw UserError(file, "PFM header: the size " + in_quotes(w_text + " " + h_text) + " is not two whole numbers");
  if (!scale || *scale == 0) throw UserError(file, "PFM header: the scale " + in_quotes(s_text) + " is not a nonzero number");
  check_picture_size(*width, *height, file);
  if (pos >= bytes.size() || !std::isspace(bytes[pos])) throw UserError(file, "PFM header: no pixels after the scale");
  ++pos;  // the single blank that ends the header
  PictureValues p;
  p.format = FileFormat::pfm;
  p.width = static_cast<int>(*width);
  p.height = static_cast<int>(*height);
  p.channels = magic == "PF" ? 3 : 1;
  const size_t row_len = static_cast<size_t>(p.width) * p.channels;
  const size_t expected = row_len * p.height * 4, found = bytes.size() - pos;
  if (found != expected)
    throw UserError(file, "PFM: the header declares " + std::to_string(p.width) + " x " + std::to_string(p.height) +
                              " pixels of " + std::to_string(p.channels) + " channel(s), " + std::to_string(expected) +
                              " bytes, but the file holds " + std::to_string(found) +
                              (found < expected ? " (truncated)" : " (extra data)"));
  const bool little = *scale < 0;
  p.values.resize(row_len * p.height);
  for (int j = 0; j < p.height; ++j) {  // stored row j is the picture's row height - 1 - j
    const unsigned char* row = bytes.data() + pos + static_cast<size_t>(j) * row_len * 4;
    double* out = p.values.data() + static_cast<size_t>(p.height - 1 - j) * row_len;
    for (size_t k = 0; k < row_len; ++k) {
      const unsigned char* b = row + 4 * k;
      const std::uint32_t bits = little ? std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 |
                                              std::uint32_t(b[3]) << 24
                                        : std::uint32_t(b[3]) | std::uint32_t(b[2]) << 8 | std::uint32_t(b[1]) << 16 |
                                              std::uint32_t(b[0]) << 24;
      out[k] = std::bit_cast<float>(bits);
    }
  }
  return p;
}

// --- PNG -----------------------------------------------------------------------------------

/// libpng reports errors by longjmp: the message is kept here and the jump lands in
/// decode_png(), whose locals are all trivially destructible or created before the setjmp.
struct PngErrors {
  char message[256] = "";
  std::jmp_buf jump;
};

void png_error_handler(png_structp png, png_const_charp message) {
  auto* errors = static_cast<PngErrors*>(png_get_error_ptr(png));
  std::snprintf(errors->message, sizeof errors->message, "%s", message);
  std::longjmp(errors->jump, 1);
}
void png_warning_handler(png_structp, png_const_charp) {}

/// Decodes the PNG in `bytes` into `out` (8 or 16-bit samples, alpha stripped), `pixels` and
/// `rows` its buffers (owned by the caller, so that nothing here needs destroying after a
/// longjmp); returns false
/// with errors.message set when libpng refuses it.
bool decode_png(const std::vector<unsigned char>& bytes, PngErrors& errors, std::vector<unsigned char>& pixels,
                std::vector<png_bytep>& rows, PictureValues& out) {
  struct Reader {
    const std::vector<unsigned char>* bytes;
    size_t pos;
  } reader{&bytes, 0};
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &errors, png_error_handler, png_warning_handler);
  if (!png) throw std::bad_alloc();
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    throw std::bad_alloc();
  }
  if (setjmp(errors.jump)) {
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  png_set_read_fn(png, &reader, [](png_structp p, png_bytep data, png_size_t length) {
    auto* r = static_cast<Reader*>(png_get_io_ptr(p));
    if (r->bytes->size() - r->pos < length) png_error(p, "the file ends early (truncated)");
    std::memcpy(data, r->bytes->data() + r->pos, length);
    r->pos += length;
  });
  png_read_info(png, info);
  const png_uint_32 width = png_get_image_width(png, info), height = png_get_image_height(png, info);
  const int colour = png_get_color_type(png, info);
  if (width > static_cast<png_uint_32>(kMaxPictureSide) || height > static_cast<png_uint_32>(kMaxPictureSide) ||
      static_cast<long long>(width) * height > kMaxPicturePixels) {
    std::snprintf(errors.message, sizeof errors.message, "the picture is too large: %u x %u", width, height);
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  png_set_palette_to_rgb(png);            // palette: RGB
  png_set_expand_gray_1_2_4_to_8(png);    // 1, 2, 4-bit grey: 8-bit, scaled to 0..255
  png_set_strip_alpha(png);               // alpha and tRNS: dropped
  png_read_update_info(png, info);
  out.width = static_cast<int>(width);
  out.height = static_cast<int>(height);
  out.channels = (colour & PNG_COLOR_MASK_COLOR) ? 3 : 1;
  const int depth = png_get_bit_depth(png, info);
  const size_t row_bytes = png_get_rowbytes(png, info);
  if (static_cast<int>(png_get_channels(png, info)) != out.channels || (depth != 8 && depth != 16) ||
      row_bytes != static_cast<size_t>(width) * out.channels * (depth / 8)) {
    std::snprintf(errors.message, sizeof errors.message, "an unsupported pixel layout (%d channels of %d bits)",
                  static_cast<int>(png_get_channels(png, info)), depth);
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  pixels.resize(row_bytes * height);
  rows.resize(height);
  for (png_uint_32 y = 0; y < height; ++y) rows[y] = pixels.data() + y * row_bytes;
  png_read_image(png, rows.data());
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  const size_t count = static_cast<size_t>(width) * height * out.channels;
  out.values.resize(count);
  for (size_t k = 0; k < count; ++k)  // 16-bit samples are stored big-endian
    out.values[k] = depth == 8 ? pixels[k] / 255.0 : (pixels[2 * k] << 8 | pixels[2 * k + 1]) / 65535.0;
  return true;
}

PictureValues read_png_file(const std::filesystem::path& path) {
  const std::string file = path.string();
  const std::vector<unsigned char> bytes = read_bytes(path);
  if (bytes.size() < 8 || png_sig_cmp(bytes.data(), 0, 8) != 0) throw UserError(file, "not a PNG file (no PNG signature)");
  PngErrors errors;
  std::vector<unsigned char> pixels;
  std::vector<png_bytep> rows;
  PictureValues p;
  p.format = FileFormat::png;
  if (!decode_png(bytes, errors, pixels, rows, p))
    throw UserError(file, std::string("cannot read PNG: ") + errors.message);
  return p;
}

// --- OpenEXR -------------------------------------------------------------------------------

PictureValues read_exr(const std::filesystem::path& path) {
  const std::string file = path.string();
  {
    std::ifstream probe(path, std::ios::binary);
    if (!probe) throw UserError(file, std::string("cannot open: ") + std::strerror(errno));
  }
  check_input_file_size(file);
  return openexr_functions(file).read(path);
}

}  // namespace

PictureValues read_picture(const std::filesystem::path& path, const std::string& where) {
  switch (file_format(path.string(), {FileFormat::pfm, FileFormat::png, FileFormat::exr}, where)) {
    case FileFormat::pfm: return read_pfm(path);
    case FileFormat::png: return read_png_file(path);
    case FileFormat::exr: return read_exr(path);
    case FileFormat::csv: break;
  }
  throw UserError(where, "unsupported picture format");
}

}  // namespace radrecon
