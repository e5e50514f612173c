#pragma once
// Parsing numbers from command-line text, whole strings only.

#include <cmath>
#include <optional>
#include <string>

namespace radrecon {

/// The finite number that is the whole of `text`, or nullopt ("4", "1e-3"; not "4x", "nan").
inline std::optional<double> parse_finite(const std::string& text) {
  size_t used = 0;
  double v = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (used == 0 || used != text.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

}  // namespace radrecon
