#pragma once
// The JSON scene format (docs/formats.md):
//   {"name": ..., "surfaces": [{"name", "corners": [[x,y,z] x3 or x4], "reflectance": number|[r,g,b],
//     "emission": number|[r,g,b], "two_sided": bool, "mesh": {"max_divisions": int}}],
//    "meshes": [{"file", "scale", "translate", "rotate_x_deg", "reflectance", "emission", "two_sided",
//      "merge_triangles", "mesh": {"max_divisions"}}],
//    "cameras": [{"name", "eye", "target", "up", "fov_deg"}]}

#include <string>
#include <vector>

#include "scene/scene.h"

namespace radrecon {

/// Parses and validates a JSON scene; `source` names it in error messages (UserError with the
/// line for invalid JSON, the field path otherwise). Warped, concave or corner-repeating quads are
/// made triangles by regularise_surfaces(), with a warning on stderr. A "meshes" entry's "file" is
/// relative to the folder of `source` (io/mesh_import.h reads it); "surfaces" may then be absent.
Scene parse_scene_json(const std::string& text, const std::string& source);

/// A model file (.obj .gltf .glb .ply, io/mesh_import.h) as a whole scene, regularised and
/// validated; UserError if none of its faces emits (with the advice to add a light in a scene JSON).
Scene load_mesh_scene(const std::string& path);

/// Reads and validates a scene: a built-in scene's name ("paper", "cornell") gives it, a model file's
/// extension load_mesh_scene(), anything else is read as a JSON scene file.
Scene load_scene(const std::string& file_or_builtin);

/// The files load_scene(file_or_builtin) reads, for commands to refuse overwriting them before
/// any work (io/paths.h): none for a built-in scene; the file itself; a JSON scene's "meshes"
/// files; and beside each model file those it names: an OBJ's "mtllib" files, a .gltf's external
/// buffers. Best effort on files that do not parse (load_scene() then refuses them anyway).
std::vector<std::string> scene_input_files(const std::string& file_or_builtin);

/// Whether `name` names a built-in scene ('paper', 'cornell'), which load_scene() makes without a file.
bool is_builtin_scene(const std::string& name);

}  // namespace radrecon
