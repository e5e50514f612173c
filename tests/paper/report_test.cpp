// The report's structure: every figure labelled, a colour scale beside every radiosity map and a
// signed one beside every difference image (their end values computed here from the white point),
// every image listed in the comparison view, the best entry of a column marked.

#include "paper/report.h"
#include "paper/tables.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

namespace radrecon {
namespace report_test {

ReportRow row(const std::string& method, double l1, double l2, double linf, std::array<double, 3> paper, bool views) {
  ReportRow r;
  r.method = method;
  r.figures.norms.l1 = l1;
  r.figures.norms.l2 = l2;
  r.figures.norms.rmse = std::sqrt(l2);
  r.figures.norms.linf = linf;
  r.figures.ssim = 1 - l1;
  r.figure_stem = "figX_" + method;
  r.paper = paper;
  r.views = views;
  return r;
}

std::string written_report(const ReportContent& content) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "radrecon_report_test";
  std::filesystem::create_directories(dir);
  write_report(dir, content);
  std::ifstream in(dir / "report.html");
  std::stringstream text;
  text << in.rdbuf();
  std::filesystem::remove_all(dir);
  return text.str();
}

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

ReportContent content() {
  const double nan = std::nan("");
  ReportContent c;
  c.white_w_m2 = 2.0;
  c.rays_per_pixel = 4;
  c.table1 = {row("constant", 0.03, 0.002, 0.5, {0.01, 0.001, 0.3}, true),
              row("bilinear", 0.02, 0.003, 0.4, {0.02, 0.002, 0.2}, true),
              row("linear", 0.01, 0.004, 0.6, {nan, nan, nan}, false)};
  c.table2 = {row("shepard", 0.05, 0.005, 0.7, {0.07, 0.009, 0.3}, true)};
  return c;
}

TEST(Report, EveryFigureHasHeadingsCaptionsAndScales) {
  const std::string html = written_report(content());
  // Fig. 2 (reference) and Fig. 3, 4 with their column headings.
  for (const char* id : {"id=fig2", "id=fig3", "id=fig4"}) EXPECT_NE(html.find(id), std::string::npos) << id;
  EXPECT_EQ(count(html, "<div class=head>view</div>"), 3u);
  EXPECT_EQ(count(html, "<div class=head>close-up</div>"), 3u);
  EXPECT_EQ(count(html, ">radiosity over the ground, W/m<sup>2</sup></div>"), 3u);
  EXPECT_EQ(count(html, ">difference to the reference, W/m<sup>2</sup></div>"), 2u);
  // A caption per row with its method, data set and norms.
  EXPECT_NE(html.find("<b>bilinear</b><br>grid data<br><span class=norms>L1 0.02 &middot; MSE 0.003 &middot; Linf 0.4"),
            std::string::npos);
  EXPECT_NE(html.find("<b>shepard</b><br>quadtree data<br>"), std::string::npos);
  // Each ground map is followed by a radiosity scale 0 .. white, each difference image by a
  // signed one -white/4 .. +white/4 (white = 2 W/m^2: 0.5).
  const std::regex ground(R"re(_ground\.png"[^>]*><svg class=scale[^>]*aria-label="radiosity scale, W/m\^2: black 0, white 2")re");
  const std::regex difference(
      R"re(_difference\.png"[^>]*><svg class=scale[^>]*aria-label="difference scale, W/m\^2: mid-grey 0, black -0.5, white \+0.5")re");
  EXPECT_EQ(std::distance(std::sregex_iterator(html.begin(), html.end(), ground), std::sregex_iterator()), 5);  // 1 + 3 + 1
  EXPECT_EQ(std::distance(std::sregex_iterator(html.begin(), html.end(), difference), std::sregex_iterator()), 4);
  const std::regex with_alt(R"re(<img [^>]*alt="[^"]+")re");
  EXPECT_EQ(std::distance(std::sregex_iterator(html.begin(), html.end(), with_alt), std::sregex_iterator()),
            static_cast<long>(count(html, "<img "))) << "every image says what it shows";
  EXPECT_NE(html.find("no view: the views show the paper's own methods"), std::string::npos) << "linear has no views";
}

TEST(Report, TiesForBestAreAllMarkedAndTheReferenceGridIsTheRunsOwn) {
  // Two methods share the best L1 (0.01): both marked (the first alone was). A reference of 16 x
  // 16 is named so in Fig. 2 and the ranking note (both said 400 x 400 whatever the run).
  ReportContent c = content();
  c.table1[0].figures.norms.l1 = 0.01;
  c.reference_grid = "16 x 16";
  const std::string html = written_report(c);
  EXPECT_EQ(count(html, "<td class=\"best\">0.01</td>"), 2u);
  EXPECT_NE(html.find("the 16 x 16 solution"), std::string::npos);
  EXPECT_NE(html.find("progressive refinement on a 16 x 16 grid"), std::string::npos);
  EXPECT_EQ(html.find("400 x 400"), std::string::npos);
}

TEST(Report, Table3SaysWhichBarriersAndTheMarkdownSpellsAMissingNormAsTheReportDoes) {
  // A --shadow-barriers run was recorded nowhere (an outside-in trial): the rule says so, and why
  // norms are missing; Markdown wrote "nan" where the report shows "n/a".
  const std::string with_lines = barrier_rule(true), without = barrier_rule(false);
  EXPECT_NE(with_lines.find("shadow lines"), std::string::npos);
  EXPECT_NE(with_lines.find("n/a"), std::string::npos);
  EXPECT_EQ(without.find("shadow"), std::string::npos);
  EXPECT_EQ(format_3g(std::nan("")), "n/a");
  EXPECT_EQ(format_3g(0.0123456), "0.0123");
  ReportContent c = content();
  c.grid_barriers = {row("constant", 0.02, 0.001, 0.6, {NAN, NAN, NAN}, false)};
  c.quadtree_barriers = c.grid_barriers;
  c.barrier_rule = with_lines;
  EXPECT_NE(written_report(c).find("with the scene's barriers: the ground's contact lines with the walls and the direct "
                                   "light's shadow lines"),
            std::string::npos);
}

TEST(Report, TheComparisonViewListsEveryPictureOfTheFigures) {
  const std::string html = written_report(content());
  std::set<std::string> figures, listed;
  const std::regex img(R"re(<img src="(figures/[^"]+\.png)")re"), entry(R"re("src":"(figures/[^"]+\.png)")re");
  for (auto it = std::sregex_iterator(html.begin(), html.end(), img); it != std::sregex_iterator(); ++it)
    figures.insert((*it)[1]);
  for (auto it = std::sregex_iterator(html.begin(), html.end(), entry); it != std::sregex_iterator(); ++it)
    listed.insert((*it)[1]);
  figures.erase("figures/fig1_quadtree.png");  // the quadtree figure is no picture of the radiosity
  EXPECT_EQ(figures, listed);
  EXPECT_EQ(figures.size(), 3u + 2 * 4 + 2 + 4);  // reference 3; constant, bilinear 4 each; linear 2; shepard 4
  EXPECT_EQ(html.find("http"), std::string::npos) << "nothing refers to the network";
}

TEST(Report, TablesMarkTheBestEntryAndGiveBothRankings) {
  const std::string html = written_report(content());
  // Table 1's smallest L1 is linear's 0.01, its smallest MSE constant's 0.002, the paper's
  // smallest L1 constant's 0.01.
  EXPECT_NE(html.find("<tr><td>linear</td><td class=\"best\">0.01</td>"), std::string::npos);
  EXPECT_NE(html.find("<tr><td>constant</td><td>0.03</td><td class=\"best\">0.002</td>"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"paper best\">0.01</td>"), std::string::npos);
  // Ranks among the paper's methods: L1 ours constant 2 / paper 1, bilinear 1 / 2.
  EXPECT_NE(html.find("<td>2 / 1</td>"), std::string::npos);
  EXPECT_NE(html.find("<td>1 / 2</td>"), std::string::npos);
  EXPECT_NE(html.find("L1: the paper ranks constant best, we rank bilinear best"), std::string::npos);
  EXPECT_NE(html.find("the scenes differ"), std::string::npos);
}

TEST(Report, Table3PutsEachMethodsFiguresWithoutBarriersBesideItsOwn) {
  // The paper has no Table 3: its columns were there, empty. Beside each method now its own
  // Table 1 row's L1, L2, Linf and SSIM, as table3.md has them; a method Table 1 lacks, blank.
  const double nan = std::nan("");
  ReportContent c = content();
  c.grid_barriers = {row("constant", 0.025, 0.0015, 0.45, {nan, nan, nan}, true),
                     row("thin-plate", 0.015, 0.001, 0.35, {nan, nan, nan}, false)};
  c.quadtree_barriers = {row("shepard", 0.04, 0.004, 0.6, {nan, nan, nan}, true)};
  const std::string html = written_report(c);
  const size_t at = html.find("<caption>Table 3a");
  ASSERT_NE(at, std::string::npos);
  const std::string table3a = html.substr(at, html.find("</table>", at) - at);
  EXPECT_EQ(table3a.find("paper L1"), std::string::npos);
  EXPECT_NE(table3a.find("<th>without barriers: L1</th><th>L2</th><th>Linf</th><th>SSIM</th>"), std::string::npos);
  // constant: 0.025 | 0.0015 | 0.0387 | 0.45 | 0.975 | (no gradient L2) | (no overshoot), then Table 1's
  // 0.03 | 0.002 | 0.5 | 0.97.
  EXPECT_NE(table3a.find("<td>0.03</td><td>0.002</td><td>0.5</td><td>0.97</td></tr>"), std::string::npos) << table3a;
  EXPECT_NE(table3a.find("<tr><td>thin-plate</td>"), std::string::npos);
  EXPECT_EQ(count(table3a, "<td></td><td></td><td></td><td></td></tr>"), 1u);  // thin-plate: not in Table 1
  EXPECT_NE(html.find("<td>0.05</td><td>0.005</td><td>0.7</td><td>0.95</td></tr>"), std::string::npos);  // Table 3b
}

}  // namespace report_test
}  // namespace radrecon
