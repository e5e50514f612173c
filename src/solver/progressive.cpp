#include "solver/progressive.h"

#include <chrono>
#include <cstdio>
#include <limits>

#include "core/check.h"
#include "core/parallel.h"
#include "core/tolerances.h"
#include "solver/bvh.h"
#include "solver/visibility.h"

namespace radrecon {

namespace {

/// A node of the shooting hierarchy over one patch: the elements [i0,i1) x [j0,j1).
struct Block {
  std::array<Vec3, 4> corners;
  Vec3 center;
  double diagonal_m = 0;
  Rgb unshot_w_m2 = Rgb::Zero();  ///< area-weighted mean unshot radiosity of the block
  bool uniform = true;            ///< every element has the same unshot radiosity
  int first_child = -1;           ///< children are consecutive; -1 for a single element
  int child_count = 0;
};

class ShooterTree {
 public:
  ShooterTree(const Surface& surface, const MeshSurface& side, const std::vector<Rgb>& unshot,
              int i0, int j0, int i1, int j1)
      : surface_(surface), side_(side), unshot_(unshot) {
    blocks_.reserve(static_cast<size_t>(2 * (i1 - i0) * (j1 - j0)));
    blocks_.emplace_back();
    build(0, i0, j0, i1, j1);
  }

  const Block& root() const { return blocks_[0]; }
  const Block& block(int k) const { return blocks_[static_cast<size_t>(k)]; }

 private:
  void build(size_t index, int i0, int j0, int i1, int j1) {
    const int nu = side_.nu, nv = side_.nv;
    MeshElement e = make_element(surface_, side_.back_side, double(i0) / nu, double(j0) / nv,
                                 double(i1) / nu, double(j1) / nv);
    Rgb weighted = Rgb::Zero(), lo = unshot_[static_cast<size_t>(j0) * nu + i0], hi = lo;
    double area = 0;
    for (int j = j0; j < j1; ++j)
      for (int i = i0; i < i1; ++i) {
        size_t k = static_cast<size_t>(j) * nu + i;
        double a = side_.elements[k].area_m2;
        weighted += a * unshot_[k];
        area += a;
        lo = lo.min(unshot_[k]);
        hi = hi.max(unshot_[k]);
      }
    Block& b = blocks_[index];
    b.corners = e.corners;
    b.center = e.center;
    b.diagonal_m = std::max((e.corners[2] - e.corners[0]).norm(), (e.corners[3] - e.corners[1]).norm());
    b.unshot_w_m2 = weighted / area;
    b.uniform = ((hi - lo) <= tol::kUniformRelative * hi.abs().max(std::numeric_limits<double>::min())).all();
    if (i1 - i0 == 1 && j1 - j0 == 1) return;
    const int mi = (i1 - i0) > 1 ? (i0 + i1) / 2 : i1;
    const int mj = (j1 - j0) > 1 ? (j0 + j1) / 2 : j1;
    std::array<std::array<int, 4>, 4> quads = {{{i0, j0, mi, mj}, {mi, j0, i1, mj}, {i0, mj, mi, j1}, {mi, mj, i1, j1}}};
    int first = static_cast<int>(blocks_.size());
    int count = 0;
    for (const auto& q : quads)
      if (q[2] > q[0] && q[3] > q[1]) ++count;
    blocks_[index].first_child = first;
    blocks_[index].child_count = count;
    blocks_.resize(blocks_.size() + static_cast<size_t>(count));
    int c = 0;
    for (const auto& q : quads)
      if (q[2] > q[0] && q[3] > q[1]) build(static_cast<size_t>(first + c++), q[0], q[1], q[2], q[3]);
  }

  const Surface& surface_;
  const MeshSurface& side_;
  const std::vector<Rgb>& unshot_;
  std::vector<Block> blocks_;
};

/// Irradiance (W/m^2 per channel) at receiver point p (unit normal n) from the shooter's unshot
/// radiosity: the block as a whole when far or uniform, else the sum over its children.
Rgb gather(const ShooterTree& tree, const Block& b, const Vec3& p, const Vec3& n,
           const Vec3& shooter_normal, const std::vector<const Occluder*>& occluders) {
  if (b.first_child < 0 || b.uniform ||
      (p - b.center).squaredNorm() > tol::kFarFieldDiagonals * tol::kFarFieldDiagonals * b.diagonal_m * b.diagonal_m) {
    if ((b.unshot_w_m2 == 0).all()) return Rgb::Zero();
    ConvexPolygon poly;
    for (const Vec3& c : b.corners) poly.push(c);
    return visible_form_factor(p, n, poly, shooter_normal, occluders) * b.unshot_w_m2;
  }
  Rgb sum = Rgb::Zero();
  for (int c = 0; c < b.child_count; ++c)
    sum += gather(tree, tree.block(b.first_child + c), p, n, shooter_normal, occluders);
  return sum;
}

struct Patch {
  size_t surface;
  int i0, j0, i1, j1;
  Rgb unshot_w = Rgb::Zero();  ///< unshot power per channel, W
};

struct SideState {
  std::vector<Rgb> radiosity, unshot, irradiance;
};

}  // namespace

Solution solve_progressive(const Scene& scene, const Mesh& mesh, const ProgressiveOptions& options,
                           const std::string& mesh_spec) {
  RR_CHECK(options.residual > 0 && options.residual < 1, "residual must be in (0, 1)");
  const auto start = std::chrono::steady_clock::now();
  const std::vector<Occluder> occluders = make_occluders(scene);
  const OccluderBvh bvh(occluders);

  std::vector<SideState> state(mesh.surfaces.size());
  std::vector<Patch> patches;
  std::vector<size_t> first_patch(mesh.surfaces.size());
  Rgb emitted = Rgb::Zero();
  for (size_t s = 0; s < mesh.surfaces.size(); ++s) {
    const MeshSurface& side = mesh.surfaces[s];
    SideState& st = state[s];
    st.radiosity.assign(side.elements.size(), side.emission_w_m2);
    st.unshot.assign(side.elements.size(), side.emission_w_m2);
    st.irradiance.assign(side.elements.size(), Rgb::Zero());
    for (const MeshElement& e : side.elements) emitted += e.area_m2 * side.emission_w_m2;
    first_patch[s] = patches.size();
    for (int pj = 0; pj < side.patches_v(); ++pj)
      for (int pi = 0; pi < side.patches_u(); ++pi)
        patches.push_back({s, pi * side.patch_size, pj * side.patch_size,
                           std::min(side.nu, (pi + 1) * side.patch_size),
                           std::min(side.nv, (pj + 1) * side.patch_size)});
  }
  auto update_patch_power = [&](size_t s) {
    const MeshSurface& side = mesh.surfaces[s];
    const size_t count = static_cast<size_t>(side.patches_u()) * side.patches_v();
    for (size_t k = 0; k < count; ++k) patches[first_patch[s] + k].unshot_w = Rgb::Zero();
    for (int j = 0; j < side.nv; ++j)
      for (int i = 0; i < side.nu; ++i) {
        size_t e = static_cast<size_t>(j) * side.nu + i;
        size_t p = first_patch[s] + static_cast<size_t>(j / side.patch_size) * side.patches_u() + i / side.patch_size;
        patches[p].unshot_w += side.elements[e].area_m2 * state[s].unshot[e];
      }
  };
  for (size_t s = 0; s < mesh.surfaces.size(); ++s) update_patch_power(s);

  Rgb escaped = Rgb::Zero();
  const double emitted_sum = emitted.sum();
  RR_CHECK(emitted_sum > 0, "the scene emits no light");
  size_t shots = 0;
  auto last_report = start;
  std::vector<Rgb> gain;
  double residual = 1.0;
  bool converged = false;  // the residual, not the shot limit, ended the loop

  while (true) {
    size_t best = 0;
    Rgb unshot_total = Rgb::Zero();
    for (size_t k = 0; k < patches.size(); ++k) {
      unshot_total += patches[k].unshot_w;
      if (patches[k].unshot_w.sum() > patches[best].unshot_w.sum()) best = k;
    }
    residual = unshot_total.sum() / emitted_sum;
    auto now = std::chrono::steady_clock::now();
    if (!options.progress_label.empty() && now - last_report > std::chrono::seconds(2) && residual >= options.residual) {
      std::fprintf(stderr, "%s: %zu shots, unshot %.2e of emitted\n", options.progress_label.c_str(),
                   shots, residual);
      last_report = now;
    }
    if (residual < options.residual) {
      converged = true;
      break;
    }
    if (options.max_shots != 0 && shots >= options.max_shots) break;

    const Patch shooter = patches[best];
    const MeshSurface& shooter_side = mesh.surfaces[shooter.surface];
    const Surface& shooter_surface = scene.surfaces[shooter_side.scene_surface];
    const ShooterTree tree(shooter_surface, shooter_side, state[shooter.surface].unshot, shooter.i0,
                           shooter.j0, shooter.i1, shooter.j1);
    Rgb shot_power = shooter.unshot_w;
    for (int j = shooter.j0; j < shooter.j1; ++j)
      for (int i = shooter.i0; i < shooter.i1; ++i)
        state[shooter.surface].unshot[static_cast<size_t>(j) * shooter_side.nu + i] = Rgb::Zero();
    update_patch_power(shooter.surface);

    const auto& sc = tree.root().corners;
    const Vec3 shooter_normal = shooter_side.normal;
    Rgb delivered = Rgb::Zero();
    for (size_t r = 0; r < mesh.surfaces.size(); ++r) {
      const MeshSurface& receiver = mesh.surfaces[r];
      if (receiver.scene_surface == shooter_side.scene_surface) continue;
      const Surface& receiver_surface = scene.surfaces[receiver.scene_surface];
      if (!quads_face(receiver_surface.corners, receiver.normal, sc, shooter_normal)) continue;
      // Occluders in the shaft between the two surfaces; then, per receiver point, in the shaft
      // between the point and the shooting patch (solver/bvh.h: the same shadows, fewer tests).
      const std::vector<const Occluder*> blockers =
          bvh.between(sc, receiver_surface.corners, receiver.scene_surface, shooter_side.scene_surface);

      gain.assign(receiver.elements.size(), Rgb::Zero());
      parallel_for(0, static_cast<std::int64_t>(receiver.elements.size()), [&](std::int64_t e) {
        const Vec3& p = receiver.elements[static_cast<size_t>(e)].center;
        thread_local std::vector<const Occluder*> near;
        near.clear();
        if (!blockers.empty())
          bvh.collect(Shaft({&p, 1}, sc), receiver.scene_surface, shooter_side.scene_surface, near);
        gain[static_cast<size_t>(e)] = gather(tree, tree.root(), p, receiver.normal, shooter_normal, near);
      });
      SideState& st = state[r];
      for (size_t e = 0; e < receiver.elements.size(); ++e) {
        const Rgb& h = gain[e];
        st.irradiance[e] += h;
        st.radiosity[e] += receiver.reflectance * h;
        st.unshot[e] += receiver.reflectance * h;
        delivered += receiver.elements[e].area_m2 * h;
      }
      update_patch_power(r);
    }
    escaped += shot_power - delivered;
    ++shots;
  }

  Solution sol;
  sol.scene = scene.name;
  sol.mesh = mesh_spec;
  SolveStats& stats = sol.stats;
  stats.method = "progressive";
  stats.shots = shots;
  stats.patches = patches.size();
  stats.emitted_w = emitted;
  stats.escaped_w = escaped;
  for (size_t s = 0; s < mesh.surfaces.size(); ++s) {
    const MeshSurface& side = mesh.surfaces[s];
    const Surface& surface = scene.surfaces[side.scene_surface];
    SurfaceSolution out;
    out.name = side.name;
    out.scene_surface = surface.name;
    out.back_side = side.back_side;
    out.grid_nu = side.nu;
    out.grid_nv = side.nv;
    out.length_u_m = surface.length_u_m();
    out.length_v_m = surface.length_v_m();
    out.elements.reserve(side.elements.size());
    for (size_t e = 0; e < side.elements.size(); ++e) {
      const MeshElement& m = side.elements[e];
      out.elements.push_back({m.u0, m.v0, m.u1, m.v1, m.center, m.area_m2, state[s].radiosity[e]});
      stats.absorbed_w += m.area_m2 * (1.0 - side.reflectance) * state[s].irradiance[e];
      stats.unshot_w += m.area_m2 * state[s].unshot[e];
    }
    stats.elements += side.elements.size();
    sol.surfaces.push_back(std::move(out));
  }
  stats.residual = stats.unshot_w.sum() / emitted_sum;
  stats.converged = converged;
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!options.progress_label.empty())
    std::fprintf(stderr, "%s: %zu shots, unshot %.2e of emitted, %.2f s\n", options.progress_label.c_str(),
                 shots, stats.residual, stats.seconds);
  return sol;
}

}  // namespace radrecon
