// The files of `radrecon interpolate`: samples and queries CSV in, CSV/PFM out, grid detection and
// raster options. Expected answers are written by hand from the CSV texts below.

#include "io/samples_csv.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/parse.h"
#include "io/raster.h"
#include "reconstruct/methods.h"
#include "reconstruct/sample_set.h"

namespace radrecon {
namespace samples_csv_test {

namespace fs = std::filesystem;

/// A scratch folder per test, removed afterwards.
class SamplesIoFiles {
 public:
  SamplesIoFiles() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("radrecon_samples_csv_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  ~SamplesIoFiles() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  /// Writes `text` to a file named `name` in the scratch folder; returns its path.
  std::string write(const std::string& name, const std::string& text) const {
    const fs::path p = dir_ / name;
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

 private:
  fs::path dir_;
};

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The message of the UserError that `f` throws ("" if none).
template <typename F>
std::string user_error_of(F&& f) {
  try {
    f();
  } catch (const UserError& e) {
    return e.what();
  }
  return "";
}

/// Expects reading `text` as samples to be refused with a message containing "NAME:LINE" and
/// `fragment`.
void expect_samples_refused(const std::string& text, int line, const std::string& fragment) {
  SamplesIoFiles files;
  const std::string path = files.write("bad.csv", text);
  const std::string msg = user_error_of([&] { read_samples_csv(path, nullptr); });
  SCOPED_TRACE("samples text:\n" + text);
  ASSERT_FALSE(msg.empty()) << "not refused";
  EXPECT_NE(msg.find(path + ":" + std::to_string(line)), std::string::npos) << msg;
  EXPECT_NE(msg.find(fragment), std::string::npos) << msg;
}

TEST(SamplesIo, ReadsCommentsBlankLinesSpacesAndTwoValueColumns) {
  SamplesIoFiles files;
  const std::string path = files.write("s.csv",
                                       "# measured on the floor\n"
                                       "\n"
                                       "x , y,red,  green\r\n"
                                       "0,0,1,2\n"
                                       "   # a comment inside\n"
                                       " 1.5 ,\t-2 , 3e-1 , +4\n"
                                       "\n"
                                       "2,0.25,-5,6");
  std::vector<std::string> names;
  const ScatteredSamples s = read_samples_csv(path, &names);
  EXPECT_EQ(names, (std::vector<std::string>{"red", "green"}));
  EXPECT_EQ(s.channels, 2);
  ASSERT_EQ(s.points.size(), 3u);
  EXPECT_EQ(s.points[1], Vec2(1.5, -2));
  EXPECT_EQ(s.points[2], Vec2(2, 0.25));
  EXPECT_EQ(s.values, (std::vector<double>{1, 2, 0.3, 4, -5, 6}));
}

TEST(SamplesIo, RefusesMalformedSamplesNamingFileAndLine) {
  expect_samples_refused("", 1, "no header");
  expect_samples_refused("# only a comment\n\n", 2, "no header");
  expect_samples_refused("x,y\n0,0\n", 1, "has 2 columns");
  expect_samples_refused("0 0\n1 0\n", 1, "has 2 columns");
  expect_samples_refused("x,y,B\n0,0,1\n1,0\n", 3, "the row has 2 fields, the header has 3");
  expect_samples_refused("x,y,B\n0,0,1,7\n", 2, "the row has 4 fields");
  expect_samples_refused("x,y,B\n# c\n0,0,1\n1,0,abc\n", 4, "column 3 (B): 'abc' is not a number");
  expect_samples_refused("x,y,B\n0,0,1\n1,0,2.5kg\n", 3, "is not a number");
  expect_samples_refused("x,y,B\n0,0,1\n1,zero,2\n", 3, "column 2 (y)");
  expect_samples_refused("x,y,B\n0,0,nan\n", 2, "not finite");
  expect_samples_refused("x,y,B\n0,0,1\n1,0,-inf\n", 3, "not finite");
  expect_samples_refused("x,y,B\n0,,1\n", 2, "column 2 (y): empty field");
  expect_samples_refused("x,y,B\n# nothing\n\n", 3, "no data rows");
  // A field's bytes are shown, never sent raw: a NUL had cut the message short before its reason.
  expect_samples_refused(std::string("x,y,B\n0,0,1\n1,0,3\0\n", 19), 3, "column 3 (B): '3\\x00' is not a number");
  expect_samples_refused("x,y,B\n0,0,1\n1,0,\x1b[2J\n", 3, "'\\x1b[2J' is not a number");
  expect_samples_refused("x,y,B\n0,0,1\n1,0,\xff\xfe\n", 3, "'\\xff\\xfe' is not a number");
  expect_samples_refused("x,y,B\n0,0,1\n1,0,\xc3\xa9t\xc3\xa9\n", 3, "'\xc3\xa9t\xc3\xa9' is not a number");  // UTF-8 as it is
  expect_samples_refused("x,y,B\n0,0,1e101\n", 2, "column 3 (B): '1e101' is beyond the largest value, 1e+100");
  expect_samples_refused("x,y,B\n0,0,1\n1,0,1e400\n", 3, "column 3 (B): '1e400' is out of the range of a double");
}

// A value too small for a double is no error: it reads as the nearest double, 0 (an outside-in
// trial's 1e-400 was refused as out of range).
TEST(SamplesIo, ReadsAValueThatUnderflowsAsZero) {
  SamplesIoFiles files;
  const ScatteredSamples s = read_samples_csv(files.write("s.csv", "x,y,B\n0,0,1e-400\n1,-1e-400,2\n0,1,5e-324\n"), nullptr, {});
  ASSERT_EQ(s.points.size(), 3u);
  EXPECT_EQ(s.values, (std::vector<double>{0, 2, std::numeric_limits<double>::denorm_min()}));
  EXPECT_EQ(s.points[1], Vec2(1, 0));
}

// The files people have: a header that does not start with x,y (columns chosen by name), R's
// quoted header, whitespace-separated XYZ without a header (nnbathy, GMT), a byte order mark.
TEST(SamplesIo, ReadsNamedColumnsQuotedHeadersAndXyzFiles) {
  SamplesIoFiles files;
  std::vector<std::string> names;
  const std::string quake = files.write("quake.csv", "long,lat,depth,mag\n174.7,-41.3,12.5,4.1\n175.1,-40.9,30,5.2\n");
  ScatteredSamples s = read_samples_csv(quake, &names, {"LONG", "lat", {"mag"}});
  EXPECT_EQ(names, (std::vector<std::string>{"mag"}));
  EXPECT_EQ(s.points, (std::vector<Vec2>{{174.7, -41.3}, {175.1, -40.9}}));
  EXPECT_EQ(s.values, (std::vector<double>{4.1, 5.2}));
  // Without --x/--y: the first two columns; every other column is a value.
  s = read_samples_csv(quake, &names);
  EXPECT_EQ(names, (std::vector<std::string>{"depth", "mag"}));
  EXPECT_EQ(s.values, (std::vector<double>{12.5, 4.1, 30, 5.2}));
  // Columns named x and y are x and y wherever they stand.
  s = read_samples_csv(files.write("yx.csv", "v,y,x\n1,2,3\n4,5,6\n"), &names);
  EXPECT_EQ(s.points, (std::vector<Vec2>{{3, 2}, {6, 5}}));
  EXPECT_EQ(names, (std::vector<std::string>{"v"}));
  s = read_samples_csv(files.write("r.csv", "\xEF\xBB\xBF\"x\",\"y\",\"elev\"\n1,2,3\n4,5,6\n"), &names);
  EXPECT_EQ(names, (std::vector<std::string>{"elev"}));
  EXPECT_EQ(s.values, (std::vector<double>{3, 6}));
  s = read_samples_csv(files.write("bathy.xyz", "# depth soundings\n0 0  -3.5\n1\t0 -4\n  0 1 -2.25\n"), &names);
  EXPECT_EQ(names, (std::vector<std::string>{"z"}));
  EXPECT_EQ(s.points, (std::vector<Vec2>{{0, 0}, {1, 0}, {0, 1}}));
  EXPECT_EQ(s.values, (std::vector<double>{-3.5, -4, -2.25}));
  const std::string missing = user_error_of([&] { read_samples_csv(quake, nullptr, {"x", "lat", {}}); });
  EXPECT_NE(missing.find("--x"), std::string::npos) << missing;
  EXPECT_NE(missing.find("no column named 'x' (its columns: long, lat, depth, mag)"), std::string::npos) << missing;
  const std::string same = user_error_of([&] { read_samples_csv(quake, nullptr, {"lat", "lat", {}}); });
  EXPECT_NE(same.find("the same column"), std::string::npos) << same;
}

TEST(SamplesIo, RefusesAMissingFile) {
  SamplesIoFiles files;
  const std::string path = files.path("absent.csv");
  const std::string msg = user_error_of([&] { read_samples_csv(path, nullptr); });
  EXPECT_NE(msg.find(path), std::string::npos) << msg;
  EXPECT_NE(msg.find("cannot open"), std::string::npos) << msg;
}

TEST(SamplesIo, MergesDuplicatePointsByAveraging) {
  SamplesIoFiles files;
  const std::string path = files.write("d.csv",
                                       "x,y,a,b\n"
                                       "0,0,1,10\n"
                                       "1,0,2,20\n"
                                       "0,0,3,30\n"
                                       "0,1,4,40\n"
                                       "1,0,5,50\n"
                                       "0.0,0,8,60\n");
  ::testing::internal::CaptureStderr();
  const ScatteredSamples s = read_samples_csv(path, nullptr);
  const std::string warning = ::testing::internal::GetCapturedStderr();
  ASSERT_EQ(s.points.size(), 3u);
  EXPECT_EQ(s.points[0], Vec2(0, 0));
  EXPECT_EQ(s.points[1], Vec2(1, 0));
  EXPECT_EQ(s.points[2], Vec2(0, 1));
  EXPECT_EQ(s.values, (std::vector<double>{4, 100.0 / 3, 3.5, 35, 4, 40}));
  EXPECT_EQ(std::count(warning.begin(), warning.end(), '\n'), 1) << warning;
  EXPECT_NE(warning.find("3 samples"), std::string::npos) << warning;
  EXPECT_NE(warning.find("6 samples -> 3 points"), std::string::npos) << warning;
}

TEST(SamplesIo, NoWarningWithoutDuplicates) {
  SamplesIoFiles files;
  const std::string path = files.write("s.csv", "x,y,B\n0,0,1\n1,0,2\n");
  ::testing::internal::CaptureStderr();
  read_samples_csv(path, nullptr);
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

TEST(SamplesIo, DetectsAShuffledRegularGrid) {
  // A 4 x 3 grid: x in {-1, 0, 1, 2}, y in {0.5, 1.25, 2}; value = 10 x + 100 y, second = -x.
  SamplesIoFiles files;
  const std::string path = files.write("g.csv",
                                       "x,y,v,w\n"
                                       "1,1.25,135,-1\n"
                                       "-1,0.5,40,1\n"
                                       "2,2,220,-2\n"
                                       "0,1.25,125,0\n"
                                       "2,0.5,70,-2\n"
                                       "-1,2,190,1\n"
                                       "1,0.5,60,-1\n"
                                       "0,2,200,0\n"
                                       "-1,1.25,115,1\n"
                                       "0,0.5,50,0\n"
                                       "2,1.25,145,-2\n"
                                       "1,2,210,-1\n");
  const ScatteredSamples s = read_samples_csv(path, nullptr);
  const std::optional<GridNodes> g = as_regular_grid(s);
  ASSERT_TRUE(g.has_value());
  EXPECT_EQ(g->nx, 4);
  EXPECT_EQ(g->ny, 3);
  EXPECT_EQ(g->channels, 2);
  EXPECT_DOUBLE_EQ(g->x0, -1);
  EXPECT_DOUBLE_EQ(g->y0, 0.5);
  EXPECT_DOUBLE_EQ(g->dx, 1);
  EXPECT_DOUBLE_EQ(g->dy, 0.75);
  const std::vector<double> expected = {40, 1,  50, 0,  60, -1,  70, -2,    // y = 0.5
                                        115, 1, 125, 0, 135, -1, 145, -2,   // y = 1.25
                                        190, 1, 200, 0, 210, -1, 220, -2};  // y = 2
  EXPECT_EQ(g->values, expected);
}

TEST(SamplesIo, ReadsQueriesIgnoringExtraColumns) {
  SamplesIoFiles files;
  const std::string path = files.write("q.csv", "# q\nX,Y,label\n0.5,1,first\n\n-2, 3e2 ,second\n");
  const std::vector<Vec2> q = read_queries_csv(path);
  ASSERT_EQ(q.size(), 2u);
  EXPECT_EQ(q[0], Vec2(0.5, 1));
  EXPECT_EQ(q[1], Vec2(-2, 300));

  const std::string bad = files.write("qb.csv", "x,y\n0,0\n1,inf\n");
  const std::string msg = user_error_of([&] { read_queries_csv(bad); });
  EXPECT_NE(msg.find(bad + ":3"), std::string::npos) << msg;
  const std::string empty = files.write("qe.csv", "x,y\n");
  EXPECT_NE(user_error_of([&] { read_queries_csv(empty); }).find("no data rows"), std::string::npos);
  const std::string short_row = files.write("qs.csv", "x,y,z\n1,2\n");
  EXPECT_NE(user_error_of([&] { read_queries_csv(short_row); }).find(short_row + ":2"), std::string::npos);
}

TEST(SamplesIo, ParsesAndChecksRasterOptions) {
  constexpr long long kMaxPoints = 100'000'000;  // parse_size's own bound ("20000x20000" is beyond it)
  const Size2 a = parse_size("400x300", "--raster", kMaxRasterSide, kMaxPoints);
  EXPECT_EQ(a.width, 400);
  EXPECT_EQ(a.height, 300);
  const Size2 b = parse_size("1X20000", "--raster", kMaxRasterSide, kMaxPoints);
  EXPECT_EQ(b.width, 1);
  EXPECT_EQ(b.height, 20000);
  for (const char* bad : {"0x5", "5x0", "20001x2", "-3x4", "4", "4x", "x4", "4x4x4", "a x b", "2.5x3", "", "+4x4",
                          "20000x20000"}) {
    const std::string msg = user_error_of([&] { parse_size(bad, "--raster", kMaxRasterSide, kMaxPoints); });
    EXPECT_NE(msg.find("--raster"), std::string::npos) << "'" << bad << "': " << msg;
  }

  const Rect r = parse_domain(" -1, 0.5 ,2,3e0", "--domain");
  EXPECT_EQ(r.x0, -1);
  EXPECT_EQ(r.y0, 0.5);
  EXPECT_EQ(r.x1, 2);
  EXPECT_EQ(r.y1, 3);
  for (const char* bad : {"0,0,1", "0,0,1,1,1", "1,0,1,1", "0,2,1,1", "0,0,inf,1", "0,nan,1,1", "0,0,1,a", ""}) {
    const std::string msg = user_error_of([&] { parse_domain(bad, "--domain"); });
    EXPECT_NE(msg.find("--domain"), std::string::npos) << "'" << bad << "': " << msg;
  }

  // Cell centres, row by row from y0 upward.
  const std::vector<Vec2> p = raster_points(Raster{2, 3, Rect{0, 10, 4, 16}});
  const std::vector<Vec2> expected = {{1, 11}, {3, 11}, {1, 13}, {3, 13}, {1, 15}, {3, 15}};
  EXPECT_EQ(p, expected);
  // A batch (across a row's end) is that slice of the whole.
  std::vector<Vec2> batch;
  raster_points(Raster{2, 3, Rect{0, 10, 4, 16}}, 1, 4, batch);
  EXPECT_EQ(batch, std::vector<Vec2>(expected.begin() + 1, expected.begin() + 5));
}

TEST(SamplesIo, CsvWriterRoundTrips) {
  SamplesIoFiles files;
  const std::vector<Vec2> points = {{0.1, -2.5}, {1.0 / 3.0, 1e-300}, {123456789.125, 0}};
  const std::vector<double> values = {0.1 + 0.2, -1, std::nan(""), 2.0 / 3.0, 1e300, -0.0};
  const std::string path = files.path("out/v.csv");
  write_values_csv(path, points, values, {"red", "green"});
  EXPECT_EQ(read_bytes(path).substr(0, 12), "x,y,red,gree");
  EXPECT_NE(read_bytes(path).find("\n0.1,-2.5,0.30000000000000004,-1\n"), std::string::npos) << read_bytes(path);
  EXPECT_NE(read_bytes(path).find(",nan,"), std::string::npos) << read_bytes(path);

  // Read it back as samples (no NaN there) and as queries (NaN in an ignored column is fine).
  const std::vector<Vec2> back = read_queries_csv(path);
  EXPECT_EQ(back, points);
  const std::vector<double> finite = {1, 2, 3, 4, 5, 6};
  write_values_csv(path, points, finite, {"a", "b"});
  std::vector<std::string> names;
  const ScatteredSamples s = read_samples_csv(path, &names);
  EXPECT_EQ(names, (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(s.points, points);
  EXPECT_EQ(s.values, finite);
  // No temporary file left beside it.
  EXPECT_EQ(std::distance(fs::directory_iterator(files.path("out")), fs::directory_iterator()), 1);
}

TEST(SamplesIo, PfmLayoutStoresTheY0RowFirst) {
  SamplesIoFiles files;
  const Raster raster{3, 2, Rect{0, 0, 3, 2}};
  // Raster order: the y0 row (10, 11, 12), then the row above (20, 21, 22).
  const std::vector<double> values = {10, 11, 12, 20, 21, 22};
  const std::string path = files.path("r.pfm");
  write_raster_pfm(path, raster, values, 1);
  const std::string bytes = read_bytes(path);
  const std::string header = "Pf\n3 2\n-1.0\n";
  ASSERT_EQ(bytes.size(), header.size() + 6 * 4);
  EXPECT_EQ(bytes.substr(0, header.size()), header);
  const float expected[6] = {10, 11, 12, 20, 21, 22};
  for (int k = 0; k < 6; ++k) {
    const std::string b = bytes.substr(header.size() + 4 * k, 4);
    std::uint32_t bits = 0;
    for (int i = 3; i >= 0; --i) bits = (bits << 8) | static_cast<unsigned char>(b[static_cast<size_t>(i)]);  // LE
    float f;
    std::memcpy(&f, &bits, 4);
    EXPECT_EQ(f, expected[k]) << "float " << k;
  }

  const std::vector<double> rgb(18, 0.5);
  write_raster_pfm(path, raster, rgb, 3);
  EXPECT_EQ(read_bytes(path).substr(0, 11), "PF\n3 2\n-1.0");
  EXPECT_EQ(read_bytes(path).size(), std::string("PF\n3 2\n-1.0\n").size() + 18 * 4);
}

TEST(SamplesIo, PngIsWrittenWithTheRasterSize) {
  SamplesIoFiles files;
  const Raster raster{5, 3, Rect{0, 0, 1, 1}};
  std::vector<double> values(15);
  for (size_t k = 0; k < values.size(); ++k) values[k] = static_cast<double>(k);
  values[3] = std::nan("");
  const std::string path = files.path("r.png");
  write_raster_png(path, raster, values, 1);
  const std::string bytes = read_bytes(path);
  ASSERT_GT(bytes.size(), 24u);
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
  const auto be32 = [&](size_t at) {
    std::uint32_t v = 0;
    for (size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(bytes[at + i]);
    return v;
  };
  EXPECT_EQ(be32(16), 5u);  // IHDR width
  EXPECT_EQ(be32(20), 3u);  // IHDR height
}

}  // namespace samples_csv_test
}  // namespace radrecon
