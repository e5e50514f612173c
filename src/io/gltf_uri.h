#pragma once
// The files a glTF's relative URIs name: one rule for the reader (io/assimp_import.h) and for the
// list of a scene's input files that no output may overwrite (io/scene_json.h).

#include <string>
#include <string_view>

namespace radrecon {

/// A relative URI's percent-encoding decoded (RFC 3986: "my%20model.bin" names "my model.bin", as
/// Blender writes it); a '%' not followed by two hex digits is kept as it is.
std::string percent_decoded(std::string_view uri);

/// The file a glTF buffer's relative URI names in `folder`: its decoded name (percent_decoded()),
/// or the name as written where only such a file exists (assimp 5.2 opens that one).
std::string gltf_uri_file(const std::string& folder, const std::string& uri);

}  // namespace radrecon
