#include "solver/gather.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include "core/parallel.h"
#include "core/tolerances.h"
#include "solver/far_field.h"

namespace radrecon {

GaussPoints gauss_points(const ParamCell& e) {
  GaussPoints out;
  if (e.is_triangle()) {
    const auto v = e.vertices();
    for (int k = 0; k < 3; ++k) out.uv[out.count++] = (4.0 * v[k] + v[(k + 1) % 3] + v[(k + 2) % 3]) / 6.0;
    return out;
  }
  const double g = 0.5 / std::sqrt(3.0);  // Gauss-Legendre nodes at the centre +- half-width / sqrt(3)
  const double um = 0.5 * (e.u0 + e.u1), vm = 0.5 * (e.v0 + e.v1);
  const double du = (e.u1 - e.u0) * g, dv = (e.v1 - e.v0) * g;
  for (const double sv : {-1.0, 1.0})
    for (const double su : {-1.0, 1.0}) out.uv[out.count++] = Vec2(um + su * du, vm + sv * dv);
  return out;
}

Receiver make_receiver(const Surface& surface, const MeshElement& e, const Vec3& normal) {
  Receiver r;
  r.center = e.center;
  r.normal = normal;
  r.size_m = std::max((e.corners[2] - e.corners[0]).norm(), (e.corners[3] - e.corners[1]).norm());
  const GaussPoints g = gauss_points(e);
  for (int k = 0; k < g.count; ++k) r.gauss[k] = surface.point(g.uv[k].x(), g.uv[k].y());
  r.gauss_count = g.count;
  return r;
}

std::vector<std::vector<Receiver>> make_receivers(const Scene& scene, const Mesh& mesh) {
  std::vector<std::vector<Receiver>> out(mesh.surfaces.size());
  for (size_t s = 0; s < mesh.surfaces.size(); ++s) {
    const MeshSurface& side = mesh.surfaces[s];
    out[s].resize(side.elements.size());
    parallel_for(0, static_cast<std::int64_t>(side.elements.size()), [&](std::int64_t e) {
      out[s][static_cast<size_t>(e)] =
          make_receiver(scene.surfaces[side.scene_surface], side.elements[static_cast<size_t>(e)], side.normal);
    });
  }
  return out;
}

double form_factor_bound(const Block& b, const Vec3& p, const Vec3& n, const Vec3& shooter_normal) {
  const double d = (p - b.center).norm() - b.radius_m;  // no point of the block is nearer to p
  if (!(d > 0)) return std::numeric_limits<double>::infinity();
  const double h = shooter_normal.dot(p - b.center);  // cos_y = h / r, the same plane for all y
  double lift = 0;  // n . (y - p) is linear in y: largest at a corner
  for (int k = 0; k < b.corner_count; ++k) lift = std::max(lift, n.dot(b.corners[k] - p));
  if (!(h > 0) || !(lift > 0)) return 0;
  return b.area_m2 * std::min(1.0, lift / d) * std::min(1.0, h / d) / (std::numbers::pi * d * d);
}

double form_factor_ceiling(const Block& b, const Vec3& p, const Vec3& shooter_normal) {
  const double h = shooter_normal.dot(p - b.center);
  return h > 0 ? std::min(1.0, b.area_m2 / (std::numbers::pi * h * h)) : 0.0;
}

bool gathers_at_centre(const Block& b, const Receiver& r) {
  const double gap_m = (r.center - b.center).norm() - 0.5 * b.diagonal_m;
  return r.size_m <= tol::kMidpointReceiverRatio * gap_m;
}

namespace {

/// What shoots_whole() found at the receiving element's centre, for gather() to reuse: the
/// visible form factor (-1 if not computed) and the kernel's log-gradient (if computed: `g` when
/// `expands`, else the angle is grazing).
struct AtCentre {
  double f = -1;
  bool partly_seen = false;  ///< with f: whether the centre sees the block in part
  bool gradient_known = false, expands = false;
  Vec3 g;
  std::optional<KernelSecondOrder> second_order;  ///< if far_field_error() computed it
};

/// Whether the block may shoot to the receiving element as one source: see gather(). Fills
/// `centre` with what it computed there to decide. `midpoint`: the element gathers at its
/// centre alone.
bool shoots_whole(const Block& b, const ConvexPolygon& poly, const Receiver& r, const Vec3& shooter_normal,
                  const ReceiverShadows& shadows, double budget_w_m2, double strict_share, bool midpoint, bool alone,
                  AtCentre& centre) {
  double& f = centre.f;
  if (b.first_child < 0 || b.uniform) return true;
  const Vec3 &p = r.center, &n = r.normal;
  if (budget_w_m2 <= 0) {
    const double far_m = tol::kFarFieldDiagonals * b.diagonal_m;
    return (p - b.center).squaredNorm() > far_m * far_m;
  }
  const double spread = (b.highest_w_m2 - b.lowest_w_m2).sum();
  // Any far field lies in [lowest, highest] times the visible form factor, as the children's sum
  // does: a strict bound with form_factor_bound() at the centre (the Gauss points, which only
  // the element's power uses, are within half its size of it).
  double form_factor = form_factor_bound(b, p, n, shooter_normal);
  if (form_factor * spread <= strict_share * budget_w_m2) return true;
  // Near the block, where that bound is large or infinite, a ceiling that holds everywhere, with
  // a tenth of the share: the error there has one sign over the elements around the block. Off
  // the midpoint rule, the largest at the Gauss points too, which carry the element's power (a
  // point nearer the shooter's plane, or in front of it when the centre is not): looked at only
  // when the centre's passes, as the largest can only be more.
  const double ceiling_share = strict_share * tol::kNearFieldCeilingShare * budget_w_m2;
  if (double ceiling = form_factor_ceiling(b, p, shooter_normal); ceiling * spread <= ceiling_share) {
    if (!midpoint)
      for (int k = 0; k < r.gauss_count; ++k) ceiling = std::max(ceiling, form_factor_ceiling(b, r.gauss[k], shooter_normal));
    if (ceiling * spread <= ceiling_share) return true;
  }
  if (!std::isfinite(form_factor)) return false;
  // A block seen in part splits: it would shoot with the mean of all of it, an error within the
  // bound but of one sign for every element that sees the same part (the ground's blocks behind
  // a wall's horizon), which adds up over the shots: the paper's walls were 0.1% too dark.
  // An element on the midpoint rule needs the visible form factor whatever follows (to shoot
  // with, or to bound with): it looks first, and a block it sees in part, or that the strict
  // bound with it lets through, costs no far-field error estimate.
  if (midpoint) {
    if (f < 0) f = shadows.visible_form_factor(0, poly, shooter_normal, &centre.partly_seen, alone);
    if (centre.partly_seen) return false;
    form_factor = f;
    if (f * spread <= budget_w_m2) return true;
  }
  // The far field is exact to second order, whatever the radiosity over the block
  // (far_field_radiosity()): what is left is the spread times the kernel's third order,
  // provided the centre sees all of the block (else the kernel seen is cut).
  centre.gradient_known = true;
  centre.expands = kernel_log_gradient(b, p, n, shooter_normal, centre.g);
  const double error_per_spread = centre.expands ? far_field_error(b, p, n, shooter_normal, centre.g, &centre.second_order)
                                                 : std::numeric_limits<double>::infinity();
  // On the midpoint rule with the visible form factor; off it with the bound's (an element that
  // gathers at its Gauss points looks at the visible one only if this passes).
  if (!(form_factor * spread * error_per_spread <= budget_w_m2)) return false;
  if (f < 0) f = shadows.visible_form_factor(0, poly, shooter_normal, &centre.partly_seen, alone);
  return !centre.partly_seen;
}

}  // namespace

std::span<const ShadowVolume> ReceiverShadows::at(int point) const {
  RR_CHECK(point >= 0 && point <= r_.gauss_count, "receiver point out of range");
  const size_t k = static_cast<size_t>(point);
  if (!made_[k]) {
    if (find_ != nullptr && !found_) {
      call_find_(find_);
      found_ = true;
    }
    shadow_volumes(point == 0 ? r_.center : r_.gauss[k - 1], r_.normal, occluders_, volumes_[k]);
    made_[k] = true;
  }
  return volumes_[k];
}

thread_local std::array<std::vector<ShadowVolume>, 5> ReceiverShadows::volumes_;
thread_local std::array<VisibleFragments, 5> ReceiverShadows::fragments_;

bool ReceiverShadows::keeps_fragments(int point, const Vec3& shooter_normal) const {
  const size_t k = static_cast<size_t>(point);
  if (fragments_state_[k] == Fragments::unknown) {
    const std::span<const ShadowVolume> volumes = at(point);
    const Vec3& p = point == 0 ? r_.center : r_.gauss[k - 1];
    fragments_state_[k] = patch_ != nullptr && volumes.size() >= tol::kKeptFragmentsShadows &&
                                  fragments_[k].find(p, r_.normal, *patch_, shooter_normal, volumes)
                              ? Fragments::kept
                              : Fragments::not_kept;
  }
  return fragments_state_[k] == Fragments::kept;
}

double ReceiverShadows::visible_form_factor(int point, const ConvexPolygon& polygon, const Vec3& shooter_normal,
                                            bool* partly_seen, bool alone) const {
  if (uses_fragments(point, shooter_normal, alone)) return fragments_[static_cast<size_t>(point)].form_factor(polygon, partly_seen);
  const Vec3& p = point == 0 ? r_.center : r_.gauss[static_cast<size_t>(point - 1)];
  return visible_form_factor_past(p, r_.normal, polygon, shooter_normal, at(point), partly_seen);
}

const BlockView* BlockViews::find(std::uint32_t block) const {
  const auto it = std::lower_bound(last.begin(), last.end(), block,
                                   [](const BlockView& v, std::uint32_t k) { return v.block < k; });
  return it != last.end() && it->block == block ? &*it : nullptr;
}

Gathered gather(const ShooterTree& tree, const Block& b, const Receiver& r, const Vec3& shooter_normal,
                const ReceiverShadows& shadows, double budget_w_m2, const SeenFromCentre* seen,
                const BlockViews* views, double strict_share) {
  Gathered out;
  if ((b.highest_w_m2 == 0).all()) return out;
  AtCentre centre;
  // What the element saw of this block at its last gather from the patch (not the root's: `seen`).
  const std::uint32_t index = static_cast<std::uint32_t>(&b - &tree.root());
  const BlockView* known = seen == nullptr && views != nullptr ? views->find(index) : nullptr;
  // A block without a view from the element's last gather (this shot goes one level deeper, or
  // the block had no unshot power then): its form factors alone, rather than finding the
  // patch's fragments for it.
  const bool alone = known == nullptr && seen == nullptr && views != nullptr && !views->last.empty();
  BlockView now;  // what it sees of it this time
  now.block = index;
  if (seen != nullptr) centre.f = seen->form_factor, centre.partly_seen = seen->partly;
  if (known != nullptr && known->centre_known) centre.f = known->centre, centre.partly_seen = known->partly;
  // Keeps what the element saw of the block, as it leaves it, for the next shot.
  const auto keep = [&] {
    if (seen != nullptr || views == nullptr) return;
    now.centre_known = centre.f >= 0;
    if (now.centre_known) now.centre = centre.f, now.partly = centre.partly_seen;
    views->now->push_back(now);
  };
  // The budget is shared among the blocks in proportion to their area: those that shoot as one
  // tile the patch, so their errors add up to at most budget_w_m2.
  const double share = budget_w_m2 * b.area_m2 / tree.root().area_m2;
  const bool midpoint = gathers_at_centre(b, r);
  ConvexPolygon poly;  // the block's outline, for its form factors
  for (int k = 0; k < b.corner_count; ++k) poly.push(b.corners[k]);
  if (!shoots_whole(b, poly, r, shooter_normal, shadows, share, strict_share, midpoint, alone, centre)) {
    keep();
    for (int c = 0; c < b.child_count; ++c)
      out += gather(tree, tree.block(b.first_child + c), r, shooter_normal, shadows, budget_w_m2, nullptr, views,
                    strict_share);
    return out;
  }
  // At the centre, with what shoots_whole() found there.
  if (centre.f < 0) centre.f = shadows.visible_form_factor(0, poly, shooter_normal, &centre.partly_seen, alone);
  const double f_centre = centre.f;
  if (f_centre == 0 || b.uniform)
    out.at_center = f_centre * b.unshot_w_m2;
  else if (centre.gradient_known)
    out.at_center = f_centre * far_field_radiosity(b, r.center, r.normal, shooter_normal, centre.expands ? &centre.g : nullptr,
                                                   centre.second_order ? &*centre.second_order : nullptr);
  else
    out.at_center = f_centre * far_field_radiosity(b, r.center, r.normal, shooter_normal);
  if (midpoint) {
    out.mean = out.at_center;
  } else {
    // The Gauss points' form factors together: those that see all of the block in one
    // vectorised integral.
    std::array<double, 4> f;
    const size_t count = static_cast<size_t>(r.gauss_count);
    double* kept = seen != nullptr ? seen->gauss : nullptr;  // the block's, from an earlier gather
    if (kept != nullptr && !std::isnan(kept[0])) {
      std::copy(kept, kept + count, f.begin());
    } else if (known != nullptr && known->gauss_known) {
      std::copy(known->gauss.begin(), known->gauss.begin() + static_cast<std::ptrdiff_t>(count), f.begin());
    } else {
      // Those behind many shadows through the patch's kept fragments, the others in a batch.
      std::array<Vec3, 4> points;
      std::array<std::span<const ShadowVolume>, 4> volumes;
      std::array<size_t, 4> slot;
      std::array<double, 4> batch;
      size_t batched = 0;
      for (size_t k = 0; k < count; ++k) {
        const int point = static_cast<int>(k) + 1;
        if (shadows.uses_fragments(point, shooter_normal, alone)) {
          f[k] = shadows.visible_form_factor(point, poly, shooter_normal);
        } else {
          points[batched] = r.gauss[k];
          volumes[batched] = shadows.at(point);
          slot[batched++] = k;
        }
      }
      if (batched > 0) {
        visible_form_factors_past({points.data(), batched}, r.normal, poly, shooter_normal, {volumes.data(), batched},
                                  {batch.data(), batched});
        for (size_t i = 0; i < batched; ++i) f[slot[i]] = batch[i];
      }
      if (kept != nullptr) std::copy(f.begin(), f.begin() + static_cast<std::ptrdiff_t>(count), kept);
    }
    // Their far fields together too (far_field_radiosity() at each, bit for bit).
    std::array<Rgb, 4> radiosity;
    if (!b.uniform) far_field_radiosities(b, {r.gauss.data(), count}, r.normal, shooter_normal, {radiosity.data(), count});
    for (size_t k = 0; k < count; ++k)
      out.mean += f[k] == 0 || b.uniform ? Rgb(f[k] * b.unshot_w_m2) : Rgb(f[k] * radiosity[k]);
    out.mean /= r.gauss_count;
    now.gauss_known = true;
    std::copy(f.begin(), f.begin() + static_cast<std::ptrdiff_t>(count), now.gauss.begin());
  }
  keep();
  return out;
}

}  // namespace radrecon
