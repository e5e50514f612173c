#pragma once
// The one JSON reader of radrecon's file formats (scenes, solutions): typed access to a parsed
// document whose errors name the file, and the line (invalid JSON) or the field path
// ("scene.json: surfaces[2].corners[1]: must be an array of 3 numbers").

#include <initializer_list>
#include <string>

#include <nlohmann/json.hpp>

#include "core/vec.h"

namespace radrecon {

/// The whole content of a file; UserError naming it (with `what`, e.g. "scene file") if it
/// cannot be read.
std::string read_text_file(const std::string& path, const std::string& what);

/// UserError naming `path` unless it is a regular file that can be opened, saying why: a folder,
/// no such file (the system's reason), a pipe or a device. `what`: e.g. "mesh file".
void require_regular_file(const std::string& path, const std::string& what);

/// Deepest nesting of arrays and objects in a JSON document read: none of radrecon's formats, nor
/// glTF, comes near it, and assimp's glTF reader recurses once a level (200,000 levels overflowed
/// the stack).
inline constexpr int kMaxJsonDepth = 256;

class JsonReader {
 public:
  using json = nlohmann::json;

  /// `source` names the document in every message (a file name, or "(built-in)").
  explicit JsonReader(std::string source) : source_(std::move(source)) {}

  /// Parses `text`. Invalid JSON throws UserError "SOURCE:LINE: not valid JSON: ..."; a number
  /// too large for a double "SOURCE:LINE: not a valid KIND: number overflow parsing '1e999'"
  /// (`kind`: "scene", "solution"); arrays and objects nested deeper than kMaxJsonDepth
  /// "SOURCE:LINE: not a valid KIND: nested deeper than 256 levels"; with Keys::unique (scene
  /// files, written by hand), a key given twice in one object "SOURCE: not a valid KIND: the key
  /// 'k' appears twice in PATH" (JSON would keep its last value silently; looking costs a second
  /// pass, half again the parse's time).
  enum class Keys { unique, as_parsed };
  json parse(const std::string& text, const std::string& kind, Keys keys = Keys::unique) const;

  /// "path.key", or "key" at the top level.
  static std::string join(const std::string& path, const std::string& key);
  /// "path[index]".
  static std::string at(const std::string& path, size_t index);

  [[noreturn]] void fail(const std::string& field, const std::string& what) const;

  /// obj[key]; "missing" if absent, "must be an object" if obj is not one (field `path`).
  const json& member(const json& obj, const std::string& key, const std::string& path) const;
  /// A finite number.
  double number(const json& j, const std::string& path) const;
  std::string string(const json& j, const std::string& path) const;
  bool boolean(const json& j, const std::string& path) const;
  /// An array of exactly 3 finite numbers.
  Vec3 vec3(const json& j, const std::string& path) const;
  /// A grey number or an [r, g, b] triple.
  Rgb colour(const json& j, const std::string& path) const;
  /// Refuses any key of `obj` not in `known` ("unknown field").
  void no_unknown_keys(const json& obj, std::initializer_list<const char*> known, const std::string& path) const;

  const std::string& source() const { return source_; }

 private:
  std::string source_;
};

}  // namespace radrecon
