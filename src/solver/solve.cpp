#include "solver/solve.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <utility>

#include "core/error.h"
#include "core/limits.h"
#include "core/parse.h"
#include "core/tolerances.h"
#include "mesh/grid_mesh.h"
#include "scene/contacts.h"
#include "scene/shadow_lines.h"
#include "scene/side.h"
#include "solver/hierarchical.h"
#include "solver/progressive.h"

namespace radrecon {

int default_patches() { return GridMeshOptions{}.max_patches; }

namespace {

/// The kind of mesh a specification names: what precedes its colon (grid, quadtree, ...).
std::string mesh_kind(const std::string& spec) { return spec.substr(0, spec.find(':')); }

}  // namespace

void refuse_unused_options(const std::string& mesh_spec, const std::vector<std::string>& grid_only_given,
                           const std::string& leaves_on_given) {
  if (mesh_kind(mesh_spec) != "grid" && !grid_only_given.empty())
    throw UserError(grid_only_given.front(), "applies to grid:N meshes only");
  if (mesh_kind(mesh_spec) != "quadtree" && !leaves_on_given.empty())
    throw UserError(leaves_on_given, "applies to quadtree:LEAVES meshes only");
}

std::string residual_problem(double residual) {
  if (residual >= kMinResidual && residual <= kMaxResidual) return {};  // NaN fails both
  return "must be a number in [" + format_number(kMinResidual) + ", " + format_number(kMaxResidual) + "], got " +
         format_number(residual);
}

std::string far_field_error_problem(double far_field_error) {
  if (far_field_error == 0 || (far_field_error >= kMinFarFieldError && far_field_error <= kMaxFarFieldError)) return {};
  return "must be 0 or a number in [" + format_number(kMinFarFieldError) + ", " + format_number(kMaxFarFieldError) +
         "], got " + format_number(far_field_error);
}

std::string patches_problem(long long patches) {
  if (patches >= 0 && patches <= kMostPatches) return {};
  return "must be 0 (the default, " + std::to_string(default_patches()) + ") or a count up to " +
         std::to_string(kMostPatches) + ", got " + std::to_string(patches);
}

void check_settings(const SolveSettings& settings) {
  if (const std::string problem = residual_problem(settings.residual); !problem.empty())
    throw UserError("residual", problem);
  if (const std::string problem = far_field_error_problem(settings.far_field_error); !problem.empty())
    throw UserError("far_field_error", problem);
  if (const std::string problem = patches_problem(settings.patches); !problem.empty()) throw UserError("patches", problem);
}

namespace {

/// The integer in [lo, hi] that is all of `text`, a part of the specification `spec`.
long long spec_integer(const std::string& text, long long lo, long long hi, const std::string& field,
                       const std::string& spec) {
  const std::optional<long long> v = parse_integer(text);
  if (!v || *v < lo || *v > hi)
    throw UserError(field, "in '" + spec + "': expected an integer in [" + std::to_string(lo) + ", " +
                               std::to_string(hi) + "], got '" + text + "'");
  return *v;
}

double parse_positive(const std::string& text, const std::string& field, const std::string& spec) {
  const std::optional<double> v = parse_finite(text);
  if (!v || *v <= 0) throw UserError(field, "in '" + spec + "': expected a positive number, got '" + text + "'");
  return *v;
}

std::string default_leaf_side(const Scene& scene) {
  // The surface under study by name: the paper's ground, a room's floor (the Cornell box's, whose
  // ceiling is a little larger).
  for (const char* name : {"ground", "floor"})
    if (const std::optional<size_t> k = scene.find_surface(name)) return side_name(scene.surfaces[*k], false);
  size_t best = 0;
  for (size_t k = 1; k < scene.surfaces.size(); ++k)
    if (scene.surfaces[k].area_m2() > scene.surfaces[best].area_m2()) best = k;
  return side_name(scene.surfaces[best], false);
}


Solution solve_by_spec(const Scene& scene, const std::string& spec, const SolveSettings& settings,
                       const std::string& field) {
  const auto colon = spec.find(':');
  if (colon == std::string::npos)
    throw UserError(field, "expected grid:N, quadtree:LEAVES or quadtree-eps:E, got '" + spec + "'");
  const std::string kind = mesh_kind(spec), value = spec.substr(colon + 1);
  if (kind == "grid") {
    const int n = static_cast<int>(spec_integer(value, 1, 100000, field, spec));
    const GridMeshOptions mesh_options{n, settings.patches > 0 ? settings.patches : default_patches()};
    const size_t elements = grid_element_count(scene, mesh_options);
    check_limit(Limit::elements, static_cast<long long>(elements), field, "'" + spec + "' makes",
                "use a smaller N");
    Mesh mesh = make_grid_mesh(scene, mesh_options);
    if (!settings.progress_label.empty())
      std::fprintf(stderr, "%s: %s, %zu elements on %zu surface sides\n", settings.progress_label.c_str(), spec.c_str(),
                   mesh.element_count(), mesh.surfaces.size());
    ProgressiveOptions po;
    po.residual = settings.residual;
    po.far_field_error = settings.far_field_error;
    po.clusters = settings.clusters;
    po.progress_label = settings.progress_label;
    return solve_progressive(scene, std::move(mesh), po, "grid:" + std::to_string(n));
  }
  HierarchicalOptions ho;
  ho.progress_label = settings.progress_label;
  ho.max_links = static_cast<size_t>(limit_value(Limit::links));
  if (kind == "quadtree-eps") {
    ho.epsilon_w = parse_positive(value, field, spec);
    return solve_hierarchical(scene, ho, spec, nullptr, field + " " + spec);  // named as grid:N's refusals are
  }
  if (kind == "quadtree") {
    const long long asked = spec_integer(value, 1, std::numeric_limits<int>::max(), field, spec);
    check_limit(Limit::leaves, asked, field, "'" + spec + "' asks for");
    const int leaves = static_cast<int>(asked);
    const std::string side = settings.leaves_on.empty() ? default_leaf_side(scene) : settings.leaves_on;
    if (!find_side(scene, side))
      throw UserError(settings.leaves_on_where, "the scene has no surface side named '" + side + "' (its sides: " + side_names(scene) + ")");
    return solve_hierarchical_leaves(scene, side, leaves, ho, field + " " + spec);
  }
  throw UserError(field, "unknown mesh kind '" + kind + "' in '" + spec + "' (expected grid, quadtree or quadtree-eps)");
}


/// Whether light reaches the enclosed area `region` of `side`: an element of the side inside it
/// is brighter than tol::kEnclosedLitRelative of `brightest_w_m2`. Inside: every corner of the
/// element in the region; where no element lies wholly inside it (a coarse mesh), its centroid.
bool lit(const SurfaceSolution& side, const Polyline& region, double brightest_w_m2) {
  const double dark_w_m2 = tol::kEnclosedLitRelative * brightest_w_m2;
  const SurfaceFrame frame = side.frame();
  bool any_whole = false, lit_whole = false, lit_centred = false;
  for (const SolutionElement& e : side.elements) {
    const std::array<Vec2, 4> corners = e.vertices();
    bool whole = true;
    for (int k = 0; k < e.vertex_count(); ++k) whole = whole && in_region(region, frame.st(corners[static_cast<size_t>(k)]));
    const bool bright = e.radiosity_w_m2.maxCoeff() > dark_w_m2;
    if (whole) any_whole = true, lit_whole = lit_whole || bright;
    else if (in_region(region, side.centroid_st(e))) lit_centred = lit_centred || bright;
  }
  return any_whole ? lit_whole : lit_centred;
}

/// Every side's contact lines (scene/contacts.h) as its barriers, its shadow lines
/// (scene/shadow_lines.h) too if asked, and its excluded regions: those the geometry hides, and
/// the enclosed areas faced by a surface standing on their outline that no light reaches (the
/// foot of a closed two-sided box; not the floor of a lit room whose walls stand inside its edge).
Solution with_barriers(const Scene& scene, Solution sol, bool shadow_lines_too) {
  double brightest_w_m2 = 0;
  for (const SurfaceSolution& side : sol.surfaces)
    for (const SolutionElement& e : side.elements) brightest_w_m2 = std::max(brightest_w_m2, e.radiosity_w_m2.maxCoeff());
  std::unordered_map<std::string, SideRef> sides;  // by name: one look-up a side, not a scan
  for (size_t k = 0; k < scene.surfaces.size(); ++k)
    for (bool back : {false, true})
      if (!back || scene.surfaces[k].two_sided) sides.emplace(side_name(scene.surfaces[k], back), SideRef{k, back});
  const ContactFinder contacts(scene);
  for (SurfaceSolution& side : sol.surfaces) {
    const auto ref = sides.find(side.name);
    if (ref == sides.end()) continue;
    SideContactSet found = contacts.at(ref->second);
    for (const Segment2& c : found.lines) side.barriers.push_back({c.a, c.b});
    if (shadow_lines_too)
      for (const Segment2& c : shadow_lines(scene, ref->second)) side.barriers.push_back({c.a, c.b});
    side.excluded.clear();
    const size_t faced_from = found.excluded.size() - found.faced;
    for (size_t k = 0; k < found.excluded.size(); ++k)
      if (k < faced_from || !lit(side, found.excluded[k], brightest_w_m2)) side.excluded.push_back(std::move(found.excluded[k]));
  }
  return sol;
}

/// Warns of each light (an emitting surface: only a front emits) that no other surface lies in
/// front of (beyond tol::kContactRelative of the other's size): all its power leaves the scene,
/// which is a light facing the wrong way far more often than an intended one (a lamp written
/// facing the sky beside one that works: 71% of the power lost without a word, an outside-in
/// trial). The first few are named, the rest counted. When no surface at all is lit,
/// solve_scene()'s own warning says so instead.
void warn_of_lights_facing_nothing(const Scene& scene) {
  constexpr size_t kNamed = 5;
  const size_t n = scene.surfaces.size();
  std::vector<double> touch_m(n);
  for (size_t j = 0; j < n; ++j)
    touch_m[j] = contact_tolerance_m(scene.surfaces[j]);
  size_t lost = 0;
  double lost_w = 0;
  for (size_t k = 0; k < n; ++k) {
    const Surface& s = scene.surfaces[k];
    if (!(s.emission_w_m2 > 0).any()) continue;
    const Vec3 n_front = s.normal();
    const double offset = n_front.dot(s.corners[0]);
    bool lights_something = false;
    for (size_t j = 0; j < n && !lights_something; ++j)
      if (j != k)
        for (const Vec3& c : scene.surfaces[j].polygon()) lights_something = lights_something || n_front.dot(c) - offset > touch_m[j];
    if (lights_something) continue;
    const double power_w = (s.emission_w_m2 * s.area_m2()).maxCoeff();
    if (++lost <= kNamed)
      warn("light '" + s.name + "' lights no surface: every other surface lies behind its plane, so its " +
           format_number(power_w) + " W leave the scene. A surface emits on its front, the side its corners run "
           "counter-clockwise around: check the order of its corners");
    else
      lost_w += power_w;
  }
  if (lost > kNamed)
    warn("and " + std::to_string(lost - kNamed) + " more lights light no surface (" + format_number(lost_w) + " W)");
}

}  // namespace

Solution solve_scene(const Scene& scene, const std::string& spec, const SolveSettings& settings,
                     const std::string& where) {
  check_settings(settings);
  Solution sol = with_barriers(scene, solve_by_spec(scene, spec, settings, where), settings.shadow_barriers);
  if (const NegativeRadiosity negative = clamp_negative_radiosity(sol); negative.count > 0)
    warn(std::to_string(negative.count) + " radiosity values below zero (down to " +
         format_number(negative.most_negative_w_m2) +
         " W/m^2, the far field's truncation) were set to 0; a smaller --far-field-error avoids them");
  // Power emitted and none absorbed: no light reaches a surface, which is a scene facing the
  // wrong way far more often than an intended one (a lamp facing the sky, a floor upside down).
  const SolveStats& st = sol.stats;
  if ((st.absorbed_w > 0).any()) warn_of_lights_facing_nothing(scene);
  if ((st.emitted_w > 0).any() && !(st.absorbed_w > 0).any())
    warn("no light reaches any surface: all " + format_number(st.emitted_w.maxCoeff()) +
         " W emitted left the scene. A surface emits and reflects on its front, the side its corners run "
         "counter-clockwise around: check that the lights face the surfaces and the surfaces face the lights "
         "(or make them two_sided)");
  return sol;
}

}  // namespace radrecon
