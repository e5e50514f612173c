#include "paper/report.h"

#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <optional>
#include <sstream>

#include "io/atomic_file.h"

namespace radrecon {

namespace {

/// `text` with the characters that HTML gives a meaning (&, <, >, ") escaped.
std::string html_escaped(const std::string& text) {
  std::string out;
  for (char ch : text) {
    switch (ch) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += ch;
    }
  }
  return out;
}

std::string num(double v) {
  if (std::isnan(v)) return "";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

std::string num(const std::optional<double>& v) { return v ? num(*v) : "n/a"; }

void table(std::ostringstream& html, const std::string& caption, const std::vector<ReportRow>& rows) {
  html << "<table><caption>" << caption << "</caption>\n<tr><th>method</th><th>L1</th><th>L2 (MSE)</th><th>RMSE</th>"
       << "<th>Linf</th><th>SSIM</th><th>gradient L2</th><th>overshoot</th><th class=paper>paper L1</th>"
       << "<th class=paper>paper L2</th><th class=paper>paper Linf</th></tr>\n";
  for (const ReportRow& r : rows) {
    const Figures& f = r.figures;
    html << "<tr><td>" << r.method << "</td><td>" << num(f.norms.l1) << "</td><td>" << num(f.norms.l2) << "</td><td>"
         << num(f.norms.rmse) << "</td><td>" << num(f.norms.linf) << "</td><td>" << num(f.ssim) << "</td><td>"
         << num(f.gradient_l2) << "</td><td>" << num(f.overshoot) << "</td><td class=paper>" << num(r.paper[0])
         << "</td><td class=paper>" << num(r.paper[1]) << "</td><td class=paper>" << num(r.paper[2]) << "</td></tr>\n";
  }
  html << "</table>\n";
}

/// Each row's figures: FIGURE_STEM + each of `parts` + ".png".
void figure_rows(std::ostringstream& html, const std::vector<ReportRow>& rows,
                 std::initializer_list<const char*> parts = {"_view", "_closeup", "_ground", "_difference"}) {
  html << "<div class=grid>\n";
  for (const ReportRow& r : rows) {
    html << "<div class=label>" << r.method << "</div>";
    for (const char* part : parts) {
      const std::string name = part;
      if (!r.views && (name == "_view" || name == "_closeup")) {
        html << "<span class=noview>" << (name == "_view" ? "ground figures only (views: the paper's methods)" : "")
             << "</span>";
        continue;
      }
      html << "<img src=\"figures/" << r.figure_stem << part << ".png\" alt=\"" << r.method << part << "\">";
    }
    html << "\n";
  }
  html << "</div>\n";
}

}  // namespace

void write_report(const std::filesystem::path& dir, const ReportContent& c) {
  std::ostringstream html;
  html << "<!DOCTYPE html>\n<html lang=en><head><meta charset=utf-8><title>radrecon: the paper experiment</title>\n"
       << "<style>body{font-family:sans-serif;max-width:1200px;margin:2em auto;line-height:1.4}"
       << "img{width:24%;margin:0.25%;image-rendering:auto}"
       << ".noview{display:inline-block;width:24%;margin:0.25%;vertical-align:middle;color:#777;font-size:90%}.grid{display:block}.label{font-weight:bold;margin-top:0.8em}"
       << "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #bbb;padding:0.2em 0.6em;text-align:right}"
       << "td:first-child{text-align:left}.paper{color:#777}caption{font-weight:bold;text-align:left}</style></head><body>\n"
       << "<h1>Reconstructing radiosity by scattered data interpolation</h1>\n"
       << "<p>After Hinkenjann and Pietrek. The scene: a 4 m x 4 m ground (reflectance 0.5) under a 1 m x 1 m light "
       << "(40 W/m<sup>2</sup>) at 2.5 m, with two perpendicular two-sided walls 1 m high (reflectance 0.5) meeting at "
       << "(2.6, 2.6) m, whose shadows fall beyond them. Radiosity in W/m<sup>2</sup>.</p>\n<h2>Settings</h2>\n<ul>\n";
  for (const std::string& s : c.settings) html << "<li>" << s << "</li>\n";
  for (const std::string& s : c.notes) html << "<li>" << html_escaped(s) << "</li>\n";
  html << "</ul>\n<h2>Fig. 1: the quadtree of the ground and its sample points</h2>\n"
       << "<img style=\"width:40%\" src=\"figures/fig1_quadtree.png\" alt=quadtree>\n"
       << "<h2>Fig. 2: reference solution (view, close-up, radiosity over the ground)</h2>\n"
       << "<img src=\"figures/fig2_reference_view.png\" alt=view><img src=\"figures/fig2_reference_closeup.png\" alt=closeup>"
       << "<img src=\"figures/fig2_reference_ground.png\" alt=ground>\n"
       << "<h2>Fig. 3: grid data (view, close-up, ground, difference x 2 against the reference, mid-grey = 0)</h2>\n";
  figure_rows(html, c.table1);
  html << "<h2>Fig. 4: quadtree data</h2>\n";
  figure_rows(html, c.table2);
  const bool barriers = !c.grid_barriers.empty();
  if (barriers) {
    html << "<h2>Fig. 5: grid data with the scene's barriers, the wall feet (close-up, ground, difference)</h2>\n";
    figure_rows(html, c.grid_barriers, {"_closeup", "_ground", "_difference"});
    html << "<h2>Fig. 6: quadtree data with the scene's barriers</h2>\n";
    figure_rows(html, c.quadtree_barriers, {"_closeup", "_ground", "_difference"});
    if (!c.grid_border.empty()) {
      html << "<h2>Fig. 7: grid data with barriers and border samples (ground, difference)</h2>\n";
      figure_rows(html, c.grid_border, {"_ground", "_difference"});
      html << "<h2>Fig. 8: quadtree data with barriers and border samples</h2>\n";
      figure_rows(html, c.quadtree_border, {"_ground", "_difference"});
    }
  }
  html << "<h2>Errors</h2>\n";
  table(html, "Table 1: reconstruction of grid data", c.table1);
  table(html, "Table 2: reconstruction of quadtree data", c.table2);
  if (barriers) {
    html << "<p>Table 3: the same data and methods with the scene's barriers; no sample's influence crosses a wall's "
            "foot.</p>\n";
    table(html, "Table 3a: grid data with barriers", c.grid_barriers);
    table(html, "Table 3b: quadtree data with barriers", c.quadtree_barriers);
    if (!c.grid_border.empty()) {
      table(html, "Table 3c: grid data with barriers and border samples", c.grid_border);
      table(html, "Table 3d: quadtree data with barriers and border samples", c.quadtree_border);
    }
  }
  html << "<p>The paper's columns are its published tables, for its own scene: compare rankings, not values. "
       << "Methods without paper columns are those the paper cites without running (gouraud, clough-tocher, hermite, "
       << "thin-plate) and those users of scattered-data tools expect (linear, sibson-c1, laplace).</p>\n"
       << "</body></html>\n";
  write_text_file(dir / "report.html", html.str());
}

}  // namespace radrecon
