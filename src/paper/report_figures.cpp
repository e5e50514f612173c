#include "paper/report_figures.h"

#include <cmath>
#include <cstdio>

#include "core/image.h"

namespace radrecon {

namespace {

std::string g3(double v) {
  if (!std::isfinite(v)) return "n/a";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

std::string g3(const std::optional<double>& v) { return v ? g3(*v) : "n/a"; }

/// A column heading and how wide the column is (its images' aspect: a view is 4:3, a ground
/// map square, so that every image of a row has the same height).
struct Part {
  const char* heading;
  const char* width;    ///< grid track of the image
  bool scale = false;   ///< a colour scale column follows
  const char* kind;     ///< the comparison view's kind
};

Part part_of(const std::string& part) {
  if (part == "_view") return {"view", "4fr", false, "view"};
  if (part == "_closeup") return {"close-up", "4fr", false, "closeup"};
  if (part == "_ground") return {"radiosity over the ground, W/m<sup>2</sup>", "3fr", true, "ground"};
  return {"difference to the reference, W/m<sup>2</sup>", "3fr", true, "difference"};
}

/// Width of a colour scale column: its SVG is 48 x 200 units, so 3fr x 48 / 200 = 0.72fr makes it as
/// tall as a ground map.
constexpr const char* kScaleTrack = "0.72fr";

/// A vertical colour scale: the gradient `gradient` from bottom to top, labelled at the bottom,
/// the middle and the top.
std::string scale_svg(const char* gradient, const std::string& bottom, const std::string& middle, const std::string& top,
                      const std::string& title) {
  return "<svg class=scale viewBox=\"0 0 48 200\" role=img aria-label=\"" + html_escaped(title) + "\"><title>" +
         html_escaped(title) + "</title><rect x=\"1\" y=\"5\" width=\"10\" height=\"190\" fill=\"url(#" + gradient +
         ")\" stroke=\"#888\" stroke-width=\"0.5\"/><text x=\"13\" y=\"12\">" + top + "</text><text x=\"13\" y=\"103\">" +
         middle + "</text><text x=\"13\" y=\"195\">" + bottom + "</text></svg>";
}

std::string caption(const ReportRow& r, const std::string& data_set, bool norms) {
  const Figures& f = r.figures;
  if (!norms) return "<div class=cap><b>" + html_escaped(r.method) + "</b><br>" + html_escaped(data_set) + "</div>";
  return "<div class=cap><b>" + html_escaped(r.method) + "</b><br>" + html_escaped(data_set) + "<br><span class=norms>L1 " +
         g3(f.norms.l1) + " &middot; MSE " + g3(f.norms.l2) + " &middot; Linf " + g3(f.norms.linf) + " &middot; SSIM " +
         g3(f.ssim) + "</span></div>";
}

}  // namespace

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

std::string colour_scale_definitions() {
  // The radiosity maps are tone_map() then the sRGB curve: the stops follow the curve, so the
  // scale's grey at height h is what a map shows for h x white.
  std::string radiosity = "<linearGradient id=rr-radiosity x1=0 y1=1 x2=0 y2=0>";
  for (int k = 0; k <= 10; ++k) {
    const int grey = static_cast<int>(std::lround(255 * srgb_encode(k / 10.0)));
    char stop[96];
    std::snprintf(stop, sizeof stop, "<stop offset=\"%.1f\" stop-color=\"rgb(%d,%d,%d)\"/>", k / 10.0, grey, grey, grey);
    radiosity += stop;
  }
  radiosity += "</linearGradient>";
  // The difference images are written linearly: black -white/4, mid-grey 0, white +white/4.
  const std::string difference =
      "<linearGradient id=rr-difference x1=0 y1=1 x2=0 y2=0><stop offset=0 stop-color=\"#000\"/>"
      "<stop offset=1 stop-color=\"#fff\"/></linearGradient>";
  return "<svg width=0 height=0 style=\"position:absolute\" aria-hidden=true><defs>" + radiosity + difference +
         "</defs></svg>\n";
}

void write_figure(std::ostringstream& html, const FigureSection& section, double white_w_m2, const std::string& units_html) {
  std::string tracks = "minmax(8em,1.1fr)";
  for (const std::string& p : section.parts) {
    const Part part = part_of(p);
    tracks += std::string(" ") + part.width + (part.scale ? std::string(" ") + kScaleTrack : "");
  }
  // "Fig. 3: ..." is #fig3.
  const size_t digits = section.title.find_first_of("0123456789");
  const std::string id = digits == std::string::npos ? "" : "fig" + section.title.substr(digits, section.title.find(':') - digits);
  html << "<section class=figure" << (id.empty() ? "" : " id=" + id) << "><h2>" << section.title << "</h2>\n" << units_html << "<div class=fig style=\"grid-template-columns:" << tracks
       << "\">\n<div class=head>method, data set, errors</div>";
  for (const std::string& p : section.parts) {
    const Part part = part_of(p);
    html << "<div class=head" << (part.scale ? " style=\"grid-column:span 2\"" : "") << ">" << part.heading << "</div>";
  }
  html << "\n";
  const std::string radiosity_scale =
      scale_svg("rr-radiosity", "0", g3(white_w_m2 / 2), g3(white_w_m2), "radiosity scale, W/m^2: black 0, white " + g3(white_w_m2));
  const std::string difference_scale =
      scale_svg("rr-difference", "&minus;" + g3(white_w_m2 / 4), "0", "+" + g3(white_w_m2 / 4),
                "difference scale, W/m^2: mid-grey 0, black -" + g3(white_w_m2 / 4) + ", white +" + g3(white_w_m2 / 4));
  for (const ReportRow& r : *section.rows) {
    html << caption(r, section.data_set, section.norms);
    for (const std::string& p : section.parts) {
      const Part part = part_of(p);
      if (!r.views && (p == "_view" || p == "_closeup")) {
        html << "<div class=noview>" << (p == "_view" ? "no view: the views show the paper's own methods" : "") << "</div>";
        continue;
      }
      html << "<img src=\"figures/" << r.figure_stem << p << ".png\" alt=\"" << html_escaped(r.method) << ", "
           << html_escaped(section.data_set) << ": " << part.kind << "\">";
      if (part.scale) html << (p == "_ground" ? radiosity_scale : difference_scale);
    }
    html << "\n";
  }
  html << "</div></section>\n";
}

namespace {

/// The comparison view's script: data-driven (the JSON in #cmp-data), so every data set and
/// method the report holds appears without changes here.
constexpr const char* kComparisonScript = R"JS(
(function () {
  'use strict';
  var errors = [];
  window.addEventListener('error', function (e) { errors.push('error: ' + (e.message || (e.target && e.target.src) || e)); }, true);
  var consoleError = console.error;
  console.error = function () { errors.push('console: ' + Array.prototype.join.call(arguments, ' ')); consoleError.apply(console, arguments); };
  var $ = function (id) { return document.getElementById(id); };
  var data = JSON.parse($('cmp-data').textContent);
  var names = {view: 'view', closeup: 'close-up', ground: 'radiosity over the ground', difference: 'difference to the reference'};
  var kind = $('cmp-kind'), a = $('cmp-a'), b = $('cmp-b'), mode = $('cmp-mode'), slider = $('cmp-slider');
  var flip = $('cmp-flip'), stage = $('cmp-stage'), imgA = $('cmp-img-a'), imgB = $('cmp-img-b');
  var flipped = false;
  var kinds = [];
  data.forEach(function (d) { if (kinds.indexOf(d.k) < 0) kinds.push(d.k); });
  kinds.forEach(function (k) {
    var o = document.createElement('option'); o.value = k; o.textContent = names[k] || k; kind.appendChild(o);
  });
  function entries() { return data.filter(function (d) { return d.k === kind.value; }); }
  function fill() {
    var list = entries();
    [a, b].forEach(function (select, n) {
      select.textContent = '';
      list.forEach(function (d, i) {
        var o = document.createElement('option'); o.value = String(i); o.textContent = d.label; select.appendChild(o);
      });
      select.value = String(Math.min(n, list.length - 1));
    });
    show();
  }
  function show() {
    var list = entries(), da = list[Number(a.value)], db = list[Number(b.value)];
    imgA.src = da.src; imgA.alt = da.label; imgB.src = db.src; imgB.alt = db.label;
    $('cmp-label-a').textContent = 'A: ' + da.label; $('cmp-label-b').textContent = 'B: ' + db.label;
    stage.className = 'cmp-' + mode.value;
    slider.hidden = mode.value !== 'slider'; flip.hidden = mode.value !== 'flip';
    imgB.parentNode.style.clipPath = mode.value === 'slider' ? 'inset(0 0 0 ' + slider.value + '%)' : '';
    imgB.parentNode.style.visibility = mode.value === 'flip' && !flipped ? 'hidden' : '';
    var both = 'A: ' + da.label + ' | B: ' + db.label;
    $('cmp-showing').textContent = mode.value === 'flip' ? both + (flipped ? ' (showing B)' : ' (showing A)') :
        mode.value === 'slider' ? both + ' (A left of the line, B right of it)' : '';
  }
  kind.addEventListener('change', fill);
  [a, b, mode].forEach(function (el) { el.addEventListener('change', show); });
  slider.addEventListener('input', show);
  flip.addEventListener('click', function () { flipped = !flipped; show(); });
  document.addEventListener('keydown', function (e) {
    if (mode.value === 'flip' && (e.key === 'f' || e.key === ' ') && e.target.tagName !== 'SELECT') { flipped = !flipped; show(); e.preventDefault(); }
  });
  fill();
  // report.html?compare opens with the comparison first (e.g. for a screenshot of it).
  if (/[?&]compare\b/.test(location.search)) {
    var section = $('compare');
    document.body.insertBefore(section, document.body.firstChild);
    kind.value = 'ground'; fill();
  }

  if (location.search.indexOf('selftest') < 0) return;
  window.addEventListener('load', function () {
    var fails = [], switches = 0;
    var images = document.querySelectorAll('.fig img');
    Array.prototype.forEach.call(images, function (img) {
      if (!img.complete || img.naturalWidth === 0) fails.push('not loaded: ' + img.getAttribute('src'));
    });
    kinds.forEach(function (k) {
      kind.value = k; fill();
      var list = entries(), last = String(list.length - 1);
      b.value = last; show();
      if (imgB.getAttribute('src') !== list[list.length - 1].src) fails.push('B did not switch for ' + k);
      if (list.length > 1 && imgA.getAttribute('src') === imgB.getAttribute('src')) fails.push('A and B alike for ' + k);
      switches++;
    });
    mode.value = 'flip'; show(); flip.click();
    if (imgB.parentNode.style.visibility === 'hidden') fails.push('flip does not show B');
    mode.value = 'side'; show();
    setTimeout(function () {
      [imgA, imgB].forEach(function (img) {
        if (!img.complete || img.naturalWidth === 0) fails.push('comparison image not loaded: ' + img.getAttribute('src'));
      });
      performance.getEntriesByType('resource').forEach(function (r) {
        if (r.name.indexOf('file:') !== 0) fails.push('request off the file: ' + r.name);
      });
      var all = fails.concat(errors);
      $('selftest').textContent = all.length ? 'SELFTEST FAIL: ' + all.join('; ') :
          'SELFTEST PASS: ' + images.length + ' images loaded, ' + kinds.length + ' kinds switched, ' + data.length + ' pictures listed';
    }, 500);
  });
})();
)JS";

}  // namespace

void write_comparison_view(std::ostringstream& html, const std::vector<FigureSection>& sections) {
  // The pictures by kind: the reference's first, then every section's rows.
  std::string json = "[";
  const auto add = [&json](const std::string& kind, const std::string& label, const std::string& src) {
    if (json.size() > 1) json += ",";
    json += "{\"k\":\"" + kind + "\",\"label\":\"" + label + "\",\"src\":\"" + src + "\"}";
  };
  for (const FigureSection& s : sections)
    for (const ReportRow& r : *s.rows)
      for (const std::string& p : s.parts) {
        if (!r.views && (p == "_view" || p == "_closeup")) continue;
        add(part_of(p).kind, r.method + ", " + s.data_set, "figures/" + r.figure_stem + p + ".png");
      }
  json += "]";
  // Method and data set names are plain words; no "</" can end the script element early.
  html << "<section id=compare><h2>Compare any two pictures</h2>\n"
       << "<p>Pick a kind of picture and two of them (A and B): side by side, with a slider (drag it), or flipping "
          "(the button or the F key). Every data set and method of this report is listed.</p>\n"
       << "<div class=cmp-controls><label>picture <select id=cmp-kind></select></label> "
       << "<label>A <select id=cmp-a></select></label> <label>B <select id=cmp-b></select></label> "
       << "<label>show <select id=cmp-mode><option value=side>side by side</option><option value=slider>slider</option>"
       << "<option value=flip>flip</option></select></label> <input type=range id=cmp-slider min=0 max=100 value=50 "
       << "aria-label=\"slider position, percent\" hidden> <button type=button id=cmp-flip hidden>flip A/B</button> "
       << "<span id=cmp-showing></span></div>\n"
       << "<div id=cmp-stage class=cmp-side><figure class=cmp-pane><img id=cmp-img-a alt=\"picture A\"><figcaption id=cmp-label-a>"
       << "</figcaption></figure><figure class=cmp-pane><img id=cmp-img-b alt=\"picture B\"><figcaption id=cmp-label-b></figcaption>"
       << "</figure></div>\n<pre id=selftest></pre>\n"
       << "<script type=\"application/json\" id=cmp-data>" << json << "</script>\n<script>" << kComparisonScript
       << "</script></section>\n";
}

}  // namespace radrecon
