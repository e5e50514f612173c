#pragma once
// OpenEXR reading and writing (Debian's libopenexr-dev) behind write_exr() (io/image_io.h) and
// read_picture() (io/image_read.h), built into the plugin libradrecon_openexr.so (io/plugin.h):
// OpenEXR's libraries are loaded only by a command that reads or writes an EXR file.

#include <filesystem>
#include <string>

#include "core/image.h"
#include "io/image_read.h"

namespace radrecon {

/// The plugin's table of functions.
struct OpenExrFunctions {
  /// Writes the image's linear RGB as 32-bit floats into `file`; a UserError naming `shown_as`
  /// if OpenEXR cannot, or a value lies beyond a float's range.
  void (*write)(const std::filesystem::path& file, const std::string& shown_as, const Image& image);
  /// Reads R, G, B (or Y) over the data window (read_picture()'s rules); a UserError naming
  /// `file` for anything it cannot read whole.
  PictureValues (*read)(const std::filesystem::path& file);
};

/// The name of the symbol the plugin exports: `const void* ()`, the address of its OpenExrFunctions.
inline constexpr const char* kOpenExrPluginEntry = "radrecon_openexr_functions";

/// The plugin's functions, loaded on first use (a UserError naming `what` if they cannot be).
const OpenExrFunctions& openexr_functions(const std::string& what);

}  // namespace radrecon
