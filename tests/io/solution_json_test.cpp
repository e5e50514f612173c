// Solution files: what is written reads back to the same numbers, and a malformed file is
// refused naming the file and the field (or the line).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "io/solution_json.h"
#include "support/temp_dir.h"

namespace radrecon {
namespace solution_json_test {

namespace fs = std::filesystem;

class SolutionFiles : public ::testing::Test {
 protected:
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }
  /// The message of reading `text` as a solution file, or "" if it is accepted.
  std::string refusal(const std::string& text) const {
    return testing_support::user_error_message([&] { read_solution_json(write("s.json", text)); });
  }
  testing_support::TempDir dir_{"radrecon_solution_json_test"};
};

/// A 2 x 1 grid side, elements in row order, as the writer lays it out.
Solution two_element_grid() {
  Solution sol;
  sol.scene = "test";
  sol.mesh = "grid:2";
  SurfaceSolution s;
  s.name = "floor";
  s.scene_surface = "floor";
  s.grid_nu = 2;
  s.grid_nv = 1;
  s.length_u_m = 2;
  s.length_v_m = 1;
  s.elements.push_back({{0, 0, 0.5, 1}, Vec3(0.5, 0.5, 0), 1.0, Rgb(0.1, 1.0 / 3, 2e-300)});
  s.elements.push_back({{0.5, 0, 1, 1}, Vec3(1.5, 0.5, 0), 1.0, Rgb(7, 8, 9)});
  sol.surfaces.push_back(s);
  sol.stats.method = "progressive";
  sol.stats.converged = false;
  return sol;
}

TEST_F(SolutionFiles, WhatIsWrittenReadsBack) {
  const fs::path path = dir_ / "round.json";
  write_solution_json(path, two_element_grid());
  const Solution back = read_solution_json(path);
  ASSERT_EQ(back.surfaces.size(), 1u);
  const SurfaceSolution& s = back.surfaces[0];
  EXPECT_EQ(s.name, "floor");
  EXPECT_EQ(s.grid_nu, 2);
  EXPECT_EQ(s.grid_nv, 1);
  ASSERT_EQ(s.elements.size(), 2u);
  EXPECT_EQ(s.elements[1].u0, 0.5);
  // Radiosity is written with 9 significant digits (float precision is ample for W/m^2).
  EXPECT_NEAR(s.elements[0].radiosity_w_m2[1], 1.0 / 3, 1e-9);
  EXPECT_EQ(s.elements[1].radiosity_w_m2[2], 9.0);
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\"converged\": false"), std::string::npos);
}

TEST_F(SolutionFiles, StatisticsAreHandedOnAsTheFileHasThem) {
  // For Python's load_solution(): the file's statistics, as written (they are not read into the
  // solution: a loaded one reported 0 shots and "converged" for a file without them).
  Solution sol = two_element_grid();
  sol.stats.method = "hierarchical";
  sol.stats.links = 12345;
  sol.stats.epsilon_w = 2.5e-7;
  sol.stats.emitted_w = Rgb(1, 2, 3);
  sol.stats.residual = 3e-5;
  sol.stats.converged = false;
  const fs::path path = dir_ / "stats.json";
  write_solution_json(path, sol);
  std::string text;
  read_solution_json(path, &text);
  const nlohmann::json stats = nlohmann::json::parse(text);
  EXPECT_EQ(stats["method"], "hierarchical");
  EXPECT_EQ(stats["links"], 12345);
  EXPECT_DOUBLE_EQ(stats["epsilon_w"].get<double>(), 2.5e-7);
  EXPECT_EQ(stats["emitted_w"][2], 3.0);
  EXPECT_DOUBLE_EQ(stats["residual"].get<double>(), 3e-5);
  EXPECT_EQ(stats["converged"], false);
  // Statistics of any shape do not stop a file from being read (render and export never use
  // them; a tool that rewrote 408 shots as 408.0 made render refuse the file: a review), and a
  // file without them hands on none.
  const std::string side = R"({"surfaces": [{"name": "a", "length_u_m": 1, "length_v_m": 1, "elements": [{"u0": 0, "v0": 0, "u1": 1, "v1": 1, "center": [0,0,0], "area": 1, "radiosity": [1,1,1]}]}])";
  EXPECT_EQ(refusal(side + R"(, "stats": {"shots": 408.0, "residual": -1, "converged": 1}})"), "");
  EXPECT_EQ(refusal(side + R"(, "stats": []})"), "");
  read_solution_json(write("none.json", side + "}"), &text);
  EXPECT_EQ(text, "");
}

TEST_F(SolutionFiles, NegativeRadiosityIsClampedToZeroAndThenReadsBack) {
  // A solution file refuses negative radiosity; solve_scene() sets any a solver gave to 0 first.
  Solution sol = two_element_grid();
  sol.surfaces[0].elements[0].radiosity_w_m2 = Rgb(-1e-17, 0.25, -0.5);
  EXPECT_NE(refusal([&] {
              write_solution_json(dir_ / "negative.json", sol);
              std::ifstream in(dir_ / "negative.json");
              return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
            }()),
            "");
  const NegativeRadiosity found = clamp_negative_radiosity(sol);
  EXPECT_EQ(found.count, 2u);
  EXPECT_EQ(found.most_negative_w_m2, -0.5);
  write_solution_json(dir_ / "clamped.json", sol);
  const Solution back = read_solution_json(dir_ / "clamped.json");
  EXPECT_EQ(back.surfaces[0].elements[0].radiosity_w_m2[0], 0.0);
  EXPECT_EQ(back.surfaces[0].elements[0].radiosity_w_m2[1], 0.25);
  EXPECT_EQ(back.surfaces[0].elements[0].radiosity_w_m2[2], 0.0);
  EXPECT_EQ(back.surfaces[0].elements[1].radiosity_w_m2[2], 9.0);  // the rest as it was
  EXPECT_EQ(clamp_negative_radiosity(sol).count, 0u);
}

// The elements' numbers are printf's text, %.17g for the rectangle and %.9g for the rest
// (std::to_chars writes them): element by element against snprintf, over magnitudes from
// subnormal to huge, both signs, integers and fractions, across the buffer's flushes.
TEST_F(SolutionFiles, ElementNumbersAreWrittenAsPrintfWritesThem) {
  Solution sol = two_element_grid();
  SurfaceSolution& s = sol.surfaces[0];
  s.elements.clear();
  const double values[] = {0.0, -0.0, 1.0, 0.1, 1.0 / 3, -2.5e-7, 123456789.0, 1e21, 4.9e-324, 2e-300, 6.02214076e23, -7.0 / 9};
  // Enough elements that the writer's buffer is flushed several times (64 KiB each), and a
  // triangle's shape among them.
  for (int repeat = 0; repeat < 30; ++repeat)
    for (const double a : values)
      for (const double b : {values[4], values[9], values[11]})
        s.elements.push_back({{a, b, -a, 1 / (1 + std::abs(a)) + repeat}, Vec3(a, b, a * b), std::abs(b), Rgb(a, b, a - b)});
  s.elements[5].shape = CellShape::lower;
  const fs::path path = dir_ / "text.json";
  write_solution_json(path, sol);
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  size_t at = 0;
  ASSERT_GT(text.size(), size_t{3} << 16);
  for (const SolutionElement& el : s.elements) {
    char want[512];
    std::snprintf(want, sizeof want,
                  "{\"u0\": %.17g, \"v0\": %.17g, \"u1\": %.17g, \"v1\": %.17g, %s\"center\": [%.9g, %.9g, %.9g], "
                  "\"area\": %.9g, \"radiosity\": [%.9g, %.9g, %.9g]}",
                  el.u0, el.v0, el.u1, el.v1, el.is_triangle() ? "\"shape\": \"lower\", " : "", el.center.x(),
                  el.center.y(), el.center.z(), el.area_m2, el.radiosity_w_m2[0], el.radiosity_w_m2[1],
                  el.radiosity_w_m2[2]);
    const size_t found = text.find(want, at);
    ASSERT_NE(found, std::string::npos) << "missing: " << want;
    at = found + 1;
  }
}

TEST_F(SolutionFiles, BarriersAndExcludedRegionsReadBackToTheLastBit) {
  Solution sol = two_element_grid();
  SurfaceSolution& s = sol.surfaces[0];
  s.barriers = {{Vec2(0.5, 0), Vec2(0.5, 1.0 / 3)}, {Vec2(0.1, 0.2), Vec2(0.3, 0.2), Vec2(0.3, 0.7)}};
  s.excluded = {{Vec2(0.1, 0.1), Vec2(0.4, 0.1), Vec2(0.4, 2.0 / 3), Vec2(0.1, 2.0 / 3)},
                {Vec2(1.2, 0.2), Vec2(1.9, 0.2), Vec2(1.5, 1e-300)}};
  const fs::path path = dir_ / "regions.json";
  write_solution_json(path, sol);
  const Solution read = read_solution_json(path);
  const SurfaceSolution& back = read.surfaces[0];
  EXPECT_EQ(back.barriers, s.barriers);
  EXPECT_EQ(back.excluded, s.excluded);
  // None is written as an empty list, and read back as none.
  s.barriers.clear();
  s.excluded.clear();
  write_solution_json(path, sol);
  const Solution reread = read_solution_json(path);
  const SurfaceSolution& none = reread.surfaces[0];
  EXPECT_TRUE(none.barriers.empty());
  EXPECT_TRUE(none.excluded.empty());
}

TEST_F(SolutionFiles, MalformedFilesAreRefusedWithTheFieldOrLine) {
  const std::string element = R"({"u0": 0, "v0": 0, "u1": 1, "v1": 1, "center": [0,0,0], "area": 1, "radiosity": [1,1,1]})";
  auto side = [&](const std::string& name, const std::string& grid, const std::string& elements) {
    return R"({"name": ")" + name + R"(", "length_u_m": 1, "length_v_m": 1, "grid": )" + grid +
           R"(, "elements": [)" + elements + "]}";
  };
  EXPECT_EQ(refusal(R"({"surfaces": [)" + side("a", "[1, 1]", element) + "]}"), "");
  // A radiosity beyond the samples' bound: reconstructions would overflow on it.
  const std::string huge = R"({"u0": 0, "v0": 0, "u1": 1, "v1": 1, "center": [0,0,0], "area": 1, "radiosity": [1,1e308,1]})";
  EXPECT_NE(refusal(R"({"surfaces": [)" + side("a", "[1, 1]", huge) + "]}").find("surfaces[0].elements[0].radiosity: beyond the largest value"),
            std::string::npos);
  // Negative radiosity (a hand-edited file) rendered with exit 0: refused where it is.
  const std::string negative = R"({"u0": 0, "v0": 0, "u1": 1, "v1": 1, "center": [0,0,0], "area": 1, "radiosity": [1,-1e-9,1]})";
  EXPECT_NE(refusal(R"({"surfaces": [)" + side("a", "[1, 1]", negative) + "]}").find("surfaces[0].elements[0].radiosity: must not be negative"),
            std::string::npos);
  // A barrier segment of zero length: every method fell back to piecewise constant on the side.
  const std::string zero_barrier = R"({"surfaces": [{"name": "a", "length_u_m": 1, "length_v_m": 1, "barriers": [[[0, 0], [1, 1]], [[0.5, 0], [0.5, 0], [0.5, 1]]], "elements": [)" +
                                   element + "]}]}";
  EXPECT_NE(refusal(zero_barrier).find("surfaces[0].barriers[1][1]: repeats the point before it"), std::string::npos);
  // No sides: render and export had drawn nothing with exit 0, or aborted.
  EXPECT_NE(refusal(R"({"scene": "paper", "surfaces": []})").find("surfaces: must be a non-empty array"), std::string::npos);
  // Excluded regions are optional; when present, polygons of at least 3 points [s, t].
  auto with_excluded = [&](const std::string& excluded) {
    return R"({"surfaces": [{"name": "a", "length_u_m": 1, "length_v_m": 1, "excluded": )" + excluded +
           R"(, "elements": [)" + element + "]}]}";
  };
  EXPECT_EQ(refusal(with_excluded("[]")), "");
  EXPECT_EQ(refusal(with_excluded("[[[0, 0], [1, 0], [1, 1]]]")), "");
  EXPECT_NE(refusal(with_excluded("{}")).find("surfaces[0].excluded: must be an array of polygons"), std::string::npos);
  EXPECT_NE(refusal(with_excluded("[[[0, 0], [1, 0], [1, 1]], [[0, 0], [1, 0]]]"))
                .find("surfaces[0].excluded[1]: must be a polygon of at least 3 points"),
            std::string::npos);
  EXPECT_NE(refusal(with_excluded("[[[0, 0], [1, 0], [1]]]")).find("surfaces[0].excluded[0][2]: must be a point [s, t]"),
            std::string::npos);
  EXPECT_NE(refusal(with_excluded(R"([[[0, 0], [1, 0], [1, "x"]]])")).find("surfaces[0].excluded[0][2][1]: must be a number"),
            std::string::npos);
  EXPECT_NE(refusal(with_excluded("[[[0, 0], [1, 0], [1, 1e999]]]")).find("number overflow parsing '1e999'"),
            std::string::npos);
  // Invalid JSON: the line.
  EXPECT_NE(refusal("{\n\"surfaces\": [\n,]}").find("s.json:3"), std::string::npos);
  // A missing field: its path.
  EXPECT_NE(refusal(R"({"surfaces": [{"name": "a"}]})").find("surfaces[0].length_u_m: missing"), std::string::npos);
  // The same side twice.
  EXPECT_NE(refusal(R"({"surfaces": [)" + side("a", "[0, 0]", element) + "," + side("a", "[0, 0]", element) + "]}")
                .find("duplicate surface side 'a'"),
            std::string::npos);
  // A grid whose elements are not stored row by row.
  const std::string e0 = R"({"u0": 0, "v0": 0, "u1": 0.5, "v1": 1, "center": [0,0,0], "area": 1, "radiosity": [1,1,1]})";
  const std::string e1 = R"({"u0": 0.5, "v0": 0, "u1": 1, "v1": 1, "center": [0,0,0], "area": 1, "radiosity": [1,1,1]})";
  EXPECT_EQ(refusal(R"({"surfaces": [)" + side("a", "[2, 1]", e0 + "," + e1) + "]}"), "");
  EXPECT_NE(refusal(R"({"surfaces": [)" + side("a", "[2, 1]", e1 + "," + e0) + "]}").find("surfaces[0].elements[0]"),
            std::string::npos);
  // A number too large for a double: the line, and the number.
  EXPECT_NE(refusal("{\"surfaces\": [],\n \"x\": 1e999}").find("s.json:2: not a valid solution: number overflow parsing '1e999'"),
            std::string::npos);
}

TEST_F(SolutionFiles, ATrianglesSideReadsBackWithItsShapesAndShear) {
  Solution sol = two_element_grid();
  SurfaceSolution& s = sol.surfaces[0];
  s.grid_nu = s.grid_nv = 0;
  s.triangle = true;
  s.shear_m = 0.25;
  s.elements[0] = {{0, 0, 1, 1, CellShape::lower}, Vec3(0.3, 0.3, 0), 0.5, Rgb(1, 2, 3)};
  s.elements.resize(1);
  const fs::path path = dir_ / "triangle.json";
  write_solution_json(path, sol);
  const Solution back = read_solution_json(path);
  const SurfaceSolution& b = back.surfaces[0];
  EXPECT_TRUE(b.triangle);
  EXPECT_EQ(b.shear_m, 0.25);
  EXPECT_EQ(b.elements[0].shape, CellShape::lower);
  // Shapes must fit the side: an upper half of the whole box lies beyond the hypotenuse; a box
  // on a triangle's side, a half on a quad's, and a grid on a triangle's are refused.
  auto side = [](const std::string& extra, const std::string& shape, const std::string& grid) {
    return R"({"surfaces": [{"name": "a", "length_u_m": 1, "length_v_m": 1, "grid": )" + grid + extra +
           R"(, "elements": [{"u0": 0, "v0": 0, "u1": 1, "v1": 1, )" + shape +
           R"("center": [0,0,0], "area": 1, "radiosity": [1,1,1]}]}]})";
  };
  const std::string triangle = R"(, "triangle": true, "shear_m": 0.5)";
  EXPECT_EQ(refusal(side(triangle, R"("shape": "lower", )", "[0, 0]")), "");
  EXPECT_NE(refusal(side(triangle, R"("shape": "upper", )", "[0, 0]")).find("beyond the triangle's parameter domain"), std::string::npos);
  EXPECT_NE(refusal(side(triangle, "", "[0, 0]")).find("must be \"lower\" or \"upper\""), std::string::npos);
  EXPECT_NE(refusal(side("", R"("shape": "lower", )", "[0, 0]")).find("must be \"box\""), std::string::npos);
  EXPECT_NE(refusal(side(triangle, R"("shape": "lower", )", "[1, 1]")).find("must be [0, 0] on a triangle's side"), std::string::npos);
  EXPECT_NE(refusal(side(triangle, R"("shape": "lozenge", )", "[0, 0]")).find("elements[0].shape"), std::string::npos);
  EXPECT_NE(refusal(side(R"(, "shear_m": 0.5)", "", "[0, 0]")).find("shear_m"), std::string::npos);
}

}  // namespace solution_json_test
}  // namespace radrecon
