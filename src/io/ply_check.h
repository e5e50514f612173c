#pragma once
// A PLY file checked whole and rewritten as assimp 5.2 reads it right (used by
// io/assimp_import.cpp). assimp's reader takes liberties that hostile or merely unusual files
// turn into misreads: it reads a truncated file as a smaller model, an unknown element's name
// as its count, comment and obj_info lines as header lines, a property list after a comment
// as ended, a record over two lines or a number it cannot parse as the next value (a value
// became a list count of billions: found by fuzzing), and drops a binary file's first byte if it
// is a line feed. So radrecon reads the file itself and gives assimp a canonical copy.

#include <cstddef>
#include <string>
#include <vector>

#include "core/vec.h"

namespace radrecon {

/// What check_ply() gives assimp.
struct CheckedPly {
  /// The file rewritten: a header of `ply`, its format line, and its elements that assimp
  /// knows (vertex, face, tristrips, edge, material; others dropped with their data), with no
  /// comments; then their data: ASCII one record a line, each value written canonically
  /// (decimal integers, reals in their shortest round-trip form); binary copied byte for byte.
  std::string bytes;
  size_t faces = 0;  ///< the faces its header declares
  /// Each face's colour, in file order, where the face element has scalar `red`, `green` and
  /// `blue` properties (or `diffuse_red`...), which assimp 5.2 does not read: integers scaled by
  /// their type's largest value (255 for uchar), reals as they are. Empty otherwise.
  std::vector<Rgb> face_colours;
};

/// Reads the PLY file's header strictly and its data (ASCII or binary, either byte order)
/// record by record, each value a number of its property's type (ASCII: one record a line of
/// printable ASCII). Throws UserError naming the file (and the line, for a header or ASCII
/// data) if anything is malformed, out of its type's range, not finite, or cut short.
CheckedPly check_ply(const std::string& path);

}  // namespace radrecon
