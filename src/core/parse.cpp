#include "core/parse.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>

#include <locale.h>  // strtod_l: POSIX

#include "core/error.h"

namespace radrecon {

NumberStatus parse_double(std::string_view f, double& v) {
  std::string_view d = f;
  if (!d.empty() && d.front() == '+') d.remove_prefix(1);
  if (d.empty() || d.front() == '+' || (f.front() == '+' && d.front() == '-')) return NumberStatus::not_a_number;
  const auto [end, ec] = std::from_chars(d.data(), d.data() + d.size(), v);
  if (ec == std::errc::result_out_of_range && end == d.data() + d.size()) {
    // from_chars leaves `v` alone both for a magnitude too large and for one too small for a
    // double. Too small is no error: "1e-400" is read as strtod rounds it (0 or a subnormal,
    // with its sign); too large is.
    // In the C locale whatever the process's (a decimal comma would stop at the point).
    static const locale_t c_numeric = newlocale(LC_NUMERIC_MASK, "C", static_cast<locale_t>(nullptr));
    const std::string text(d);
    const double rounded = strtod_l(text.c_str(), nullptr, c_numeric);
    if (!std::isfinite(rounded) || std::abs(rounded) >= std::numeric_limits<double>::min()) return NumberStatus::out_of_range;
    v = rounded;
    return NumberStatus::ok;
  }
  if (ec != std::errc() || end != d.data() + d.size()) return NumberStatus::not_a_number;
  return std::isfinite(v) ? NumberStatus::ok : NumberStatus::not_finite;
}

std::optional<double> parse_finite(std::string_view text) {
  double v = 0;
  if (parse_double(text, v) != NumberStatus::ok) return std::nullopt;
  return v;
}

std::optional<long long> parse_integer(std::string_view text) {
  std::string_view d = text;
  if (!d.empty() && d.front() == '+') d.remove_prefix(1);
  if (d.empty() || d.front() == '+' || (text.front() == '+' && d.front() == '-')) return std::nullopt;
  long long v = 0;
  const auto [end, ec] = std::from_chars(d.data(), d.data() + d.size(), v);
  if (ec != std::errc() || end != d.data() + d.size()) return std::nullopt;
  return v;
}

std::string format_number(double v) {
  if (std::isnan(v)) return "nan";
  char buf[64];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return ec == std::errc() ? std::string(buf, end) : std::string("?");
}

std::string_view trim_blanks(std::string_view s) {
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  return s;
}

void split_fields(std::string_view line, std::vector<std::string_view>& fields) {
  fields.clear();
  size_t start = 0;
  while (true) {
    const size_t comma = line.find(',', start);
    if (comma == std::string_view::npos) {
      fields.push_back(trim_blanks(line.substr(start)));
      return;
    }
    fields.push_back(trim_blanks(line.substr(start, comma - start)));
    start = comma + 1;
  }
}

namespace {

/// The length of the well-formed UTF-8 sequence of 2 to 4 bytes at the start of `s`, else 0.
size_t utf8_sequence(std::string_view s) {
  const auto byte = [&](size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char lead = byte(0);
  const size_t n = lead >= 0xc2 && lead <= 0xdf ? 2 : lead >= 0xe0 && lead <= 0xef ? 3 : lead >= 0xf0 && lead <= 0xf4 ? 4 : 0;
  if (n == 0 || s.size() < n) return 0;
  for (size_t k = 1; k < n; ++k)
    if ((byte(k) & 0xc0) != 0x80) return 0;
  // No overlong forms, surrogates or code points beyond U+10FFFF.
  if ((lead == 0xe0 && byte(1) < 0xa0) || (lead == 0xed && byte(1) > 0x9f) || (lead == 0xf0 && byte(1) < 0x90) ||
      (lead == 0xf4 && byte(1) > 0x8f))
    return 0;
  return n;
}

}  // namespace

std::string in_quotes(std::string_view s) {
  constexpr size_t kMax = 40;
  const bool cut = s.size() > kMax;
  if (cut) s = s.substr(0, kMax);
  std::string out = "'";
  // Control characters and bytes that are not UTF-8 as \xNN: a message shows the input, never
  // sends a terminal its raw bytes (nor ends at a NUL).
  for (size_t i = 0; i < s.size();) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
      ++i;
    } else if (const size_t n = c >= 0x80 ? utf8_sequence(s.substr(i)) : 0; n > 0) {
      out.append(s.substr(i, n));
      i += n;
    } else {
      static constexpr char kHex[] = "0123456789abcdef";
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
      ++i;
    }
  }
  return out + (cut ? "...'" : "'");
}

std::string ascii_lower(std::string_view text) {
  std::string out(text);
  for (char& c : out)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return out;
}

std::string lower_extension(const std::string& path) {
  return ascii_lower(std::filesystem::path(path).extension().string());
}

Size2 parse_size(const std::string& text, const std::string& where, int max_side, long long max_pixels) {
  const std::string expected = "expected WIDTHxHEIGHT, e.g. 400x300, got " + in_quotes(text);
  const size_t x = text.find_first_of("xX");
  if (x == std::string::npos) throw UserError(where, expected);
  const auto side = [&](std::string_view s, const char* name) {
    const bool digits = !s.empty() && s.find_first_not_of("0123456789") == std::string_view::npos;
    if (!digits) throw UserError(where, expected);
    const std::optional<long long> v = parse_integer(s);
    if (!v || *v < 1 || *v > max_side)
      throw UserError(where, std::string("the ") + name + " must be between 1 and " + std::to_string(max_side) +
                                 ", got " + in_quotes(s));
    return static_cast<int>(*v);
  };
  const std::string_view all(text);
  Size2 size{side(all.substr(0, x), "width"), side(all.substr(x + 1), "height")};
  const long long pixels = static_cast<long long>(size.width) * size.height;
  if (pixels > max_pixels)
    throw UserError(where, std::to_string(size.width) + "x" + std::to_string(size.height) + " is " + std::to_string(pixels) +
                               " points, more than the limit of " + std::to_string(max_pixels));
  return size;
}

}  // namespace radrecon
