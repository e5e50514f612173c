#include "sampling/solution_reconstruction.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <optional>

#include "core/error.h"
#include "core/parse.h"
#include "core/tolerances.h"
#include "reconstruct/border_samples.h"
#include "sampling/surface_samples.h"
#include "scene/contacts.h"

namespace radrecon {

namespace {

/// An interpolant that has no value (NaN) inside the side's excluded regions, but within
/// `band_m` of their outlines (SideSampling::outline_band_m), where a point takes the value at the
/// nearest point of the outline, `nudge_m` outside it.
class OutsideExcluded final : public Interpolant {
 public:
  OutsideExcluded(std::unique_ptr<Interpolant> inner, std::vector<Polyline> regions, double band_m, double nudge_m)
      : inner_(std::move(inner)), regions_(std::move(regions)), band_m_(band_m), nudge_m_(nudge_m) {
    // Each ring's orientation, once: its outside lies right of an edge of a counter-clockwise one.
    for (const Polyline& r : regions_) {
      counter_clockwise_.push_back(twice_signed_area(r) > 0);
    }
  }
  int channels() const override { return inner_->channels(); }
  /// The inner interpolant sees only the points outside the regions: what it would give inside
  /// them is never asked (gouraud would search for the nearest cell outside its holes).
  void evaluate(std::span<const Vec2> points, std::span<double> out) const override {
    const size_t C = static_cast<size_t>(channels());
    std::vector<Vec2> outside;
    std::vector<size_t> at;  // their indices in `points`
    size_t moved = 0;
    for (size_t k = 0; k < points.size(); ++k)
      if (!points[k].allFinite() || !in_excluded_region(regions_, points[k])) {
        outside.push_back(points[k]), at.push_back(k);
      } else if (const std::optional<Vec2> q = band_m_ > 0 ? just_outside(points[k]) : std::nullopt) {
        outside.push_back(*q), at.push_back(k), ++moved;
      } else {
        for (size_t c = 0; c < C; ++c) out[k * C + c] = std::numeric_limits<double>::quiet_NaN();
      }
    if (at.size() == points.size() && moved == 0) return inner_->evaluate(points, out);
    std::vector<double> values(outside.size() * C);
    inner_->evaluate(outside, values);
    for (size_t i = 0; i < at.size(); ++i)
      for (size_t c = 0; c < C; ++c) out[at[i] * C + c] = values[i * C + c];
  }

 private:
  /// The nearest point of the regions' outlines to `p` (in a region), moved nudge_m out across
  /// its edge; none beyond band_m, or if the point so moved still lies in a region.
  std::optional<Vec2> just_outside(const Vec2& p) const {
    double best = band_m_;
    std::optional<Vec2> found;
    for (size_t k = 0; k < regions_.size(); ++k) {
      const Polyline& r = regions_[k];
      for (size_t i = 0; i < r.size(); ++i) {
        const Vec2 &a = r[i], &b = r[(i + 1) % r.size()];
        const Vec2 q = a + nearest_on_segment_t(p, a, b) * (b - a);
        const double d = (q - p).norm();
        if (!(d <= best) || a == b) continue;
        const Vec2 along = (b - a).normalized();
        const Vec2 out_normal = counter_clockwise_[k] ? Vec2(along.y(), -along.x()) : Vec2(-along.y(), along.x());
        best = d;
        found = q + nudge_m_ * out_normal;
      }
    }
    if (found && in_excluded_region(regions_, *found)) return std::nullopt;
    return found;
  }

  std::unique_ptr<Interpolant> inner_;
  std::vector<Polyline> regions_;
  std::vector<bool> counter_clockwise_;  ///< per region
  double band_m_, nudge_m_;
};

/// The samples outside the excluded regions.
ScatteredSamples outside_regions(const ScatteredSamples& all, const std::vector<Polyline>& regions) {
  if (regions.empty()) return all;
  ScatteredSamples kept;
  kept.channels = all.channels;
  for (size_t k = 0; k < all.points.size(); ++k)
    if (!in_excluded_region(regions, all.points[k])) {
      kept.points.push_back(all.points[k]);
      kept.values.insert(kept.values.end(), all.values.begin() + static_cast<std::ptrdiff_t>(k * all.channels),
                         all.values.begin() + static_cast<std::ptrdiff_t>((k + 1) * all.channels));
    }
  return kept;
}

/// reconstruct_side() without the excluded regions' masking.
InterpolantResult reconstruct_unmasked(const SurfaceSolution& s, Method method, const MethodParams& plain,
                                       const SideSampling& sampling) {
  MethodParams params = plain;
  // The side's barriers if asked, and always the outlines of its excluded regions: they hide
  // the cells of a grid under them from every point outside (a grid keeps all its cells).
  // (Methods that take no barriers reconstruct across them: reconstruct_side() says so.)
  std::vector<Polyline> lines;
  if (sampling.barriers && takes_barriers(method)) lines = s.barriers;
  if (takes_barriers(method))
    for (const Polyline& region : s.excluded) {
      lines.push_back(region);
      if (region.front() != region.back()) lines.back().push_back(region.front());
    }
  if (!lines.empty()) {
    Result<Barriers> barriers = Barriers::from_polylines(lines);
    if (!barriers) return Failure{"its barriers: " + barriers.reason()};
    params.barriers = std::move(barriers).value();
  }
  const bool grid = s.grid_nu > 0 && s.grid_nv > 0;
  const bool point_method = method != Method::constant && !is_grid_method(method) && !is_cell_method(method);
  // Border samples first: a grid side with excluded regions (the Cornell box's floor) went to the
  // branch below and took none (an outside-in trial).
  if (sampling.border_samples && point_method && !s.triangle) {  // border samples frame a quad's sides
    ScatteredSamples samples = outside_regions(grid ? grid_cells(s).centres() : element_centres(s), s.excluded);
    const Result<size_t> added = add_border_samples(method, samples, Rect{0, 0, s.length_u_m, s.length_v_m}, params);
    if (!added) return Failure{"its border samples: " + added.reason()};
    return make_scattered_interpolant(method, samples, params);
  }
  if (grid && !s.excluded.empty() && point_method)
    return make_scattered_interpolant(method, outside_regions(grid_cells(s).centres(), s.excluded), params);
  if (is_cell_method(method) && !s.excluded.empty()) {
    // The cells under excluded regions are holes (NaN): no value there, no influence outside.
    // Every cell centred under one (a coarse quadtree's one ceiling leaf under a lamp): the cells
    // as they are, the regions masked, as constant does below.
    CellSamples cells = grid ? to_cells(grid_cells(s)) : element_cells(s);
    const CellSamples unmasked = cells;
    size_t holes = 0;
    for (size_t k = 0; k < cells.cells.size(); ++k)
      if (in_excluded_region(s.excluded, cells.cells[k].center())) {
        ++holes;
        for (int c = 0; c < cells.channels; ++c) cells.values[k * cells.channels + c] = std::numeric_limits<double>::quiet_NaN();
      }
    return make_cell_interpolant(method, holes == cells.cells.size() ? unmasked : cells, params);
  }
  if (grid) return make_grid_interpolant(method, grid_cells(s), params);
  if ((method == Method::constant && params.barriers.empty()) || is_cell_method(method))
    return make_cell_interpolant(method, element_cells(s), params);
  if (is_grid_method(method))
    return Failure{method_name(method) + " needs grid data; this side is " +
                   (s.triangle ? "a triangle (its elements are no grid of boxes)" : "an adaptive subdivision")};
  const ScatteredSamples outside = outside_regions(element_centres(s), s.excluded);
  // Every element centred under an excluded region (a coarse quadtree's one leaf under a lamp
  // lying on it): piecewise constant draws the elements as they are, the regions masked.
  if (method == Method::constant && outside.points.empty()) return make_cell_interpolant(method, element_cells(s), plain);
  return make_scattered_interpolant(method, outside, params);
}

/// Refuses a solution side whose elements' centres are not where the scene's surface puts their
/// (u, v) centroids: a surface moved (or turned) since the solve, keeping its edge lengths.
void check_in_place(const SurfaceSolution& side, const Surface& surface, const std::string& source) {
  double size_m = 0;
  for (int i = 0; i < surface.corner_count; ++i) size_m = std::max(size_m, surface.corners[i].cwiseAbs().maxCoeff());
  size_m += std::max(surface.length_u_m(), surface.length_v_m());
  for (const SolutionElement& e : side.elements) {
    const Vec2 uv = e.centroid();
    const Vec3 want = surface.point(uv.x(), uv.y());
    if ((e.center - want).norm() > tol::kSolutionCentreRelative * size_m)
      throw UserError(source, "surface '" + side.name + "' has an element centred at (" + format_number(e.center.x()) + ", " +
                                  format_number(e.center.y()) + ", " + format_number(e.center.z()) + ") in the solution but at (" +
                                  format_number(want.x()) + ", " + format_number(want.y()) + ", " + format_number(want.z()) +
                                  ") in the scene: the surface has moved since the solve (solve again)");
  }
}

}  // namespace

bool in_excluded_region(const std::vector<Polyline>& regions, const Vec2& st) {
  for (const Polyline& r : regions)
    if (in_region(r, st)) return true;
  return false;
}

InterpolantResult reconstruct_side(const SurfaceSolution& s, Method method, const MethodParams& params,
                                   const SideSampling& sampling) {
  InterpolantResult built = reconstruct_unmasked(s, method, params, sampling);
  if (!built || s.excluded.empty()) return built;
  const double nudge_m = tol::kExcludedOutlineNudgeRelative * std::max(s.length_u_m, s.length_v_m);
  return InterpolantResult(
      std::make_unique<OutsideExcluded>(std::move(built).value(), s.excluded, sampling.outline_band_m, nudge_m));
}

InterpolantResult reconstruct_side_or_constant(const SurfaceSolution& side, Method method, const MethodParams& params,
                                               const SideSampling& sampling, std::optional<Fallback>& fallback) {
  fallback.reset();
  InterpolantResult built = reconstruct_side(side, method, params, sampling);
  if (built) return built;
  const auto same = [&](const SolutionElement& e) { return (e.radiosity_w_m2 == side.elements.front().radiosity_w_m2).all(); };
  fallback = Fallback{side.name, built.reason(), std::all_of(side.elements.begin(), side.elements.end(), same)};
  return reconstruct_side(side, Method::constant, params, SideSampling{.barriers = false, .outline_band_m = sampling.outline_band_m});
}

SolutionReconstruction::SolutionReconstruction(const Scene& scene, const Solution& solution, Method method,
                                               const MethodParams& params, const std::string& source,
                                               const SideSampling& sampling) {
  sides_.resize(side_slots(scene));
  // Every side of the scene must be there, before any is built: one missing would be drawn
  // black as if unlit.
  std::vector<bool> present(side_slots(scene), false);
  for (const SurfaceSolution& side : solution.surfaces)
    if (const std::optional<SideRef> ref = find_side(scene, side.name)) present[ref->slot()] = true;
  for (size_t k = 0; k < scene.surfaces.size(); ++k)
    for (const bool back : {false, true}) {
      if (back && !scene.surfaces[k].two_sided) continue;
      if (!present[SideRef{k, back}.slot()])
        throw UserError(source, "the scene's side '" + side_name(scene.surfaces[k], back) +
                                    "' is not in the solution (it holds " + std::to_string(solution.surfaces.size()) +
                                    (solution.surfaces.size() == 1 ? " side" : " sides") +
                                    "): it belongs to another scene, or was cut short; solve the scene again");
    }
  for (const SurfaceSolution& side : solution.surfaces) {
    const std::optional<SideRef> ref = find_side(scene, side.name);
    if (!ref)
      throw UserError(source, "surface '" + side.name + "' is not a side of the scene's surfaces (" + side_names(scene) + ")");
    // The scene's edge lengths, so that (s, t) match the renderer's; a solution of another scene
    // whose sides have the same names has other lengths.
    const Surface& surface = scene.surfaces[ref->surface];
    const auto differs = [](double a, double b) { return std::abs(a - b) > tol::kSolutionLengthRelative * b; };
    if (differs(side.length_u_m, surface.length_u_m()) || differs(side.length_v_m, surface.length_v_m()))
      throw UserError(source, "surface '" + side.name + "' is " + format_number(side.length_u_m) + " m x " +
                                  format_number(side.length_v_m) + " m in the solution but " +
                                  format_number(surface.length_u_m()) + " m x " + format_number(surface.length_v_m()) +
                                  " m in the scene: the solution belongs to another scene");
    if (side.triangle != surface.is_triangle())
      throw UserError(source, "surface '" + side.name + "' is a " + (side.triangle ? "triangle" : "quad") +
                                  " in the solution but a " + (surface.is_triangle() ? "triangle" : "quad") +
                                  " in the scene: the solution belongs to another scene");
    check_in_place(side, surface, source);
    SurfaceSolution s = side;
    s.length_u_m = surface.length_u_m();
    s.length_v_m = surface.length_v_m();
    s.shear_m = surface.shear_m();
    SideSampling own = sampling;
    own.outline_band_m = surface.frame_bend_m();
    std::optional<Fallback> fallback;
    InterpolantResult built = reconstruct_side_or_constant(s, method, params, own, fallback);
    if (!built) throw UserError(source, "surface '" + side.name + "': " + built.reason());
    if (fallback) fallbacks_.push_back(*fallback);
    sides_[ref->slot()] = std::move(built).value();
  }
}

SolutionReconstruction::~SolutionReconstruction() = default;

const Interpolant* SolutionReconstruction::side(SideRef side) const { return sides_[side.slot()].get(); }

std::vector<Fallback> SolutionReconstruction::notable_fallbacks() const {
  std::vector<Fallback> out;
  std::copy_if(fallbacks_.begin(), fallbacks_.end(), std::back_inserter(out), [](const Fallback& f) { return !f.exact; });
  return out;
}

}  // namespace radrecon
