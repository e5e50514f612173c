#include "solver/progressive.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <limits>
#include <memory>
#include <numeric>
#include <span>

#include "core/check.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/tolerances.h"
#include "solver/bvh.h"
#include "solver/covered.h"
#include "solver/enclosed.h"
#include "solver/gather.h"
#include "solver/patch_views.h"
#include "solver/shooter_clusters.h"
#include "solver/shooter_tree.h"
#include "solver/shooting_patches.h"
#include "solver/visibility.h"

namespace radrecon {

namespace {

/// Per element of a side, W/m^2: radiosity at the element's centre; unshot radiosity and
/// irradiance as the element's means (Gathered), which carry the power.
struct SideState {
  std::vector<Rgb> radiosity, unshot, irradiance;
  /// The fraction of each element that surfaces lying on the side leave exposed (solver/covered.h),
  /// which scales the power it absorbs, reflects and emits; empty where nothing lies on it (1).
  std::vector<double> exposed;
  double exposed_at(size_t e) const { return exposed.empty() ? 1.0 : exposed[e]; }
};

/// A side that receives from the current shot: its elements are gain[first, first + their count).
struct ReceivingSide {
  size_t side;
  size_t first;
  std::vector<const Occluder*> blockers;  ///< in the shaft between the two surfaces
  /// Whether each element takes `blockers` as they are rather than searching its own shaft (see
  /// kFewBlockers).
  bool blockers_as_they_are = false;
};

/// At most this many blockers between a receiving side and the shooter, and each receiving
/// element takes them all rather than those in its own shaft: making the shaft costs more than
/// the shadow volumes it saves (9% of the processor time of the paper's reference solve, 4
/// blockers at most; 6% of the Cornell box's at grid:128, 10 faces of its two blocks). The same
/// visible polygons: the side's shaft holds every segment from a point of the side to the patch,
/// so the side's list holds every occluder that shades the patch from the element's points, and
/// with a convex solid's face seen from the back the face in front that hides what it would
/// (ConvexSolid::face_hides_nothing()). The form factors agree to round-off (an extra volume that
/// meets a block's polygon only loosely can send it down another path of the clipping).
constexpr size_t kFewBlockers = 12;

/// Receiving elements handed to a thread at a time: one costs a microsecond (a far patch, no
/// occluder) to milliseconds (a near one behind many occluders).
constexpr std::int64_t kReceiverGrain = 16;

}  // namespace

Solution solve_progressive(const Scene& scene, Mesh mesh, const ProgressiveOptions& options,
                           const std::string& mesh_spec) {
  RR_CHECK(options.residual > 0 && options.residual < 1, "residual must be in (0, 1)");
  RR_CHECK(options.far_field_error >= 0 && options.far_field_error < 1, "far_field_error must be in [0, 1)");
  const auto start = std::chrono::steady_clock::now();
  const std::vector<Occluder> occluders = make_occluders(scene);
  const OccluderBvh bvh(occluders);

  std::vector<SideState> state(mesh.surfaces.size());
  std::vector<ShooterSplits> splits;  // per side, for its shooter trees
  const ContactFinder contacts(scene);
  std::vector<SideContactSet> contacts_by_side;  // found once: the shooter trees' splits and the enclosed parts
  for (const MeshSurface& side : mesh.surfaces) {
    contacts_by_side.push_back(contacts.at(SideRef{side.scene_surface, side.back_side}));
    splits.push_back(shooter_splits(scene, side, contacts_by_side.back()));
  }
  const std::vector<std::vector<ConvexPolygon>> covers_by = covers_by_surface(scene);
  std::vector<std::vector<Receiver>> receivers = make_receivers(scene, mesh);  // once for all shots
  // Elements partly enclosed by surfaces standing on their side: they gather on their exposed
  // part, and their areas, which carry every power of the solve, are their exposed parts'.
  const std::vector<EnclosedElement> enclosed = enclosed_elements(scene, mesh, contacts_by_side);
  std::vector<SideContactSet>().swap(contacts_by_side);  // no further use
  std::vector<double> whole_area_m2;  // theirs, for the solution
  for (const EnclosedElement& x : enclosed) {
    MeshElement& element = mesh.surfaces[x.side].elements[x.element];
    whole_area_m2.push_back(element.area_m2);
    element.area_m2 *= std::max(x.exposed, tol::kEnclosedLeastFraction);
    if (!x.exposed_uv.empty())
      move_to_exposed_part(scene.surfaces[mesh.surfaces[x.side].scene_surface], x.exposed_uv, receivers[x.side][x.element]);
  }
  ShootingPatches shooting(mesh);
  const std::vector<ShootingPatch>& patches = shooting.patches();
  Rgb emitted = Rgb::Zero();
  double total_area_m2 = 0;
  for (size_t s = 0; s < mesh.surfaces.size(); ++s) {
    const MeshSurface& side = mesh.surfaces[s];
    SideState& st = state[s];
    const std::vector<ConvexPolygon>& covers = covers_by[side.scene_surface];
    if (!covers.empty()) {
      st.exposed.resize(side.elements.size());
      for (size_t e = 0; e < side.elements.size(); ++e) {
        const MeshElement& element = side.elements[e];
        st.exposed[e] = exposed_fraction({element.corners.data(), static_cast<size_t>(element.corner_count())}, side.normal, covers);
      }
    }
    st.radiosity.assign(side.elements.size(), side.emission_w_m2);
    st.unshot.resize(side.elements.size());
    st.irradiance.assign(side.elements.size(), Rgb::Zero());
    for (size_t e = 0; e < side.elements.size(); ++e) {
      st.unshot[e] = st.exposed_at(e) * side.emission_w_m2;
      emitted += side.elements[e].area_m2 * st.unshot[e];
      total_area_m2 += st.exposed_at(e) * side.elements[e].area_m2;
    }
  }
  std::vector<const std::vector<Rgb>*> unshot_by_side;
  for (const SideState& st : state) unshot_by_side.push_back(&st.unshot);
  std::vector<size_t> updated_sides(mesh.surfaces.size());  // the sides whose patches' power is summed again
  std::iota(updated_sides.begin(), updated_sides.end(), size_t{0});
  shooting.sum_power(mesh, unshot_by_side, updated_sides);
  // The sides of one element, grouped to shoot together (solver/shooter_clusters.h): their own
  // patches never shoot alone.
  const ShooterClusters clusters = options.clusters ? make_shooter_clusters(mesh) : ShooterClusters{};
  const auto cluster_of_side = [&](size_t s) { return clusters.empty() ? -1 : clusters.cluster_of_side[s]; };
  std::vector<double> cluster_unshot_w(clusters.roots.size());
  Rgb escaped = Rgb::Zero();
  const double emitted_sum = emitted.sum();
  RR_CHECK(emitted_sum > 0, "the scene emits no light");
  size_t shots = 0;
  Progress progress(options.progress_label, options.progress_label.empty());
  ConvergencePace pace(options.residual);
  std::vector<Gathered> gain;  // per receiving element of the shot, in the order of `jobs`
  std::vector<ReceivingSide> jobs;
  // The shooter trees' blocks, reused from shot to shot: made once, for the largest patch's tree
  // (made as it comes, it grew shot by shot: fresh pages and a copy each time).
  std::vector<Block> tree_storage;
  {
    size_t most_blocks = 0;
    for (const ShootingPatch& p : patches)
      most_blocks = std::max(most_blocks, ShooterTree::block_count(mesh.surfaces[p.surface], &splits[p.surface], p.i0,
                                                                   p.j0, p.i1, p.j1));
    tree_storage.resize(most_blocks);
  }
  double residual = 1.0;
  bool converged = false;  // the residual, not the shot limit, ended the loop
  // Made at a patch's first shot, with a far-field budget only; kept empty where they did not fit.
  std::vector<std::unique_ptr<PatchViews>> patch_views(options.far_field_error > 0 ? patches.size() : 0);
  size_t patch_view_bytes = 0, block_view_bytes = 0;

  while (true) {
    // The patch or cluster with the most unshot power (the first of equals).
    size_t best = 0;
    double best_w = -1;
    Rgb unshot_total = Rgb::Zero();
    std::fill(cluster_unshot_w.begin(), cluster_unshot_w.end(), 0.0);
    for (size_t k = 0; k < patches.size(); ++k) {
      unshot_total += patches[k].unshot_w;
      if (const int c = cluster_of_side(patches[k].surface); c >= 0) {
        cluster_unshot_w[static_cast<size_t>(c)] += patches[k].unshot_w.sum();
      } else if (patches[k].unshot_w.sum() > best_w) {
        best = k;
        best_w = patches[k].unshot_w.sum();
      }
    }
    int best_cluster = -1;
    for (size_t c = 0; c < cluster_unshot_w.size(); ++c)
      if (cluster_unshot_w[c] > best_w) best_cluster = static_cast<int>(c), best_w = cluster_unshot_w[c];
    residual = unshot_total.sum() / emitted_sum;
    if (residual > 0 && residual < 1) {
      // The residual falls about geometrically, more slowly as the solve goes on: the time left
      // at the pace of late (ConvergencePace).
      char what[96];
      std::snprintf(what, sizeof what, "the way to a residual of %.0e (%zu shots, unshot %.2e of emitted)",
                    options.residual, shots, residual);
      progress.update(pace.share_done(residual), what);
    }
    if (residual < options.residual) {
      converged = true;
      break;
    }
    if (options.max_shots != 0 && shots >= options.max_shots) break;

    // The receiving side of the receiving element of index i.
    const auto job_of = [&](std::int64_t i) {
      return std::prev(std::upper_bound(jobs.begin(), jobs.end(), static_cast<size_t>(i),
                                        [](size_t k, const ReceivingSide& s) { return k < s.first; }));
    };
    Rgb shot_power;
    if (best_cluster >= 0) {
      // A cluster shoots: every element of every side receives (the members from each other).
      const ClusterShot shot(scene, mesh, clusters, static_cast<size_t>(best_cluster), bvh, unshot_by_side);
      shot_power = shot.power_w();
      const ShooterClusters::Node& root = clusters.nodes[static_cast<size_t>(clusters.roots[static_cast<size_t>(best_cluster)])];
      // Every side receives, and its patches' power is summed again below.
      for (int m = root.begin; m < root.end; ++m) {
        const size_t s = clusters.sides[static_cast<size_t>(m)];
        std::fill(state[s].unshot.begin(), state[s].unshot.end(), Rgb::Zero());
      }
      jobs.clear();
      size_t receiving = 0;
      for (size_t r = 0; r < mesh.surfaces.size(); ++r) {
        jobs.push_back({r, receiving, {}});
        receiving += mesh.surfaces[r].elements.size();
      }
      gain.resize(receiving);
      parallel_for_grained(0, static_cast<std::int64_t>(receiving), kReceiverGrain, [&](std::int64_t i) {
        const auto job = job_of(i);
        gain[static_cast<size_t>(i)] = shot.gather(receivers[job->side][static_cast<size_t>(i) - job->first], job->side);
      });
    } else {
      const ShootingPatch shooter = patches[best];
      const MeshSurface& shooter_side = mesh.surfaces[shooter.surface];
      const Surface& shooter_surface = scene.surfaces[shooter_side.scene_surface];
      ShooterTree tree(shooter_surface, shooter_side, state[shooter.surface].unshot, shooter.i0, shooter.j0,
                       shooter.i1, shooter.j1, std::move(tree_storage), &splits[shooter.surface]);
      shot_power = shooter.unshot_w;
      shooting.shoot(mesh, best, state[shooter.surface].unshot);

      const Block& root = tree.root();
      ConvexPolygon patch_outline;
      for (int k = 0; k < root.corner_count; ++k) patch_outline.push(root.corners[k]);
      const double least_irradiance_w_m2 = tol::kFarFieldLeastIrradianceFraction * shot_power.sum() / total_area_m2;
      const Vec3 shooter_normal = shooter_side.normal;
      // The sides that can receive from the shooter, with the occluders in the shaft between the
      // two surfaces (then, per receiving element, in the shaft between the element and the
      // shooting patch: solver/bvh.h, the same shadows, fewer tests); their elements numbered
      // one after the other, so that one parallel loop covers every receiving element.
      const std::span<const Vec3> shooter_outline(root.corners.data(), static_cast<size_t>(root.corner_count));
      jobs.clear();
      size_t receiving = 0;
      for (size_t r = 0; r < mesh.surfaces.size(); ++r) {
        const MeshSurface& receiver = mesh.surfaces[r];
        // Neither side of the shooter's surface receives (ShootingPatches::shoot() counts on it).
        if (receiver.scene_surface == shooter_side.scene_surface) continue;
        if (!quads_face(scene.surfaces[receiver.scene_surface].corners, receiver.normal, shooter_surface.corners,
                        shooter_normal))
          continue;
        jobs.push_back({r, receiving, {}});
        receiving += receiver.elements.size();
      }
      parallel_for_coarse(0, static_cast<std::int64_t>(jobs.size()), [&](std::int64_t j) {
        ReceivingSide& job = jobs[static_cast<size_t>(j)];
        const MeshSurface& receiver = mesh.surfaces[job.side];
        job.blockers = bvh.between(shooter_outline, scene.surfaces[receiver.scene_surface].polygon(),
                                   receiver.scene_surface, shooter_side.scene_surface);
        job.blockers_as_they_are = job.blockers.size() <= kFewBlockers;
      });
      gain.resize(receiving);  // every entry is written below: no need to clear it first
      // The receiving element of index i: its side's job and its index on that side.
      const auto receiving_element = [&](std::int64_t i) {
        const auto job = job_of(i);
        const size_t e = static_cast<size_t>(i) - job->first;
        return std::pair<decltype(job), const Receiver&>{job, receivers[job->side][e]};
      };
      PatchViews* views = nullptr;
      if (options.far_field_error > 0 && receiving > 0) {
        std::unique_ptr<PatchViews>& v = patch_views[best];
        if (!v) {
          // The patch's first shot: a slot for each element off the midpoint rule, if they fit.
          v = std::make_unique<PatchViews>();
          if (patch_view_bytes + PatchViews::bytes(receiving, 0) <= kMostPatchViewBytes) {
            std::vector<std::uint8_t> at_centre(receiving);
            parallel_for(0, static_cast<std::int64_t>(receiving), [&](std::int64_t i) {
              at_centre[static_cast<size_t>(i)] = gathers_at_centre(root, receiving_element(i).second);
            });
            const size_t slots = receiving - static_cast<size_t>(std::count(at_centre.begin(), at_centre.end(), 1));
            if (patch_view_bytes + PatchViews::bytes(receiving, slots) <= kMostPatchViewBytes) {
              v->form_factor.assign(receiving, std::numeric_limits<double>::quiet_NaN());
              v->partly.assign(receiving, 0);
              v->gauss_at.assign(receiving, PatchViews::kAtCentre);
              std::uint32_t slot = 0;
              for (size_t k = 0; k < receiving; ++k)
                if (!at_centre[k]) v->gauss_at[k] = 4 * slot++;
              v->gauss.assign(4 * slots, std::numeric_limits<double>::quiet_NaN());
              patch_view_bytes += PatchViews::bytes(receiving, slots);
              // Block views where the tree is small and the most they can hold (every receiving
              // element, every block) fits in what is left of their bytes.
              const size_t blocks = ShooterTree::block_count(shooter_side, &splits[shooter.surface], shooter.i0,
                                                             shooter.j0, shooter.i1, shooter.j1);
              const size_t most_bytes = receiving * (sizeof(std::vector<BlockView>) + blocks * sizeof(BlockView));
              v->keep_blocks = options.keep_block_views && blocks <= kMostViewedBlocks &&
                               block_view_bytes + most_bytes <= kMostBlockViewBytes;
              if (v->keep_blocks) {
                v->blocks.resize(receiving);
                block_view_bytes += most_bytes;
              }
            }
          }
        }
        if (!v->form_factor.empty()) {
          RR_CHECK_EQ(v->form_factor.size(), receiving, "a patch's receivers changed between its shots");
          views = v.get();
        }
      }
      parallel_for_grained(0, static_cast<std::int64_t>(receiving), kReceiverGrain, [&](std::int64_t i) {
        const auto found = receiving_element(i);
        const auto job = found.first;
        const Receiver& element = found.second;
        const size_t e = static_cast<size_t>(i) - job->first;
        const MeshSurface& receiver = mesh.surfaces[job->side];
        // The occluders in the shaft between the element and the patch, searched when a shadow is
        // first needed (for the estimate and every gather below). gather() looks from the centre
        // and the Gauss points: the shaft from the centre, widened by their farthest distance from
        // it, holds every segment it follows.
        thread_local std::vector<const Occluder*> near;
        near.clear();
        const auto find_near = [&] {
          if (job->blockers.empty()) return;
          if (job->blockers_as_they_are) {
            near = job->blockers;
            return;
          }
          double reach_m = 0;
          for (int k = 0; k < element.gauss_count; ++k) reach_m = std::max(reach_m, (element.gauss[k] - element.center).norm());
          bvh.collect(Shaft({&element.center, 1}, shooter_outline, reach_m), receiver.scene_surface,
                      shooter_side.scene_surface, near);
        };
        const ReceiverShadows shadows(element, near, find_near, &patch_outline);
        const double so_far_w_m2 = state[job->side].irradiance[e].sum();
        double budget_w_m2 = 0;  // the distance rule
        SeenFromCentre seen{-1, false};  // the whole patch, as the root block's outline
        if (options.far_field_error > 0) {
          // A fraction of the element's irradiance: so far, plus this shot's from the whole patch.
          const size_t k = static_cast<size_t>(i);
          if (views != nullptr && !std::isnan(views->form_factor[k])) {
            seen = {views->form_factor[k], views->partly[k] != 0};
          } else {
            seen.form_factor = shadows.visible_form_factor(0, patch_outline, shooter_normal, &seen.partly);
            if (views != nullptr) views->form_factor[k] = seen.form_factor, views->partly[k] = seen.partly;
          }
          if (views != nullptr && views->gauss_at[k] != PatchViews::kAtCentre) seen.gauss = &views->gauss[views->gauss_at[k]];
          const double estimate = seen.form_factor * root.unshot_w_m2.sum();
          budget_w_m2 = options.far_field_error * std::max(so_far_w_m2 + estimate, least_irradiance_w_m2);
        }
        const SeenFromCentre* root_seen = seen.form_factor >= 0 ? &seen : nullptr;
        // What the element saw of the other blocks at the patch's last shot, and sees now.
        thread_local std::vector<BlockView> seen_now;
        seen_now.clear();
        BlockViews block_views;
        const bool keep_blocks = views != nullptr && views->keep_blocks;
        if (keep_blocks) block_views = {views->blocks[static_cast<size_t>(i)], &seen_now};
        const BlockViews* blocks_seen = keep_blocks ? &block_views : nullptr;
        // Occluders may hide part of the patch: less share for the strict bound alone (gather()).
        const double strict = seen.partly && !job->blockers.empty() ? tol::kPartlyHiddenStrictShare : 1.0;
        Gathered got = gather(tree, tree.root(), element, shooter_normal, shadows, budget_w_m2, root_seen, blocks_seen, strict);
        if (budget_w_m2 > 0) {
          // The whole patch's estimate can exceed what the element gets many times over (a dark
          // element beside a bright one, a patch seen in part): then again, for what it got.
          const double irradiance = so_far_w_m2 + std::min(got.at_center.sum(), got.mean.sum());
          const double budget_got = options.far_field_error * std::max(irradiance, least_irradiance_w_m2);
          if (budget_got < tol::kFarFieldRegatherRatio * budget_w_m2) {
            seen_now.clear();
            got = gather(tree, tree.root(), element, shooter_normal, shadows, budget_got, root_seen, blocks_seen, strict);
          }
        }
        gain[static_cast<size_t>(i)] = got;
        // Kept for an element behind many shadows, where finding them again costs most.
        if (keep_blocks) {
          std::vector<BlockView>& kept = views->blocks[static_cast<size_t>(i)];
          if (shadows.kept_fragments() || !kept.empty()) {
            std::sort(seen_now.begin(), seen_now.end(), [](const BlockView& a, const BlockView& b) { return a.block < b.block; });
            kept.assign(seen_now.begin(), seen_now.end());
          }
        }
      });
      tree_storage = std::move(tree).release();
    }
    // What each element keeps, side by side; the power delivered summed in order, on one thread.
    parallel_for(0, static_cast<std::int64_t>(gain.size()), [&](std::int64_t i) {
      const auto job = job_of(i);
      const size_t e = static_cast<size_t>(i) - job->first;
      SideState& st = state[job->side];
      Gathered& h = gain[static_cast<size_t>(i)];
      // A covered part receives nothing: its radiosity is the exposed part's.
      h.mean *= st.exposed_at(e);
      const Rgb& reflectance = mesh.surfaces[job->side].reflectance;
      st.irradiance[e] += h.mean;
      st.radiosity[e] += reflectance * h.at_center;
      st.unshot[e] += reflectance * h.mean;
    });
    Rgb delivered = Rgb::Zero();
    updated_sides.clear();
    for (const ReceivingSide& job : jobs) {
      const MeshSurface& receiver = mesh.surfaces[job.side];
      for (size_t e = 0; e < receiver.elements.size(); ++e) delivered += receiver.elements[e].area_m2 * gain[job.first + e].mean;
      updated_sides.push_back(job.side);
    }
    shooting.sum_power(mesh, unshot_by_side, updated_sides);
    escaped += shot_power - delivered;
    ++shots;
  }

  // The shots' buffers freed first: the solution's elements take their memory, not fresh pages.
  [](auto&... v) { (std::remove_reference_t<decltype(v)>().swap(v), ...); }(receivers, patch_views, tree_storage, gain);
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
    // A triangle's elements are no grid of boxes: its sides reconstruct as scattered data.
    out.grid_nu = side.domain.is_triangle() ? 0 : side.nu;
    out.grid_nv = side.domain.is_triangle() ? 0 : side.nv;
    out.length_u_m = surface.length_u_m();
    out.length_v_m = surface.length_v_m();
    out.shear_m = surface.shear_m();
    out.triangle = surface.is_triangle();
    out.elements.reserve(side.elements.size());
    for (size_t e = 0; e < side.elements.size(); ++e) {
      const MeshElement& m = side.elements[e];
      out.elements.push_back({m, m.center, m.area_m2, state[s].radiosity[e]});
      stats.absorbed_w += m.area_m2 * (1.0 - side.reflectance) * state[s].irradiance[e];
      stats.unshot_w += m.area_m2 * state[s].unshot[e];
    }
    stats.elements += side.elements.size();
    sol.surfaces.push_back(std::move(out));
  }
  // The file keeps each element's whole area, as its cell has it.
  for (size_t k = 0; k < enclosed.size(); ++k)
    sol.surfaces[enclosed[k].side].elements[enclosed[k].element].area_m2 = whole_area_m2[k];
  stats.residual = stats.unshot_w.sum() / emitted_sum;
  stats.converged = converged;
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  progress.done();
  if (!options.progress_label.empty())
    std::fprintf(stderr, "%s: %zu shots, unshot %.2e of emitted, %.2f s\n", options.progress_label.c_str(),
                 shots, stats.residual, stats.seconds);
  return sol;
}

}  // namespace radrecon
