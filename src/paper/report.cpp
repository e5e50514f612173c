#include "paper/report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <optional>
#include <sstream>

#include "io/atomic_file.h"
#include "paper/rankings.h"
#include "paper/report_figures.h"

namespace radrecon {

namespace {

std::string num(double v) {
  if (std::isnan(v)) return "";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}


double value_or_nan(const std::optional<double>& v) { return v ? *v : std::nan(""); }

constexpr const char* kStyle =
    "body{font-family:sans-serif;width:min(96vw,1500px);margin:1.5em auto;line-height:1.4}"
    "h2{margin-top:1.6em}.units{color:#444;font-size:90%;margin:0.2em 0 0.6em}"
    ".fig{display:grid;gap:6px 8px;align-items:start}.fig>*{min-width:0}"
    ".fig img,.fig svg.scale{width:100%;height:auto;display:block}svg.scale text{font-size:9px;fill:#222}"
    ".head{font-weight:bold;font-size:90%;border-bottom:1px solid #bbb;align-self:end}"
    ".cap{font-size:90%}.norms{color:#444;font-size:90%}.noview{color:#777;font-size:85%;align-self:center}"
    "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #bbb;padding:0.2em 0.6em;text-align:right}"
    "td:first-child{text-align:left}.paper{color:#666}caption{font-weight:bold;text-align:left}"
    "td.best{font-weight:bold;background:#e3f1e3}.ranking{max-width:70em}"
    ".cmp-controls{margin:0.5em 0}.cmp-controls label{margin-right:1em}#cmp-stage{max-width:1200px}"
    "#cmp-stage.cmp-side{display:grid;grid-template-columns:1fr 1fr;gap:8px}"
    "#cmp-stage.cmp-slider,#cmp-stage.cmp-flip{position:relative;max-width:800px}"
    ".cmp-pane{margin:0}.cmp-pane img{width:100%;height:auto;display:block}"
    ".cmp-slider .cmp-pane+.cmp-pane,.cmp-flip .cmp-pane+.cmp-pane{position:absolute;top:0;left:0;width:100%}"
    ".cmp-slider figcaption,.cmp-flip figcaption{display:none}#selftest:empty{display:none}";

/// One numeric column of a table: its heading, its value in a row, and which end is best.
struct Column {
  const char* heading;
  std::function<double(const ReportRow&)> value;
  bool larger_is_better = false;
  bool paper = false;
  bool marks_best = true;  ///< its best entry is marked (not for figures of other tables, shown beside)
};

/// A table of `rows`; the paper's columns where it has figures, and with `without` (Table 3's
/// tables: the same methods without barriers, Table 1 or 2) their L1, L2, Linf and SSIM beside,
/// as table3.md has them.
void table(std::ostringstream& html, const std::string& caption, const std::vector<ReportRow>& rows,
           const std::vector<ReportRow>* without = nullptr) {
  std::vector<Column> columns = {
      {"L1", [](const ReportRow& r) { return r.figures.norms.l1; }},
      {"L2 (MSE)", [](const ReportRow& r) { return r.figures.norms.l2; }},
      {"RMSE", [](const ReportRow& r) { return r.figures.norms.rmse; }},
      {"Linf", [](const ReportRow& r) { return r.figures.norms.linf; }},
      {"SSIM", [](const ReportRow& r) { return value_or_nan(r.figures.ssim); }, true},
      {"gradient L2", [](const ReportRow& r) { return value_or_nan(r.figures.gradient_l2); }},
      {"overshoot", [](const ReportRow& r) { return value_or_nan(r.figures.overshoot); }}};
  if (std::any_of(rows.begin(), rows.end(), [](const ReportRow& r) { return !std::isnan(r.paper[0]); })) {
    columns.push_back({"paper L1", [](const ReportRow& r) { return r.paper[0]; }, false, true});
    columns.push_back({"paper L2", [](const ReportRow& r) { return r.paper[1]; }, false, true});
    columns.push_back({"paper Linf", [](const ReportRow& r) { return r.paper[2]; }, false, true});
  }
  if (without != nullptr) {
    // The same method's row without barriers; NaN (shown as a dash) if it has none.
    const auto beside = [without](const std::function<double(const ReportRow&)>& f) {
      return [without, f](const ReportRow& r) {
        for (const ReportRow& w : *without)
          if (w.method == r.method) return f(w);
        return std::numeric_limits<double>::quiet_NaN();
      };
    };
    columns.push_back({"without barriers: L1", beside([](const ReportRow& r) { return r.figures.norms.l1; }), false, false, false});
    columns.push_back({"L2", beside([](const ReportRow& r) { return r.figures.norms.l2; }), false, false, false});
    columns.push_back({"Linf", beside([](const ReportRow& r) { return r.figures.norms.linf; }), false, false, false});
    columns.push_back({"SSIM", beside([](const ReportRow& r) { return value_or_nan(r.figures.ssim); }), true, false, false});
  }
  std::vector<RankedMethod> ranked;
  for (const ReportRow& r : rows)
    ranked.push_back({r.method, {r.figures.norms.l1, r.figures.norms.l2, r.figures.norms.linf}, r.paper});
  std::vector<RankingComparison> ranks;
  for (int norm = 0; norm < 3; ++norm) ranks.push_back(compare_rankings(ranked, norm));
  const bool has_paper = !ranks[0].methods.empty();

  // Each column's best value, marked wherever it occurs (ties alike: four methods share an
  // overshoot of 0), NaN where the column marks none.
  std::vector<double> best;
  for (const Column& c : columns) {
    std::vector<double> values;
    for (const ReportRow& r : rows) values.push_back(c.value(r));
    const int b = c.marks_best ? best_index(values, c.larger_is_better) : -1;
    best.push_back(b >= 0 ? values[static_cast<size_t>(b)] : std::nan(""));
  }
  html << "<table><caption>" << caption << "</caption>\n<tr><th>method</th>";
  for (const Column& c : columns) html << "<th" << (c.paper ? " class=paper" : "") << ">" << c.heading << "</th>";
  if (has_paper)
    for (const char* norm : kRankedNorms) html << "<th>rank " << norm << "<br>ours / paper</th>";
  html << "</tr>\n";
  for (size_t i = 0; i < rows.size(); ++i) {
    html << "<tr><td>" << html_escaped(rows[i].method) << "</td>";
    for (size_t c = 0; c < columns.size(); ++c) {
      const std::vector<std::string> classes = {columns[c].paper ? "paper" : "", columns[c].value(rows[i]) == best[c] ? "best" : ""};
      const std::string cls = classes[0] + (classes[0].empty() || classes[1].empty() ? "" : " ") + classes[1];
      html << "<td" << (cls.empty() ? "" : " class=\"" + cls + "\"") << ">" << num(columns[c].value(rows[i])) << "</td>";
    }
    if (has_paper)
      for (const RankingComparison& k : ranks) {
        std::string cell = "&ndash;";
        for (size_t m = 0; m < k.methods.size(); ++m)
          if (k.methods[m] == rows[i].method) cell = std::to_string(k.ours[m]) + " / " + std::to_string(k.paper[m]);
        html << "<td>" << cell << "</td>";
      }
    html << "</tr>\n";
  }
  html << "</table>\n";
  if (has_paper) html << "<p class=ranking>" << html_escaped(ranking_paragraph(caption.substr(0, caption.find(':')), ranked)) << "</p>\n";
}

std::string units_line(const ReportContent& c) {
  const std::string w = num(c.white_w_m2), q = num(c.white_w_m2 / 4);
  return "<p class=units>Radiosity in W/m<sup>2</sup>. Views and radiosity maps: display = clamp(B / " + w +
         ", 0, 1), sRGB-encoded (black 0, white " + w + " W/m<sup>2</sup>; views with " + std::to_string(c.rays_per_pixel) +
         " rays per pixel). Differences: 0.5 + 2 (B &minus; B<sub>ref</sub>) / " + w + ", linear: mid-grey 0, black &minus;" + q +
         ", white +" + q + " W/m<sup>2</sup>. The ground maps show the 4 m x 4 m ground from above.</p>\n";
}

}  // namespace

void write_report(const std::filesystem::path& dir, const ReportContent& c) {
  const ReportRow reference{"reference", {}, "fig2_reference", {NAN, NAN, NAN}, true};
  const std::vector<ReportRow> reference_rows = {reference};
  const std::vector<std::string> all = {"_view", "_closeup", "_ground", "_difference"};
  std::vector<FigureSection> sections = {
      {"Fig. 2: the reference solution", "the " + c.reference_grid + " solution", &reference_rows, {"_view", "_closeup", "_ground"}, false},
      {"Fig. 3: grid data", "grid data", &c.table1, all},
      {"Fig. 4: quadtree data", "quadtree data", &c.table2, all}};
  const bool barriers = !c.grid_barriers.empty();
  if (barriers) {
    sections.push_back({"Fig. 5: grid data with the scene's barriers, the wall feet", "grid data, barriers", &c.grid_barriers,
                        {"_closeup", "_ground", "_difference"}});
    sections.push_back({"Fig. 6: quadtree data with the scene's barriers", "quadtree data, barriers", &c.quadtree_barriers,
                        {"_closeup", "_ground", "_difference"}});
  }
  if (barriers && !c.grid_border.empty()) {
    sections.push_back({"Fig. 7: grid data with barriers and border samples", "grid data, barriers, border samples",
                        &c.grid_border, {"_ground", "_difference"}});
    sections.push_back({"Fig. 8: quadtree data with barriers and border samples", "quadtree data, barriers, border samples",
                        &c.quadtree_border, {"_ground", "_difference"}});
  }

  std::ostringstream html;
  html << "<!DOCTYPE html>\n<html lang=en><head><meta charset=utf-8><title>radrecon: the paper experiment</title>\n"
       << "<meta name=viewport content=\"width=device-width, initial-scale=1\"><style>" << kStyle << "</style></head><body>\n"
       << colour_scale_definitions()
       << "<h1>Reconstructing radiosity by scattered data interpolation</h1>\n"
       << "<p>After Hinkenjann and Pietrek. The scene: a 4 m x 4 m ground (reflectance 0.5) under a 1 m x 1 m light "
       << "(40 W/m<sup>2</sup>) at 2.5 m, with two perpendicular two-sided walls 1 m high (reflectance 0.5) meeting at "
       << "(2.6, 2.6) m, whose shadows fall beyond them. Radiosity in W/m<sup>2</sup>. Contents: "
       << "<a href=\"#settings\">settings</a>, the figures, <a href=\"#compare\">compare any two pictures</a>, "
       << "<a href=\"#errors\">tables</a>.</p>\n<h2 id=settings>Settings</h2>\n<ul>\n";
  for (const std::string& s : c.settings) html << "<li>" << s << "</li>\n";
  for (const std::string& s : c.notes) html << "<li>" << html_escaped(s) << "</li>\n";
  html << "</ul>\n<section class=figure><h2>Fig. 1: the quadtree of the ground and its sample points</h2>\n"
       << "<img style=\"width:min(40em,90%)\" src=\"figures/fig1_quadtree.png\" alt=\"quadtree of the ground\"></section>\n";
  const std::string units = units_line(c);
  for (const FigureSection& s : sections) write_figure(html, s, c.white_w_m2, units);
  write_comparison_view(html, sections);
  html << "<h2 id=errors>Errors</h2>\n<p>Norms over the reference's cell centres; the best entry of each column is "
       << "marked. The paper's columns are its published tables, for its own scene; the ranks compare the order of the "
       << "methods it ran, 1 = smallest error.</p>\n";
  table(html, "Table 1: reconstruction of grid data", c.table1);
  table(html, "Table 2: reconstruction of quadtree data", c.table2);
  html << "<p class=ranking>" << html_escaped(ranking_reasons(c.reference_grid)) << "</p>\n";
  if (barriers) {
    html << "<p>Table 3: the same data and methods with the scene's barriers: "
         << html_escaped(c.barrier_rule.empty() ? "no sample's influence crosses a wall's foot" : c.barrier_rule) << ".</p>\n";
    table(html, "Table 3a: grid data with barriers", c.grid_barriers, &c.table1);
    table(html, "Table 3b: quadtree data with barriers", c.quadtree_barriers, &c.table2);
    if (!c.grid_border.empty()) {
      table(html, "Table 3c: grid data with barriers and border samples", c.grid_border, &c.table1);
      table(html, "Table 3d: quadtree data with barriers and border samples", c.quadtree_border, &c.table2);
    }
  }
  html << "<p>Methods without paper columns are those the paper cites without running (gouraud, clough-tocher, "
       << "hermite, thin-plate) and those users of scattered-data tools expect (linear, sibson-c1, laplace).</p>\n"
       << "</body></html>\n";
  write_text_file(dir / "report.html", html.str());
}

}  // namespace radrecon
