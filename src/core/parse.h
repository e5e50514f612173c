#pragma once
// The one home of parsing numbers from text (command-line values, CSV fields, mesh
// specifications): whole strings only, decimal, no surrounding blanks.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace radrecon {

enum class NumberStatus { ok, not_a_number, out_of_range, not_finite };

/// Parses all of `text` as a decimal floating-point number ("4", "-2.5", "3e-4", a leading '+'
/// allowed; not "4x", " 4", "nan", "inf"). On ok, `value` holds a finite double: a magnitude too
/// small for a double ("1e-400") rounds to 0 or a subnormal, as strtod does; out_of_range means
/// too large ("1e400").
NumberStatus parse_double(std::string_view text, double& value);

/// The finite number that is the whole of `text`, or nullopt.
std::optional<double> parse_finite(std::string_view text);

/// The integer that is the whole of `text` (decimal, optional sign), or nullopt (also when it
/// does not fit in a long long).
std::optional<long long> parse_integer(std::string_view text);

/// "WIDTHxHEIGHT" (or "WIDTHXHEIGHT"), e.g. "400x300".
struct Size2 {
  int width = 0, height = 0;
};

/// Parses a size with 1 <= width, height <= max_side and width * height <= max_pixels; throws
/// UserError naming `where` (an option or field) otherwise.
Size2 parse_size(const std::string& text, const std::string& where, int max_side, long long max_pixels);

/// The shortest decimal text that reads back as `v` ("1e+100", "0.1", "nan").
std::string format_number(double v);

/// `text` without the blanks (spaces, tabs, a carriage return) at either end.
std::string_view trim_blanks(std::string_view text);

/// Splits `line` at every comma into `fields` (cleared first), each trimmed of blanks; no
/// quoting. "a, b,,c" gives "a", "b", "", "c".
void split_fields(std::string_view line, std::vector<std::string_view>& fields);

/// `text` in single quotes for a message, cut to 40 bytes; control characters and bytes that
/// are not UTF-8 written as \xNN ("a\x00b" for a NUL), well-formed UTF-8 as it is.
std::string in_quotes(std::string_view text);

/// `text` with ASCII letters in lower case (locale-independent).
std::string ascii_lower(std::string_view text);

/// The extension of `path` with its dot, in lower case: "scene.OBJ" gives ".obj", "x" gives "".
std::string lower_extension(const std::string& path);

}  // namespace radrecon
