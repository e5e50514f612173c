// radrecon compare: two pictures or two solutions, the second the reference; the norms and the
// metrics of evaluate/metrics.h, a difference image, thresholds for scripts (after pbrt's
// `imgtool diff`).

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "core/check.h"
#include "core/error.h"
#include "core/image.h"
#include "core/parse.h"
#include "core/tolerances.h"
#include "evaluate/metrics.h"
#include "io/atomic_file.h"
#include "io/image_io.h"
#include "io/image_read.h"
#include "io/paths.h"
#include "io/solution_json.h"

namespace radrecon::cli {

namespace {

struct CompareArgs {
  std::string a, b;
  std::string diff;
  double scale = 2;
  double white = 0;
  std::vector<std::string> thresholds;
  bool json = false;
};

/// A figure a threshold may bound; SSIM is exceeded when smaller, the others when larger.
struct Threshold {
  std::string key;
  double value;
};

const std::vector<std::string> kThresholdKeys = {"L1", "L2", "RMSE", "Linf", "gradient_L2", "SSIM"};

std::vector<Threshold> parse_thresholds(const std::vector<std::string>& texts) {
  std::vector<Threshold> out;
  for (const std::string& t : texts) {
    const size_t eq = t.find('=');
    const std::string key = t.substr(0, eq);
    if (eq == std::string::npos || std::find(kThresholdKeys.begin(), kThresholdKeys.end(), key) == kThresholdKeys.end())
      throw UserError("--threshold", in_quotes(t) + ": expected KEY=VALUE with KEY one of L1, L2, RMSE, Linf, gradient_L2, SSIM");
    const std::optional<double> value = parse_finite(std::string_view(t).substr(eq + 1));
    if (!value) throw UserError("--threshold", in_quotes(t) + ": the value is not a finite number");
    out.push_back({key, *value});
  }
  return out;
}

/// What compare measured, and about what.
struct Comparison {
  Figures figures;
  nlohmann::json about = nlohmann::json::object();  ///< sizes, white, sides: printed and in --json
  std::string summary;                              ///< one line for the text output
};

bool is_solution_file(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == ".json";
}

double largest_finite(std::span<const double> values) {
  double m = -std::numeric_limits<double>::infinity();
  for (const double v : values)
    if (std::isfinite(v)) m = std::max(m, v);
  return m;
}

// --- pictures ------------------------------------------------------------------------------

Comparison compare_pictures(const CompareArgs& args) {
  PictureValues a = read_picture(args.a, "A"), b = read_picture(args.b, "B");
  if ((a.format == FileFormat::png) != (b.format == FileFormat::png))
    throw UserError(args.a + " vs " + args.b, "one is a PNG (display values) and the other holds linear values "
                                              "(PFM, EXR); compare pictures of the same kind");
  if (a.width != b.width || a.height != b.height || a.channels != b.channels)
    throw UserError(args.a + " vs " + args.b,
                    "the pictures differ in size: " + args.a + " is " + std::to_string(a.width) + " x " +
                        std::to_string(a.height) + " with " + std::to_string(a.channels) + " channel(s), " + args.b +
                        " is " + std::to_string(b.width) + " x " + std::to_string(b.height) + " with " +
                        std::to_string(b.channels) + "; compare needs the same width, height and channels");
  Comparison out;
  const bool png = b.format == FileFormat::png;
  double white = args.white;
  if (white <= 0) white = png ? 1.0 : largest_finite(b.values);
  const bool dark_reference = !(white > 0);
  if (dark_reference) white = 1;  // a black or empty reference
  const ImageShape shape{a.width, a.height, a.channels};
  // Values missing (NaN: interpolate's no-data) in both pictures agree: left out of the norms, and
  // 0 in both for SSIM and the gradients. Missing in one only, the figures are NaN.
  // (In place: a picture of 4000 x 4000 RGB holds 384 MB of doubles.)
  std::vector<double>&va = a.values, &vb = b.values;
  size_t missing_both = 0, missing_one = 0;
  for (size_t k = 0; k < va.size(); ++k) {
    const bool na = std::isnan(va[k]), nb = std::isnan(vb[k]);
    missing_both += na && nb;
    missing_one += na != nb;
  }
  if (missing_both == 0) {
    out.figures.norms = error_norms(va, vb);
  } else {
    std::vector<double> kept_a, kept_b;
    kept_a.reserve(va.size() - missing_both), kept_b.reserve(va.size() - missing_both);
    for (size_t k = 0; k < va.size(); ++k) {
      if (std::isnan(va[k]) && std::isnan(vb[k])) {
        va[k] = vb[k] = 0;
        continue;
      }
      kept_a.push_back(va[k]), kept_b.push_back(vb[k]);
    }
    out.figures.norms = error_norms(kept_a, kept_b);
  }
  // SSIM on what a viewer sees: a PNG's values as stored (already display values), linear
  // values tone-mapped and sRGB-encoded as the figures are.
  std::vector<double> da, db;
  if (png) {
    da.resize(va.size()), db.resize(vb.size());
    for (size_t k = 0; k < da.size(); ++k) da[k] = tone_map(va[k], white), db[k] = tone_map(vb[k], white);
  } else {
    da = display_values(va, white), db = display_values(vb, white);
  }
  out.figures.ssim = ssim(da, db, shape);
  out.figures.gradient_l2 = gradient_l2(va, vb, shape, 1, 1);
  out.about = {{"kind", "pictures"}, {"width", a.width}, {"height", a.height}, {"channels", a.channels},
               {"count", out.figures.norms.count}, {"white", white}, {"missing_in_both", missing_both},
               {"missing_in_one", missing_one}};
  out.summary = std::to_string(a.width) + " x " + std::to_string(a.height) + " pixels, " + std::to_string(a.channels) +
                " channel(s); white " + format_number(white) +
                (png ? (args.white > 0 ? " (PNG values divided by --white)" : " (PNG values as stored)")
                     : dark_reference ? " (B has no value above 0)" : "");
  if (missing_both > 0)
    out.summary += "; " + std::to_string(missing_both) + " value(s) missing (NaN) in both, left out of the norms";
  if (missing_one > 0)
    out.summary += "; " + std::to_string(missing_one) + " value(s) missing in one picture only: the figures are NaN";
  if (!args.diff.empty()) {
    Image diff(a.width, a.height);
    for (int y = 0; y < a.height; ++y)
      for (int x = 0; x < a.width; ++x)
        for (int c = 0; c < 3; ++c) {
          const size_t k = (static_cast<size_t>(y) * a.width + x) * a.channels + std::min(c, a.channels - 1);
          diff.at(x, y)[c] = std::clamp(0.5 + args.scale * (va[k] - vb[k]) / white, 0.0, 1.0);  // missing in both: mid-grey
        }
    write_png(args.diff, diff, false);  // linear: zero is mid-grey (128)
  }
  return out;
}

// --- solutions -----------------------------------------------------------------------------

/// Refuses two solutions that are not of the same mesh, naming what differs.
void check_same_mesh(const Solution& a, const Solution& b, const std::string& where) {
  auto refuse = [&](const std::string& what) {
    throw UserError(where, "not solutions of the same mesh: " + what);
  };
  if (a.surfaces.size() != b.surfaces.size())
    refuse(std::to_string(a.surfaces.size()) + " surfaces in A, " + std::to_string(b.surfaces.size()) + " in B");
  for (size_t s = 0; s < a.surfaces.size(); ++s) {
    const SurfaceSolution &sa = a.surfaces[s], &sb = b.surfaces[s];
    const std::string at = "surface " + std::to_string(s) + " ('" + sa.name + "')";
    if (sa.name != sb.name) refuse("surface " + std::to_string(s) + " is '" + sa.name + "' in A, '" + sb.name + "' in B");
    if (sa.elements.size() != sb.elements.size())
      refuse(at + " has " + std::to_string(sa.elements.size()) + " elements in A, " +
             std::to_string(sb.elements.size()) + " in B");
    if (sa.grid_nu != sb.grid_nu || sa.grid_nv != sb.grid_nv)
      refuse(at + " is a " + std::to_string(sa.grid_nu) + " x " + std::to_string(sa.grid_nv) + " grid in A, " +
             std::to_string(sb.grid_nu) + " x " + std::to_string(sb.grid_nv) + " in B (0 x 0: adaptive)");
    for (size_t e = 0; e < sa.elements.size(); ++e) {
      const SolutionElement &ea = sa.elements[e], &eb = sb.elements[e];
      const double d = std::max({std::abs(ea.u0 - eb.u0), std::abs(ea.v0 - eb.v0), std::abs(ea.u1 - eb.u1),
                                 std::abs(ea.v1 - eb.v1)});
      if (!(d <= tol::kSolutionGridParameter))
        refuse(at + ", element " + std::to_string(e) + ": (u, v) rectangles differ by " + format_number(d));
    }
  }
}

Comparison compare_solutions(const CompareArgs& args) {
  const Solution a = read_solution_json(args.a), b = read_solution_json(args.b);
  check_same_mesh(a, b, args.a + " vs " + args.b);
  std::vector<double> va, vb;
  // Grid sides: SSIM weighted by element count over the sides at least the window's size, the
  // gradient error pooled over all grid sides' points.
  double ssim_sum = 0, grad_sum = 0;
  size_t ssim_count = 0, grad_count = 0, grid_sides = 0, ssim_sides = 0;
  bool nan = false;
  for (size_t s = 0; s < a.surfaces.size(); ++s) {
    const SurfaceSolution &sa = a.surfaces[s], &sb = b.surfaces[s];
    std::vector<double> side_a, side_b;
    for (size_t e = 0; e < sa.elements.size(); ++e)
      for (int c = 0; c < 3; ++c)
        side_a.push_back(sa.elements[e].radiosity_w_m2[c]), side_b.push_back(sb.elements[e].radiosity_w_m2[c]);
    va.insert(va.end(), side_a.begin(), side_a.end());
    vb.insert(vb.end(), side_b.begin(), side_b.end());
    if (sa.grid_nu <= 0 || sa.grid_nv <= 0) continue;
    ++grid_sides;
    const ImageShape shape{sa.grid_nu, sa.grid_nv, 3};
    const double dx = sa.length_u_m / sa.grid_nu, dy = sa.length_v_m / sa.grid_nv;
    const double g = gradient_l2(side_a, side_b, shape, dx > 0 ? dx : 1, dy > 0 ? dy : 1);
    nan = nan || std::isnan(g);
    grad_sum += g * sa.elements.size(), grad_count += sa.elements.size();
    double white = args.white > 0 ? args.white : largest_finite(side_b);
    if (!(white > 0)) white = 1;  // a dark side: as for pictures
    const std::optional<double> q = ssim(display_values(side_a, white), display_values(side_b, white), shape);
    if (q) ssim_sum += *q * sa.elements.size(), ssim_count += sa.elements.size(), ++ssim_sides;
  }
  Comparison out;
  out.figures.norms = error_norms(va, vb);
  const double kNaN = std::numeric_limits<double>::quiet_NaN();
  if (grad_count > 0) out.figures.gradient_l2 = nan ? kNaN : grad_sum / grad_count;
  if (ssim_count > 0) out.figures.ssim = nan ? kNaN : ssim_sum / ssim_count;
  out.about = {{"kind", "solutions"}, {"surfaces", a.surfaces.size()}, {"count", out.figures.norms.count},
               {"grid_sides", grid_sides}, {"ssim_sides", ssim_sides}};
  if (args.white > 0) out.about["white"] = args.white;
  out.summary = std::to_string(a.surfaces.size()) + " sides, " + std::to_string(va.size() / 3) + " elements; " +
                std::to_string(grid_sides) + " grid side(s) for gradient_L2, " + std::to_string(ssim_sides) +
                " of at least " + std::to_string(kSsimWindow) + " x " + std::to_string(kSsimWindow) + " for SSIM";
  return out;
}

// --- the command ---------------------------------------------------------------------------

void run_compare(const CompareArgs& args) {
  const std::vector<Threshold> thresholds = parse_thresholds(args.thresholds);
  const bool solutions = is_solution_file(args.a);
  if (solutions != is_solution_file(args.b))
    throw UserError(args.a + " vs " + args.b, "compare two pictures (.pfm, .exr, .png) or two solutions (.json), not one of each");
  if (!(args.scale > 0) || !std::isfinite(args.scale)) throw UserError("--scale", "must be a positive number");
  if (!args.diff.empty()) {
    if (solutions) throw UserError("--diff", "applies to pictures only, not to solutions");
    file_format(args.diff, {FileFormat::png}, "--diff");
    refuse_overwriting_inputs(args.diff, "--diff", {args.a, args.b});
    check_output_file(args.diff, "--diff");
    // Nor the file stdout goes to (--diff /dev/stdout > d.png): the figures would be written into
    // the picture, or the picture over the figures.
    struct stat out = {}, diff = {};
    if (::fstat(STDOUT_FILENO, &out) == 0 && S_ISREG(out.st_mode) && ::stat(args.diff.c_str(), &diff) == 0 &&
        out.st_dev == diff.st_dev && out.st_ino == diff.st_ino)
      throw UserError("--diff", "'" + args.diff + "' is the file standard output goes to, where the figures are printed; "
                                "give the difference image its own file");
  }
  const Comparison c = solutions ? compare_solutions(args) : compare_pictures(args);

  // Thresholds: a figure that is not defined (or NaN) exceeds any threshold on it.
  std::vector<std::string> exceeded;
  const Figures& f = c.figures;
  const std::pair<const char*, std::optional<double>> rows[] = {
      {"L1", f.norms.l1}, {"L2", f.norms.l2},     {"RMSE", f.norms.rmse},         {"Linf", f.norms.linf},
      {"SSIM", f.ssim},   {"gradient_L2", f.gradient_l2}, {"overshoot", f.overshoot}};
  for (const Threshold& t : thresholds) {
    const auto row = std::find_if(std::begin(rows), std::end(rows), [&](const auto& r) { return t.key == r.first; });
    RR_CHECK(row != std::end(rows), "a threshold on a figure compare does not print");
    const std::optional<double> v = row->second;
    const bool over = !v || std::isnan(*v) || (t.key == "SSIM" ? *v < t.value : *v > t.value);
    if (over)  // as the table prints it: n/a (not defined) or nan (a value missing in A or B)
      exceeded.push_back(t.key + " = " + (v ? format_number(*v) : std::string("n/a")) +
                         (t.key == "SSIM" ? " is below " : " is above ") + format_number(t.value));
  }
  if (args.json) {
    nlohmann::json j = figures_json(c.figures);
    j["A"] = args.a;
    j["B"] = args.b;
    for (const auto& [key, value] : c.about.items()) j[key] = value;
    j["thresholds_exceeded"] = exceeded;
    std::printf("%s\n", j.dump(2).c_str());
  } else {
    std::printf("A: %s\nB: %s (reference)\n%s\n", args.a.c_str(), args.b.c_str(), c.summary.c_str());
    for (const auto& [key, v] : rows)  // NaN (a NaN value in A or B) prints as nan
      std::printf("%-12s %s\n", key, v ? format_number(*v).c_str() : (std::string(key) == "overshoot" ? "n/a (no samples)" : "n/a"));
    if (!args.diff.empty()) std::printf("difference image: %s (scale %s)\n", args.diff.c_str(), format_number(args.scale).c_str());
  }
  // The figures written (a full disk, a closed stdout: exit 2 with the reason) before the verdict.
  if (std::fflush(stdout) != 0) throw output_error("standard output", errno);
  for (const std::string& e : exceeded) std::fprintf(stderr, "compare: threshold exceeded: %s\n", e.c_str());
  if (!exceeded.empty()) throw ExitStatus{1};
}

}  // namespace

void add_compare_command(CLI::App& app) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* cmd = app.add_subcommand(
      "compare",
      "Compare A with the reference B: two pictures (.pfm, .exr, .png; same width, height and channels) or two "
      "solutions (.json from 'radrecon solve') of the same mesh. Prints L1, L2, RMSE, Linf (of A - B over all "
      "values), SSIM (Wang et al. 2004, 11 x 11 Gaussian window, sigma 1.5, mean over the windows inside the "
      "picture and the channels; n/a below 11 x 11) and gradient_L2 (mean squared difference of the "
      "finite-difference gradients); overshoot needs samples and is n/a here.\n"
      "Pictures: SSIM on display values, PFM/EXR as the figures show them (clamp(v / white, 0, 1), sRGB-encoded; "
      "white: --white, else the largest value of B, 1 if none is above 0), PNG values as stored (white 1; with "
      "--white, divided by it); gradient_L2 with a pixel "
      "spacing of 1; a value missing (NaN, interpolate's no-data) in both pictures is left out of the norms (0 in both "
      "for SSIM and the gradients), one missing in one only makes the figures NaN. Solutions: norms over every element's values; SSIM and gradient_L2 over the grid sides, each an "
      "nu x nv picture (white: --white, else the side's largest value in B; spacing: the element size in metres), "
      "SSIM weighted by element count over the sides of at least 11 x 11, gradient_L2 over all grid-side elements; "
      "adaptive (quadtree) sides count in the norms only.\n"
      "Exit code 0; 1 when a --threshold is exceeded (after printing the figures); 2 for refused input or figures "
      "that cannot be written to stdout.");
  cmd->add_option("A", args->a, "The picture or solution to judge")->required();
  cmd->add_option("B", args->b, "The reference picture or solution")->required();
  cmd->add_option("--diff", args->diff,
                  "Pictures only: write a difference image (.png), display = clamp(0.5 + scale (A - B) / white, 0, 1) "
                  "written linearly: zero is mid-grey (128), brighter is A above B");
  cmd->add_option("--scale", args->scale, "The difference image's scale (the paper's figures: 2)")->capture_default_str();
  cmd->add_option("--white", args->white, "The value shown as white (W/m^2 for radiosity); see above for the default")
      ->check(positive_at_most(1e300));
  cmd->add_option("--threshold", args->thresholds,
                  "KEY=VALUE, repeatable: exit with code 1 when L1, L2, RMSE, Linf or gradient_L2 is above VALUE, or SSIM "
                  "below it (a figure that is n/a or NaN exceeds every threshold)");
  cmd->add_flag("--json", args->json,
                "Print one JSON object instead: L1, L2, RMSE, Linf, SSIM, gradient_L2, overshoot (the keys of "
                "errors.json; null where not defined), A, B, kind, count, the sizes (width, height, channels of pictures; "
                "surfaces, grid_sides, ssim_sides of solutions), white, thresholds_exceeded");
  cmd->footer(
      "Examples:\n"
      "  radrecon compare approx.pfm reference.pfm --diff diff.png\n"
      "  radrecon compare a.exr b.exr --threshold RMSE=0.01 --threshold SSIM=0.99 || echo worse\n"
      "  radrecon compare coarse.json fine.json --json");
  add_limit_options(*cmd, {Limit::file_bytes});
  cmd->callback([args] { run_compare(*args); });
}

}  // namespace radrecon::cli
