#include "core/barrier_line.h"

#include "core/parse.h"

namespace radrecon {

namespace {

std::string bracketed(const Vec2& p) {
  std::string t = "[";  // appended, not "[" + ...: GCC 12 warns (-Wrestrict) on that falsely
  t += format_number(p.x());
  t += ", ";
  t += format_number(p.y());
  t += "]";
  return t;
}

}  // namespace

std::optional<BarrierLineDefect> barrier_line_defect(std::span<const Vec2> line, BarrierLineKind kind,
                                                     std::string_view noun) {
  const std::string n(noun);
  for (size_t i = 1; i < line.size(); ++i)
    if (line[i] == line[i - 1])
      return BarrierLineDefect{i, "repeats the " + n + " before it, " + bracketed(line[i]) + ": a segment of zero length"};
  const std::string count = std::to_string(line.size());
  if (kind == BarrierLineKind::line_string) {
    if (line.size() < 2) return BarrierLineDefect{std::nullopt, "a LineString needs at least 2 " + n + "s, it has " + count};
    return std::nullopt;
  }
  if (line.size() < 4)
    return BarrierLineDefect{std::nullopt, "a Polygon ring needs at least 4 " + n + "s (a closed triangle), it has " + count};
  if (line.front() != line.back())
    return BarrierLineDefect{std::nullopt, "a Polygon ring must be closed: its last " + n + " " + bracketed(line.back()) +
                                               " must repeat its first " + bracketed(line.front())};
  return std::nullopt;
}

}  // namespace radrecon
