#pragma once
// The figures of the report (paper/report.h): labelled grids of images with colour scales, and
// the comparison view that shows any two of them side by side, with a slider or by flipping.

#include <sstream>
#include <string>
#include <vector>

#include "paper/report.h"

namespace radrecon {

/// One figure of the report: a row of images per method (FIGURE_STEM + part + ".png" under
/// figures/), all of one data set.
struct FigureSection {
  std::string title;     ///< e.g. "Fig. 3: grid data"
  std::string data_set;  ///< e.g. "grid data", shown in every caption
  const std::vector<ReportRow>* rows = nullptr;
  std::vector<std::string> parts;  ///< of "_view", "_closeup", "_ground", "_difference"
  bool norms = true;               ///< captions give the rows' errors (not for the reference)
};

/// The SVG gradients the colour scales refer to; once per page, before the figures.
std::string colour_scale_definitions();

/// The figure as a grid: column headings, then per method a caption (method, data set, norms)
/// and its images, with a colour scale in W/m^2 beside each radiosity map and a signed one
/// beside each difference image (white point `white_w_m2`); `units_html` under the heading.
void write_figure(std::ostringstream& html, const FigureSection& section, double white_w_m2, const std::string& units_html);

/// The comparison view: every image of `sections` (and the reference's) listed by kind, two
/// chosen at a time. Plain JavaScript, no network. With "?selftest" in the page's address it
/// checks itself on load (every image loaded, no error, no request but for files, the view
/// switches images) and writes "SELFTEST PASS" or "SELFTEST FAIL: reasons" into #selftest.
void write_comparison_view(std::ostringstream& html, const std::vector<FigureSection>& sections);

/// `text` with the characters that HTML gives a meaning (&, <, >, ") escaped.
std::string html_escaped(const std::string& text);

}  // namespace radrecon
