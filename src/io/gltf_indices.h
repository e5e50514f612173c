#pragma once
// The vertex indices of a glTF 2.0 file, checked before assimp reads it: assimp 5.2 drops a
// triangle with an index past its vertices without a word, and reads past the end of its
// vertices (a crash) for a line loop. (Used by io/gltf_extras.h.)

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "io/gltf_uri.h"

namespace radrecon {

/// Checks that every accessor fits its buffer view and every view its buffer (UserError naming
/// the accessor: assimp 5.2 refuses them too but leaks memory doing so), and that every index of
/// every primitive's indices accessor is below the count of its
/// POSITION accessor. `bin` is a .glb's BIN chunk (buffer 0 without a uri), `folder` the one the
/// file's relative buffer URIs are in. Buffers it cannot resolve (a missing file), accessors that
/// do not fit their buffer and sparse accessors are left to assimp, which refuses them.
/// UserError "PATH: meshes[i].primitives[j]: vertex index K out of range (N vertices)"; also for
/// a line loop of fewer than 2 indices, which assimp 5.2 reads past.
/// Every integer field it reads (and those assimp reads: a mesh's, a node's, a scene's) is first
/// held to the glTF 2.0 schema's bounds, naming the field ("accessors[1].byteOffset: must be an
/// integer >= 0 (the glTF schema), got -2"): assimp 5.2 reads a negative or fractional one as absent.
void check_gltf_indices(const nlohmann::json& doc, const std::string& bin, const std::string& folder, const std::string& path);

/// In `copy`, the document assimp is to read (checked by check_gltf_indices()), makes every buffer
/// view hold count x byteStride bytes of each strided accessor in it, as assimp 5.2 requires (the
/// spec asks for (count - 1) x byteStride + the element's size: a view whose last element is not
/// padded was refused, "count*stride 128 > maxSize 124"): the view takes the bytes after it in its
/// buffer, or, at the end of a .glb's BIN chunk (`bin`, when `binary`), zeros appended to it.
/// UserError naming the accessor and the view where neither can be (the end of another buffer).
/// Returns whether `copy` (or `bin`) changed.
bool pad_strided_views(nlohmann::json& copy, std::string& bin, bool binary, const std::string& path);

}  // namespace radrecon
