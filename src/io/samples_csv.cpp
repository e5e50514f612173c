#include "io/samples_csv.h"

#include <algorithm>
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

#include "core/check.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/parse.h"
#include "core/tolerances.h"
#include "io/atomic_file.h"
#include "reconstruct/sample_set.h"

namespace radrecon {

namespace {

// --- CSV reading ------------------------------------------------------------------------------

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
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

  /// The coordinate in field `column`: a finite number of magnitude at most
  /// tol::kMaxSampleCoordinate.
  double coordinate(const std::vector<std::string_view>& fields, size_t column) const {
    const double v = number(fields, column);
    if (std::abs(v) > tol::kMaxSampleCoordinate)
      throw UserError(where(), "column " + std::to_string(column + 1) + " (" + header_[column] + "): " +
                                   in_quotes(fields[column]) + " is beyond the largest coordinate, " + format_number(tol::kMaxSampleCoordinate));
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
      const std::string_view t = trim_blanks(line);
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
    const double x = table.coordinate(f, 0), y = table.coordinate(f, 1);
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

std::vector<Vec2> read_queries_csv(const std::string& path) {
  CsvTable table(path, 2, "x,y[,...]");
  std::vector<Vec2> points;
  points.reserve(table.remaining_lines());
  table.for_each_row([&](const std::vector<std::string_view>& f) {
    const double x = table.coordinate(f, 0), y = table.coordinate(f, 1);
    points.emplace_back(x, y);
  });
  return points;
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

}  // namespace radrecon
