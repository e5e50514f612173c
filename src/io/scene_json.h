#pragma once
// The JSON scene format (docs/formats.md):
//   {"name": ..., "surfaces": [{"name", "corners": [[x,y,z] x3 or x4], "reflectance": number|[r,g,b],
//     "emission": number|[r,g,b], "two_sided": bool, "mesh": {"max_divisions": int}}],
//    "cameras": [{"name", "eye", "target", "up", "fov_deg"}]}

#include <string>

#include "scene/scene.h"

namespace radrecon {

/// Parses and validates a JSON scene; `source` names it in error messages (UserError with the
/// line for invalid JSON, the field path otherwise). Warped, concave or corner-repeating quads are
/// made triangles by regularise_surfaces(), with a warning on stderr.
Scene parse_scene_json(const std::string& text, const std::string& source);

/// Reads and validates a scene: a built-in scene's name ("paper", "cornell") gives it, anything else is
/// read as a JSON scene file.
Scene load_scene(const std::string& file_or_builtin);

}  // namespace radrecon
