#include "io/samples_csv.h"

#include <algorithm>
#include <array>
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
#include <optional>

#include "core/check.h"
#include "core/error.h"
#include "core/limits.h"
#include "core/parallel.h"
#include "core/parse.h"
#include "core/tolerances.h"
#include "io/atomic_file.h"
#include "io/json_reader.h"
#include "reconstruct/sample_set.h"

namespace radrecon {

namespace {

// --- CSV reading ------------------------------------------------------------------------------

/// Field `f` without one pair of surrounding double quotes (R's and spreadsheets' headers).
std::string_view unquoted(std::string_view f) {
  if (f.size() >= 2 && f.front() == '"' && f.back() == '"') return trim_blanks(f.substr(1, f.size() - 2));
  return f;
}

/// A table read line by line: the header, then each data row through a callback. Fields are
/// separated by commas when the header line has one, else by runs of spaces or tabs (XYZ files
/// of nnbathy and GMT); a header whose fields are all numbers is no header but the first row.
class CsvTable {
 public:
  /// Reads the whole file and its header; `min_columns` names the columns the header must have.
  CsvTable(const std::string& path, size_t min_columns, const char* expected_header)
      : path_(path), text_(read_text_file(path, "CSV file")) {  // pipes too, within the file-size limit
    if (text_.compare(0, 3, "\xEF\xBB\xBF") == 0) pos_ = 3;  // a UTF-8 byte order mark
    // Lines ended by carriage returns alone (classic Mac OS) read as one line: "no data rows".
    if (text_.find('\n') == std::string::npos && text_.find('\r') != std::string::npos)
      throw UserError(path, "its lines end in carriage returns alone (classic Mac OS text); end them in line feeds "
                            "(e.g. tr '\\r' '\\n')");

    std::string_view line;
    const size_t header_pos = pos_;
    if (!next_line(line))
      throw UserError(where(), std::string("no header line; expected ") + expected_header);
    comma_ = line.find(',') != std::string_view::npos;
    std::vector<std::string_view> fields;
    split(line, fields);
    bool numbers = true;
    for (std::string_view f : fields) {
      double v = 0;
      numbers = numbers && parse_double(f, v) == NumberStatus::ok;
    }
    if (numbers && fields.size() >= min_columns) {
      // No header: x, y, then z (one value) or value1, value2, ...; the line is the first row.
      for (size_t c = 0; c < fields.size(); ++c)
        header_.push_back(c == 0 ? "x" : c == 1 ? "y" : fields.size() == 3 ? "z" : "value" + std::to_string(c - 1));
      pos_ = header_pos;
      line_number_ = 0;
    } else {
      for (std::string_view f : fields) header_.emplace_back(f);
    }
    if (header_.size() < min_columns)
      throw UserError(where(), "the header " + in_quotes(line) + " has " + std::to_string(header_.size()) +
                                   " column" + (header_.size() == 1 ? "" : "s") + "; expected " + expected_header);
    for (size_t c = 0; c < header_.size(); ++c)
      if (header_[c].empty()) throw UserError(where(), "column " + std::to_string(c + 1) + " of the header has no name");
    header_line_ = line_number_;
  }

  /// Refuses a column the command uses whose name keeps a double quote: a name in quotes loses
  /// them (unquoted()), so one left is a quote without its pair, or one within the name.
  void check_name(size_t c) const {
    if (header_[c].find('"') != std::string::npos)
      throw UserError(path_ + ":" + std::to_string(std::max<size_t>(header_line_, 1)),
                      "column " + std::to_string(c + 1) + " of the header, " + in_quotes(header_[c]) +
                          ", has a double quote in its name (names are plain or in one pair of double quotes)");
  }

  /// The column named `name` (case-insensitive), for option `option`; UserError if none is.
  /// The column named `name`, which names one column (UserError naming `option` otherwise: a
  /// second 'x' became a value column named x, beside the first read as x).
  size_t column(const std::string& name, const std::string& option) const {
    const std::optional<size_t> c = find(name);
    size_t named = 0;
    for (const std::string& h : header_) named += ascii_lower(h) == ascii_lower(name);
    if (named > 1)
      throw UserError(option, path_ + " has " + std::to_string(named) + " columns named " + in_quotes(name) +
                                  " (names are matched without case); rename all but one");
    if (!c) {
      std::string names;
      for (const std::string& h : header_) names += (names.empty() ? "" : ", ") + h;
      throw UserError(option, path_ + " has no column named '" + name + "' (its columns: " + names + ")");
    }
    return *c;
  }
  std::optional<size_t> find(const std::string& name) const {
    for (size_t c = 0; c < header_.size(); ++c)
      if (ascii_lower(header_[c]) == ascii_lower(name)) return c;
    return std::nullopt;
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
      split(line, fields);
      if (fields.size() != header_.size()) {
        // The header decides the separator: a row of the other kind reads as one field, or many.
        const bool other = comma_ ? line.find(',') == std::string_view::npos : line.find(',') != std::string_view::npos;
        throw UserError(where(), "the row has " + std::to_string(fields.size()) + (fields.size() == 1 ? " field" : " fields") +
                                     ", the header has " + std::to_string(header_.size()) +
                                     (other ? std::string("; the header's separator (") + (comma_ ? "commas" : "spaces") +
                                                  ") decides the table's, and this row uses " + (comma_ ? "spaces" : "commas")
                                            : ""));
      }
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

  /// The value in field `column`: a finite number of magnitude at most tol::kMaxSampleValue.
  double value(const std::vector<std::string_view>& fields, size_t column) const {
    return bounded(fields, column, tol::kMaxSampleValue, "value");
  }

  /// The coordinate in field `column`: a finite number of magnitude at most
  /// tol::kMaxSampleCoordinate.
  double coordinate(const std::vector<std::string_view>& fields, size_t column) const {
    return bounded(fields, column, tol::kMaxSampleCoordinate, "coordinate");
  }

  /// The number in field `column`, of magnitude at most `most`: else "beyond the largest WHAT".
  double bounded(const std::vector<std::string_view>& fields, size_t column, double most, const char* what) const {
    const double v = number(fields, column);
    if (std::abs(v) > most)
      throw UserError(where(), "column " + std::to_string(column + 1) + " (" + header_[column] + "): " +
                                   in_quotes(fields[column]) + " is beyond the largest " + what + ", " + format_number(most));
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

  void split(std::string_view line, std::vector<std::string_view>& fields) const {
    if (comma_) {
      split_fields(line, fields);
      for (std::string_view& f : fields) f = unquoted(f);
      return;
    }
    fields.clear();
    size_t at = 0;
    while (true) {
      at = line.find_first_not_of(" \t\r", at);
      if (at == std::string_view::npos) return;
      const size_t end = std::min(line.size(), line.find_first_of(" \t\r", at));
      fields.push_back(unquoted(line.substr(at, end - at)));
      at = end;
    }
  }

  std::string path_;
  std::string text_;
  bool comma_ = true;
  size_t pos_ = 0;
  size_t line_number_ = 0;
  size_t header_line_ = 1;  ///< the header's line (blank and '#' lines may come first)
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

namespace {

/// The x and y columns: the named ones, else the first pair of kCoordinateNames in the header
/// (any case), else the first two.
std::pair<size_t, size_t> xy_columns(const CsvTable& table, const CsvColumns& columns) {
  std::string x_name = "x", y_name = "y";
  for (const auto& [xn, yn] : kCoordinateNames)
    if (table.find(std::string(xn)) && table.find(std::string(yn))) {
      x_name = xn, y_name = yn;
      break;
    }
  const size_t x = !columns.x.empty() ? table.column(columns.x, "--x") : table.find(x_name) ? table.column(x_name, "--x") : 0;
  const size_t y = !columns.y.empty() ? table.column(columns.y, "--y") : table.find(y_name) ? table.column(y_name, "--y") : 1;
  if (x == y) throw UserError("--x/--y", "x and y are the same column ('" + table.header()[x] + "')");
  return {x, y};
}

}  // namespace

ScatteredSamples read_samples_csv(const std::string& path, std::vector<std::string>* value_names,
                                  const CsvColumns& columns, const Barriers& barriers) {
  CsvTable table(path, 3, "x,y,VALUE[,VALUE...] (or --x, --y, --value naming the columns)");
  const std::pair<size_t, size_t> xy = xy_columns(table, columns);  // not a structured binding: lambdas take these
  const size_t xc = xy.first, yc = xy.second;
  std::vector<size_t> value_columns;
  for (const std::string& name : columns.values) value_columns.push_back(table.column(name, "--value"));
  if (columns.values.empty()) {
    std::string left_out;
    for (size_t c = 0; c < table.header().size(); ++c) {
      if (c == xc || c == yc) continue;
      if (repeats_a_coordinate_name(table.header()[c])) {
        left_out += (left_out.empty() ? "" : ", ") + table.header()[c];
        continue;
      }
      value_columns.push_back(c);
    }
    if (value_columns.empty())
      throw UserError(path, "has no value column: its columns besides --x and --y are named x or y (" + left_out +
                                "); name the ones to interpolate with --value");
    if (!left_out.empty())
      warn(path + (left_out.find(',') == std::string::npos ? ": the column " + left_out + " is not interpolated: it is"
                                                            : ": the columns " + left_out + " are not interpolated: they are") +
           " named as the output's coordinate columns (x, y), the points' coordinates coming from --x and --y (--value "
           "names the columns to interpolate)");
  }
  for (const size_t c : value_columns) table.check_name(c);  // each becomes an output column's name
  ScatteredSamples s;
  s.channels = static_cast<int>(value_columns.size());
  const size_t rows = std::min<size_t>(table.remaining_lines(), static_cast<size_t>(limit_value(Limit::samples)) + 1);
  s.points.reserve(rows);
  s.values.reserve(rows * value_columns.size());
  table.for_each_row([&](const std::vector<std::string_view>& f) {
    check_limit(Limit::samples, static_cast<long long>(s.points.size()) + 1, path, "holds at least");
    const double x = table.coordinate(f, xc), y = table.coordinate(f, yc);
    s.points.emplace_back(x, y);
    for (const size_t c : value_columns) s.values.push_back(table.value(f, c));
  });
  if (value_names) {
    value_names->clear();
    for (const size_t c : value_columns) value_names->push_back(table.header()[c]);
  }
  const size_t before = s.points.size();
  const Result<size_t> merged = merge_duplicate_points(s, barriers);
  if (!merged) throw UserError(path, merged.reason());
  const size_t removed = merged.value();
  if (removed > 0) warn(path + ": " + merged_samples_message(removed, before, s.points.size()));
  return s;
}

std::vector<Vec2> read_queries_csv(const std::string& path, const CsvColumns& columns) {
  CsvTable table(path, 2, "x,y[,...] (or --x, --y naming the columns)");
  const std::pair<size_t, size_t> xy = xy_columns(table, columns);  // not a structured binding: lambdas take these
  const size_t xc = xy.first, yc = xy.second;
  std::vector<Vec2> points;
  points.reserve(std::min<size_t>(table.remaining_lines(), static_cast<size_t>(limit_value(Limit::raster_points)) + 1));
  table.for_each_row([&](const std::vector<std::string_view>& f) {
    check_limit(Limit::raster_points, static_cast<long long>(points.size()) + 1, path, "holds at least",
                "query points count as raster points");
    const double x = table.coordinate(f, xc), y = table.coordinate(f, yc);
    points.emplace_back(x, y);
  });
  return points;
}

void write_values_csv(const std::string& path, std::span<const Vec2> points, std::span<const double> values,
                      const std::vector<std::string>& value_names) {
  const size_t ch = value_names.size();
  RR_CHECK(values.size() == points.size() * ch, "values do not match the points");
  write_file_atomically(path, [&](const std::filesystem::path& tmp) {
    OutputFile out(tmp, path);
    std::string header = "x,y";
    for (const std::string& n : value_names) header += "," + n;
    header += "\n";
    out.write(header);
    // Rows are formatted in parallel, a block at a time, and written in order.
    constexpr size_t kChunk = 4096, kChunksPerBlock = 64;
    std::vector<std::string> chunks(kChunksPerBlock);
    for (size_t block = 0; block < points.size(); block += kChunk * kChunksPerBlock) {
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
      for (std::int64_t c = 0; c < count; ++c) out.write(chunks[static_cast<size_t>(c)]);
    }
    out.close();
  });
}

}  // namespace radrecon
