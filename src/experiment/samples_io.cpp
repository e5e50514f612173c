#include "experiment/samples_io.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>

#include "core/atomic_file.h"
#include "core/check.h"
#include "core/error.h"
#include "core/image.h"
#include "core/parallel.h"
#include "render/ground_map.h"

namespace radrecon {

namespace {

// --- CSV reading ------------------------------------------------------------------------------

std::string_view trim(std::string_view s) {
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
      fields.push_back(trim(line.substr(start)));
      return;
    }
    fields.push_back(trim(line.substr(start, comma - start)));
    start = comma + 1;
  }
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::string in_quotes(std::string_view s) {
  constexpr size_t kMax = 40;
  std::string out = "'";
  out += s.size() > kMax ? std::string(s.substr(0, kMax)) + "..." : std::string(s);
  return out + "'";
}

enum class NumberStatus { ok, not_a_number, out_of_range, not_finite };

/// Parses all of `f` as a decimal floating-point number (a leading '+' allowed).
NumberStatus parse_double(std::string_view f, double& v) {
  std::string_view d = f;
  if (!d.empty() && d.front() == '+') d.remove_prefix(1);
  if (d.empty() || d.front() == '+' || (f.front() == '+' && d.front() == '-')) return NumberStatus::not_a_number;
  const auto [end, ec] = std::from_chars(d.data(), d.data() + d.size(), v);
  if (ec == std::errc::result_out_of_range) return NumberStatus::out_of_range;
  if (ec != std::errc() || end != d.data() + d.size()) return NumberStatus::not_a_number;
  return std::isfinite(v) ? NumberStatus::ok : NumberStatus::not_finite;
}

/// A CSV table read line by line: the header, then each data row through a callback.
class CsvTable {
 public:
  /// Reads the whole file and its header; `min_columns` names the columns the header must have.
  CsvTable(const std::string& path, size_t min_columns, const char* expected_header) : path_(path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw UserError(path, std::string("cannot open: ") + std::strerror(errno));
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    if (!ec) text_.reserve(static_cast<size_t>(size));
    std::vector<char> chunk(size_t{1} << 20);  // reads pipes too (no seeking)
    while (in.read(chunk.data(), static_cast<std::streamsize>(chunk.size())) || in.gcount() > 0)
      text_.append(chunk.data(), static_cast<size_t>(in.gcount()));
    if (in.bad()) throw UserError(path, "cannot read");

    std::string_view line;
    if (!next_line(line))
      throw UserError(where(), std::string("no header line; expected ") + expected_header);
    std::vector<std::string_view> fields;
    split_fields(line, fields);
    for (std::string_view f : fields) header_.emplace_back(f);
    if (header_.size() < 2 || lower(header_[0]) != "x" || lower(header_[1]) != "y")
      throw UserError(where(), std::string("the header (the first line that is not a comment) must start with x,y; ") +
                                   "got " + in_quotes(line) + "; expected " + expected_header);
    if (header_.size() < min_columns)
      throw UserError(where(), "the header has " + std::to_string(header_.size()) + " columns; expected " +
                                   expected_header);
    for (size_t c = 0; c < header_.size(); ++c)
      if (header_[c].empty()) throw UserError(where(), "column " + std::to_string(c + 1) + " of the header has no name");
  }

  const std::vector<std::string>& header() const { return header_; }
  /// An upper bound of the number of data rows still to come (for reserving).
  size_t remaining_lines() const {
    return static_cast<size_t>(std::count(text_.begin() + static_cast<std::ptrdiff_t>(std::min(pos_, text_.size())),
                                          text_.end(), '\n')) + 1;
  }

  /// Calls row(fields) for each data row; refuses a row with the wrong field count and a table
  /// without rows.
  void for_each_row(const std::function<void(const std::vector<std::string_view>&)>& row) {
    std::string_view line;
    size_t rows = 0;
    std::vector<std::string_view> fields;
    while (next_line(line)) {
      split_fields(line, fields);
      if (fields.size() != header_.size())
        throw UserError(where(), "the row has " + std::to_string(fields.size()) + " fields, the header has " +
                                     std::to_string(header_.size()));
      row(fields);
      ++rows;
    }
    if (rows == 0) throw UserError(where(), "no data rows after the header");
  }

  /// The finite number in field `column` (0-based) of the current row.
  double number(const std::vector<std::string_view>& fields, size_t column) const {
    std::string_view f = fields[column];
    double v = 0;
    const NumberStatus status = f.empty() ? NumberStatus::not_a_number : parse_double(f, v);
    if (status == NumberStatus::ok) return v;
    const std::string what = "column " + std::to_string(column + 1) + " (" + header_[column] + ")";
    if (f.empty()) throw UserError(where(), what + ": empty field, expected a number");
    switch (status) {
      case NumberStatus::ok: break;
      case NumberStatus::not_a_number: throw UserError(where(), what + ": " + in_quotes(f) + " is not a number");
      case NumberStatus::out_of_range: throw UserError(where(), what + ": " + in_quotes(f) + " is out of the range of a double");
      case NumberStatus::not_finite:
        throw UserError(where(), what + ": " + in_quotes(f) + " is not finite (NaN and Inf are refused)");
    }
    return v;
  }

  /// "FILE:LINE" of the current line (the last line read; line 1 for an empty file).
  std::string where() const { return path_ + ":" + std::to_string(std::max<size_t>(line_number_, 1)); }

 private:
  /// The next line that is not blank nor a comment; false at the end of the file.
  bool next_line(std::string_view& line) {
    while (pos_ < text_.size()) {
      size_t end = text_.find('\n', pos_);
      if (end == std::string::npos) end = text_.size();
      line = std::string_view(text_).substr(pos_, end - pos_);
      pos_ = end + 1;
      ++line_number_;
      const std::string_view t = trim(line);
      if (t.empty() || t.front() == '#') continue;
      return true;
    }
    return false;
  }

  std::string path_;
  std::string text_;
  size_t pos_ = 0;
  size_t line_number_ = 0;
  std::vector<std::string> header_;
};

// --- grid detection ---------------------------------------------------------------------------

/// The sorted distinct values of `v`, values within `tol` of the previous distinct one merged.
std::vector<double> distinct_values(std::vector<double> v, double tol) {
  std::sort(v.begin(), v.end());
  std::vector<double> out;
  for (double x : v)
    if (out.empty() || x - out.back() > tol) out.push_back(x);
  return out;
}

constexpr double kGridTolerance = 1e-9;

struct Axis {
  double lo = 0, hi = 0, tol = 0;
  std::vector<double> distinct;
};

Axis axis_of(const ScatteredSamples& s, int dim) {
  Axis a;
  std::vector<double> v(s.points.size());
  for (size_t k = 0; k < v.size(); ++k) v[k] = s.points[k][dim];
  if (v.empty()) return a;
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  a.lo = *lo;
  a.hi = *hi;
  a.tol = kGridTolerance * (a.hi - a.lo);
  a.distinct = distinct_values(std::move(v), a.tol);
  return a;
}

// --- number formatting ------------------------------------------------------------------------

void append_number(std::string& out, double v) {
  if (std::isnan(v)) {
    out += "nan";
    return;
  }
  char buf[64];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);  // shortest round trip
  RR_CHECK(ec == std::errc(), "number formatting failed");
  out.append(buf, end);
}

void check_raster_values(const Raster& raster, std::span<const double> values, int channels) {
  RR_CHECK(channels >= 1 && values.size() == static_cast<size_t>(raster.width) * raster.height * channels,
           "raster values do not match the raster size");
}

}  // namespace

// --- samples and queries ----------------------------------------------------------------------

ScatteredSamples read_samples_csv(const std::string& path, std::vector<std::string>* value_names) {
  CsvTable table(path, 3, "x,y,VALUE[,VALUE...]");
  const size_t columns = table.header().size();
  ScatteredSamples s;
  s.channels = static_cast<int>(columns - 2);
  const size_t rows = table.remaining_lines();
  s.points.reserve(rows);
  s.values.reserve(rows * (columns - 2));
  table.for_each_row([&](const std::vector<std::string_view>& f) {
    const double x = table.number(f, 0), y = table.number(f, 1);
    s.points.emplace_back(x, y);
    for (size_t c = 2; c < columns; ++c) s.values.push_back(table.number(f, c));
  });
  if (value_names) value_names->assign(table.header().begin() + 2, table.header().end());
  const size_t before = s.points.size();
  const size_t removed = merge_duplicate_points(s);
  if (removed > 0)
    std::fprintf(stderr,
                 "radrecon: warning: %s: %zu sample%s the point of an earlier sample; samples at the same point "
                 "are merged, their values averaged (%zu samples -> %zu points)\n",
                 path.c_str(), removed, removed == 1 ? " repeats" : "s repeat", before, s.points.size());
  return s;
}

std::size_t merge_duplicate_points(ScatteredSamples& s) {
  const size_t n = s.points.size(), ch = static_cast<size_t>(s.channels);
  RR_CHECK(s.values.size() == n * ch, "sample values do not match the points");
  // Sorted by (x, y, index): equal points are adjacent, the first of them first.
  struct Key {
    double x, y;
    size_t index;
  };
  std::vector<Key> keys(n);
  for (size_t k = 0; k < n; ++k) keys[k] = {s.points[k].x(), s.points[k].y(), k};
  std::sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) {
    if (a.x != b.x) return a.x < b.x;
    if (a.y != b.y) return a.y < b.y;
    return a.index < b.index;
  });
  // rep[k]: the first sample at sample k's point.
  std::vector<size_t> rep(n);
  size_t removed = 0;
  for (size_t a = 0; a < n;) {
    size_t b = a + 1;
    while (b < n && keys[b].x == keys[a].x && keys[b].y == keys[a].y) ++b;
    for (size_t k = a; k < b; ++k) rep[keys[k].index] = keys[a].index;
    removed += b - a - 1;
    a = b;
  }
  if (removed == 0) return 0;

  std::vector<double> sum(n * ch, 0.0);
  std::vector<size_t> count(n, 0);
  for (size_t k = 0; k < n; ++k) {
    ++count[rep[k]];
    for (size_t c = 0; c < ch; ++c) sum[rep[k] * ch + c] += s.values[k * ch + c];
  }
  ScatteredSamples merged;
  merged.channels = s.channels;
  for (size_t k = 0; k < n; ++k) {
    if (rep[k] != k) continue;
    merged.points.push_back(s.points[k]);
    for (size_t c = 0; c < ch; ++c) merged.values.push_back(sum[k * ch + c] / static_cast<double>(count[k]));
  }
  s = std::move(merged);
  return removed;
}

std::vector<Vec2> read_queries_csv(const std::string& path) {
  CsvTable table(path, 2, "x,y[,...]");
  std::vector<Vec2> points;
  points.reserve(table.remaining_lines());
  table.for_each_row([&](const std::vector<std::string_view>& f) {
    const double x = table.number(f, 0), y = table.number(f, 1);
    points.emplace_back(x, y);
  });
  return points;
}

// --- regular grids ----------------------------------------------------------------------------

DistinctCoordinates count_distinct_coordinates(const ScatteredSamples& samples) {
  return {axis_of(samples, 0).distinct.size(), axis_of(samples, 1).distinct.size()};
}

std::optional<GridNodes> as_regular_grid(const ScatteredSamples& s) {
  const Axis ax = axis_of(s, 0), ay = axis_of(s, 1);
  const size_t nx = ax.distinct.size(), ny = ay.distinct.size();
  if (nx < 2 || ny < 2 || nx * ny != s.points.size()) return std::nullopt;
  const double dx = (ax.hi - ax.lo) / static_cast<double>(nx - 1);
  const double dy = (ay.hi - ay.lo) / static_cast<double>(ny - 1);
  // The index of coordinate v on an axis, or -1 when v is not within tolerance of a node.
  const auto index = [](double v, double lo, double d, size_t count, double tol) -> long {
    const long i = std::lround((v - lo) / d);
    if (i < 0 || i >= static_cast<long>(count)) return -1;
    return std::abs(v - (lo + static_cast<double>(i) * d)) <= tol ? i : -1;
  };
  const size_t ch = static_cast<size_t>(s.channels);
  GridNodes g;
  g.nx = static_cast<int>(nx);
  g.ny = static_cast<int>(ny);
  g.x0 = ax.lo;
  g.y0 = ay.lo;
  g.dx = dx;
  g.dy = dy;
  g.channels = s.channels;
  g.values.assign(nx * ny * ch, 0.0);
  std::vector<char> seen(nx * ny, 0);
  for (size_t k = 0; k < s.points.size(); ++k) {
    const long i = index(s.points[k].x(), ax.lo, dx, nx, ax.tol);
    const long j = index(s.points[k].y(), ay.lo, dy, ny, ay.tol);
    if (i < 0 || j < 0) return std::nullopt;
    const size_t node = static_cast<size_t>(j) * nx + static_cast<size_t>(i);
    if (seen[node]) return std::nullopt;
    seen[node] = 1;
    for (size_t c = 0; c < ch; ++c) g.values[node * ch + c] = s.values[k * ch + c];
  }
  return g;  // nx * ny samples, none twice: every node is present
}

// --- rasters ----------------------------------------------------------------------------------

void parse_raster_size(const std::string& text, const std::string& option, int& width, int& height) {
  const std::string expected = "expected WIDTHxHEIGHT, e.g. 400x300, got " + in_quotes(text);
  const size_t x = text.find_first_of("xX");
  if (x == std::string::npos) throw UserError(option, expected);
  const auto parse_side = [&](std::string_view s, const char* name) {
    s = trim(s);
    long long v = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (s.empty() || ec == std::errc::invalid_argument || end != s.data() + s.size()) throw UserError(option, expected);
    if (ec == std::errc::result_out_of_range || v < 1 || v > kMaxRasterSide)
      throw UserError(option, std::string("the ") + name + " must be between 1 and " + std::to_string(kMaxRasterSide) +
                                  ", got " + in_quotes(s));
    return static_cast<int>(v);
  };
  const std::string_view all(text);
  width = parse_side(all.substr(0, x), "width");
  height = parse_side(all.substr(x + 1), "height");
  if (static_cast<long long>(width) * height > kMaxRasterPoints)
    throw UserError(option, "a raster of " + std::to_string(static_cast<long long>(width) * height) + " points is more than " +
                                std::to_string(kMaxRasterPoints) + " (about 60 bytes each in memory)");
}

Rect parse_domain(const std::string& text, const std::string& option) {
  std::vector<std::string_view> f;
  split_fields(text, f);
  if (f.size() != 4) throw UserError(option, "expected x0,y0,x1,y1 (four numbers), got " + in_quotes(text));
  double v[4];
  static const char* const names[4] = {"x0", "y0", "x1", "y1"};
  for (int k = 0; k < 4; ++k) {
    if (parse_double(f[static_cast<size_t>(k)], v[k]) != NumberStatus::ok)
      throw UserError(option, std::string(names[k]) + ": expected a finite number, got " + in_quotes(f[static_cast<size_t>(k)]));
  }
  if (!(v[2] > v[0])) throw UserError(option, "x1 must be greater than x0, got " + in_quotes(text));
  if (!(v[3] > v[1])) throw UserError(option, "y1 must be greater than y0, got " + in_quotes(text));
  if (!std::isfinite(v[2] - v[0]) || !std::isfinite(v[3] - v[1]))
    throw UserError(option, "the domain's width and height must be finite numbers, got " + in_quotes(text));
  return Rect{v[0], v[1], v[2], v[3]};
}

std::vector<Vec2> raster_points(const Raster& r) {
  RR_CHECK(r.width > 0 && r.height > 0, "raster size must be positive");
  std::vector<Vec2> points(static_cast<size_t>(r.width) * r.height);
  const double sx = (r.domain.x1 - r.domain.x0) / r.width, sy = (r.domain.y1 - r.domain.y0) / r.height;
  for (int j = 0; j < r.height; ++j)
    for (int i = 0; i < r.width; ++i)
      points[static_cast<size_t>(j) * r.width + i] = Vec2(r.domain.x0 + (i + 0.5) * sx, r.domain.y0 + (j + 0.5) * sy);
  return points;
}

// --- outputs ----------------------------------------------------------------------------------

OutputFormat output_format_of(const std::string& path, const std::string& option) {
  const std::string ext = lower(std::filesystem::path(path).extension().string());
  if (ext == ".csv") return OutputFormat::csv;
  if (ext == ".pfm") return OutputFormat::pfm;
  if (ext == ".png") return OutputFormat::png;
  throw UserError(option, (ext.empty() ? std::string("no file extension") : "unknown file extension " + in_quotes(ext)) +
                              " in '" + path + "'; expected .csv, .pfm or .png");
}

void write_values_csv(const std::string& path, std::span<const Vec2> points, std::span<const double> values,
                      const std::vector<std::string>& value_names) {
  const size_t ch = value_names.size();
  RR_CHECK(values.size() == points.size() * ch, "values do not match the points");
  write_file_atomically(path, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    std::string header = "x,y";
    for (const std::string& n : value_names) header += "," + n;
    header += "\n";
    out << header;
    // Rows are formatted in parallel, a block at a time, and written in order.
    constexpr size_t kChunk = 4096, kChunksPerBlock = 64;
    std::vector<std::string> chunks(kChunksPerBlock);
    for (size_t block = 0; block < points.size() && out; block += kChunk * kChunksPerBlock) {
      const size_t block_end = std::min(points.size(), block + kChunk * kChunksPerBlock);
      const auto count = static_cast<std::int64_t>((block_end - block + kChunk - 1) / kChunk);
      parallel_for(0, count, [&](std::int64_t c) {
        std::string& text = chunks[static_cast<size_t>(c)];
        text.clear();
        const size_t begin = block + static_cast<size_t>(c) * kChunk, end = std::min(block_end, begin + kChunk);
        for (size_t k = begin; k < end; ++k) {
          append_number(text, points[k].x());
          text += ',';
          append_number(text, points[k].y());
          for (size_t v = 0; v < ch; ++v) {
            text += ',';
            append_number(text, values[k * ch + v]);
          }
          text += '\n';
        }
      });
      for (std::int64_t c = 0; c < count; ++c) out << chunks[static_cast<size_t>(c)];
    }
    out.close();
    if (!out) throw UserError(path, "cannot write");
  });
}

void write_values_pfm(const std::string& path, const Raster& raster, std::span<const double> values, int channels) {
  if (channels != 1 && channels != 3)
    throw UserError("--out", "PFM needs 1 or 3 value columns (greyscale or colour); the samples have " +
                                 std::to_string(channels) + "; write .csv instead");
  check_raster_values(raster, values, channels);
  write_file_atomically(path, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << (channels == 1 ? "Pf" : "PF") << "\n" << raster.width << " " << raster.height << "\n-1.0\n";
    // PFM's rows go bottom to top, raster rows y0 upward: the same order. -1.0: little endian.
    const size_t row_len = static_cast<size_t>(raster.width) * channels;
    std::vector<std::uint32_t> row(row_len);
    for (int j = 0; j < raster.height; ++j) {
      for (size_t k = 0; k < row_len; ++k) {
        std::uint32_t bits = std::bit_cast<std::uint32_t>(static_cast<float>(values[j * row_len + k]));
        if constexpr (std::endian::native == std::endian::big)
          bits = (bits >> 24) | ((bits >> 8) & 0xff00u) | ((bits << 8) & 0xff0000u) | (bits << 24);
        row[k] = bits;
      }
      out.write(reinterpret_cast<const char*>(row.data()), static_cast<std::streamsize>(row_len * sizeof(std::uint32_t)));
    }
    out.close();
    if (!out) throw UserError(path, "cannot write PFM");
  });
}

void write_values_png(const std::string& path, const Raster& raster, std::span<const double> values, int channels) {
  check_raster_values(raster, values, channels);
  const bool rgb = channels == 3;
  const size_t ch = static_cast<size_t>(channels), shown = rgb ? 3 : 1;
  double lo = INFINITY, hi = -INFINITY;
  for (size_t k = 0; k < values.size(); k += ch)
    for (size_t c = 0; c < shown; ++c)
      if (std::isfinite(values[k + c])) {
        lo = std::min(lo, values[k + c]);
        hi = std::max(hi, values[k + c]);
      }
  const auto display = [&](double v) -> double {
    if (std::isnan(v)) return 0.0;
    if (std::isinf(v)) return v > 0 ? 1.0 : 0.0;
    if (!(hi > lo)) return 0.5;
    return tone_map(v - lo, hi - lo);
  };
  Image img(raster.width, raster.height);
  for (int j = 0; j < raster.height; ++j)
    for (int i = 0; i < raster.width; ++i) {
      const size_t k = (static_cast<size_t>(j) * raster.width + i) * ch;
      Rgb& px = img.at(i, raster.height - 1 - j);
      if (rgb) px = Rgb(display(values[k]), display(values[k + 1]), display(values[k + 2]));
      else px = Rgb::Constant(display(values[k]));
    }
  write_png(path, img, true);
}

}  // namespace radrecon
