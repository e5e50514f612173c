#include "solver/progressive.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <span>

#include "core/check.h"
#include "core/parallel.h"
#include "core/tolerances.h"
#include "solver/bvh.h"
#include "solver/visibility.h"

namespace radrecon {

namespace {

/// A node of the shooting hierarchy over one patch: the elements of the cells [i0,i1) x [j0,j1),
/// or a single element of a cell that holds two (a triangle's lower and upper halves).
struct Block {
  /// The block's outline, counter-clockwise seen from the front of the side: a box of cells, cut
  /// by a triangle's hypotenuse (5 corners at most).
  std::array<Vec3, 5> corners{Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};
  int corner_count = 0;
  Vec3 center;
  double diagonal_m = 0;          ///< the largest distance between two corners
  Rgb unshot_w_m2 = Rgb::Zero();  ///< area-weighted mean unshot radiosity of the block
  Rgb lowest_w_m2 = Rgb::Zero(), highest_w_m2 = Rgb::Zero();  ///< its elements' extremes
  /// The first moment of the unshot radiosity about the block's centroid, per channel (column),
  /// divided by the block's area: sum_k A_k (c_k - c) (B_k - B_mean) / A, W/m^2 times metres.
  Eigen::Matrix3d dipole = Eigen::Matrix3d::Zero();
  bool uniform = true;            ///< every element has the same unshot radiosity
  int first_child = -1;           ///< children are consecutive; -1 for a single element
  int child_count = 0;
};

/// The largest distance between two of the block's corners, metres.
double widest(const Block& b) {
  double d = 0;
  for (int a = 0; a < b.corner_count; ++a)
    for (int c = a + 1; c < b.corner_count; ++c) d = std::max(d, (b.corners[a] - b.corners[c]).norm());
  return d;
}

class ShooterTree {
 public:
  ShooterTree(const Surface& surface, const MeshSurface& side, const std::vector<Rgb>& unshot,
              int i0, int j0, int i1, int j1)
      : surface_(surface), side_(side), unshot_(unshot) {
    blocks_.reserve(static_cast<size_t>(3 * (i1 - i0) * (j1 - j0)));
    blocks_.emplace_back();
    build(0, i0, j0, i1, j1);
  }

  const Block& root() const { return blocks_[0]; }
  const Block& block(int k) const { return blocks_[static_cast<size_t>(k)]; }

 private:
  /// The outline of the (u,v) box [u0,u1] x [v0,v1] inside the side's parameter domain.
  void set_outline(Block& b, double u0, double v0, double u1, double v1) const {
    std::array<Vec2, 5> uv;
    int n = 0;
    if (!side_.domain.is_triangle() || u1 + v1 <= 1) {
      uv = {Vec2(u0, v0), Vec2(u1, v0), Vec2(u1, v1), Vec2(u0, v1), Vec2()};
      n = 4;
    } else {
      // The box clipped by u + v <= 1 (one Sutherland-Hodgman pass); the box's lower-left corner
      // is inside, as the block holds elements.
      const std::array<Vec2, 4> box = {Vec2(u0, v0), Vec2(u1, v0), Vec2(u1, v1), Vec2(u0, v1)};
      for (int k = 0; k < 4; ++k) {
        const Vec2 &a = box[k], &c = box[(k + 1) % 4];
        const double da = 1 - a.sum(), dc = 1 - c.sum();
        if (da >= 0) uv[n++] = a;
        if ((da > 0 && dc < 0) || (da < 0 && dc > 0)) uv[n++] = a + da / (da - dc) * (c - a);
      }
    }
    set_corners(b, uv.data(), n);
  }

  void set_corners(Block& b, const Vec2* uv, int n) const {
    b.corner_count = n;
    for (int k = 0; k < n; ++k) {
      const Vec2& q = uv[side_.back_side && k > 0 ? n - k : k];
      b.corners[k] = surface_.point(q.x(), q.y());
    }
    b.diagonal_m = widest(b);
  }

  void set_radiosity(Block& b, std::span<const size_t> elements) const {
    Rgb weighted = Rgb::Zero(), lo = unshot_[elements[0]], hi = lo;
    double area = 0;
    Vec3 center = Vec3::Zero();
    for (const size_t k : elements) {
      const double a = side_.elements[k].area_m2;
      weighted += a * unshot_[k];
      center += a * side_.elements[k].center;
      area += a;
      lo = lo.min(unshot_[k]);
      hi = hi.max(unshot_[k]);
    }
    b.unshot_w_m2 = weighted / area;
    b.center = center / area;
    b.lowest_w_m2 = lo;
    b.highest_w_m2 = hi;
    b.dipole.setZero();
    for (const size_t k : elements)
      b.dipole += side_.elements[k].area_m2 * (side_.elements[k].center - b.center) *
                  (unshot_[k] - b.unshot_w_m2).matrix().transpose();
    b.dipole /= area;
    b.uniform = ((hi - lo) <= tol::kUniformRelative * hi.abs().max(std::numeric_limits<double>::min())).all();
  }

  void build(size_t index, int i0, int j0, int i1, int j1) {
    const int nu = side_.nu, nv = side_.nv;
    std::vector<size_t> elements;
    for (int j = j0; j < j1; ++j)
      for (int i = i0; i < i1; ++i) {
        const auto [first, last] = side_.cell_elements(i, j);
        for (size_t k = first; k < last; ++k) elements.push_back(k);
      }
    Block& b = blocks_[index];
    set_outline(b, double(i0) / nu, double(j0) / nv, double(i1) / nu, double(j1) / nv);
    set_radiosity(b, elements);
    if (i1 - i0 == 1 && j1 - j0 == 1) {
      if (elements.size() > 1) add_element_children(index, elements);
      return;
    }
    const int mi = (i1 - i0) > 1 ? (i0 + i1) / 2 : i1;
    const int mj = (j1 - j0) > 1 ? (j0 + j1) / 2 : j1;
    std::array<std::array<int, 4>, 4> quads = {{{i0, j0, mi, mj}, {mi, j0, i1, mj}, {i0, mj, mi, j1}, {mi, mj, i1, j1}}};
    // A part of the box beyond a triangle's hypotenuse (no elements) is no child.
    const auto holds_elements = [&](const std::array<int, 4>& q) {
      return q[2] > q[0] && q[3] > q[1] && (!side_.domain.is_triangle() || q[0] + q[1] <= nu - 1);
    };
    int first = static_cast<int>(blocks_.size());
    int count = 0;
    for (const auto& q : quads) count += holds_elements(q) ? 1 : 0;
    blocks_[index].first_child = first;
    blocks_[index].child_count = count;
    blocks_.resize(blocks_.size() + static_cast<size_t>(count));
    int c = 0;
    for (const auto& q : quads)
      if (holds_elements(q)) build(static_cast<size_t>(first + c++), q[0], q[1], q[2], q[3]);
  }

  /// A cell of two elements: one child block per element.
  void add_element_children(size_t index, const std::vector<size_t>& elements) {
    const int first = static_cast<int>(blocks_.size());
    blocks_[index].first_child = first;
    blocks_[index].child_count = static_cast<int>(elements.size());
    for (const size_t k : elements) {
      Block child;
      const MeshElement& e = side_.elements[k];
      child.corner_count = e.corner_count();
      std::copy_n(e.corners.begin(), child.corner_count, child.corners.begin());
      child.diagonal_m = widest(child);
      set_radiosity(child, std::span<const size_t>(&k, 1));
      blocks_.push_back(child);
    }
  }

  const Surface& surface_;
  const MeshSurface& side_;
  const std::vector<Rgb>& unshot_;
  std::vector<Block> blocks_;
};

/// The radiosity a far block shoots with to the receiver point p (unit normal n): its mean plus the
/// first-order correction for the variation of both the radiosity and the form factor's kernel
/// across the block. With F_k = (A_k / A) F (1 + g . (c_k - c)), g the gradient over the
/// source point y of ln k(x, y), k = cos_y cos_x / (pi r^2) the point-to-point kernel, the sum
/// over the block's elements sum_k F_k B_k = F (B_mean + g . dipole): the mean alone errs to
/// first order in (block size / distance) wherever the radiosity varies (a wall lit at its top
/// and dark at its foot), and that error does not cancel over the receivers: it gains or loses
/// power. Clamped to the block's range of unshot radiosity.
Rgb far_field_radiosity(const Block& b, const Vec3& p, const Vec3& n, const Vec3& shooter_normal) {
  const Vec3 d = p - b.center;  // from the source point y = c to the receiver x = p
  const double r2 = d.squaredNorm(), cos_y = shooter_normal.dot(d), cos_x = -n.dot(d);
  if (!(cos_y > tol::kKernelCosine * std::sqrt(r2) && cos_x > tol::kKernelCosine * std::sqrt(r2))) return b.unshot_w_m2;
  const Vec3 g = -shooter_normal / cos_y - n / cos_x + 4.0 * d / r2;
  const Rgb corrected = b.unshot_w_m2 + (g.transpose() * b.dipole).transpose().array();
  return corrected.max(b.lowest_w_m2).min(b.highest_w_m2);
}

/// A receiving element as gather() sees it: its centre, and the points of a Gauss rule over it
/// for the blocks it is near to.
struct Receiver {
  Vec3 center, normal;
  double size_m = 0;  ///< the longer diagonal, metres
  std::array<Vec3, 4> gauss;
  int gauss_count = 0;
};

/// The Gauss rule's points over the element, equal weights: exact for cubics in (u, v) on a box
/// (2 x 2 points), for quadratics on a triangle (3 points at barycentric (2/3, 1/6, 1/6) and its
/// permutations); the surface's Jacobian taken as constant over the element (exact for
/// parallelograms and triangles).
Receiver make_receiver(const Surface& surface, const MeshElement& e, const Vec3& normal) {
  Receiver r;
  r.center = e.center;
  r.normal = normal;
  r.size_m = std::max((e.corners[2] - e.corners[0]).norm(), (e.corners[3] - e.corners[1]).norm());
  if (e.is_triangle()) {
    const auto v = e.vertices();
    for (int k = 0; k < 3; ++k) {
      const Vec2 uv = (4.0 * v[k] + v[(k + 1) % 3] + v[(k + 2) % 3]) / 6.0;
      r.gauss[r.gauss_count++] = surface.point(uv.x(), uv.y());
    }
    return r;
  }
  const double g = 0.5 / std::sqrt(3.0);  // Gauss-Legendre nodes at the centre +- half-width / sqrt(3)
  const double um = 0.5 * (e.u0 + e.u1), vm = 0.5 * (e.v0 + e.v1);
  const double du = (e.u1 - e.u0) * g, dv = (e.v1 - e.v0) * g;
  for (const double sv : {-1.0, 1.0})
    for (const double su : {-1.0, 1.0}) r.gauss[r.gauss_count++] = surface.point(um + su * du, vm + sv * dv);
  return r;
}

/// What a receiving element gathers from one shot, W/m^2 per channel.
struct Gathered {
  Rgb at_center = Rgb::Zero();  ///< the irradiance at its centre: its radiosity's
  Rgb mean = Rgb::Zero();       ///< its mean irradiance: the power it absorbs and reflects
  Gathered& operator+=(const Gathered& o) {
    at_center += o.at_center;
    mean += o.mean;
    return *this;
  }
};

/// Irradiance on the receiving element from the shooter's unshot radiosity: the block as a whole
/// when far or uniform, else the sum over its children. The element's radiosity is its value at
/// its centre (what reconstructions sample); its power is its mean, the midpoint rule's (the
/// centre's value, relative error of order (size / distance)^2) unless the element is large
/// against its distance to the block (tol::kMidpointReceiverRatio): then by the Gauss rule, so
/// that no power is gained or lost by point collocation next to the shooter.
Gathered gather(const ShooterTree& tree, const Block& b, const Receiver& r, const Vec3& shooter_normal,
                const std::vector<const Occluder*>& occluders) {
  Gathered out;
  const double far_m = tol::kFarFieldDiagonals * b.diagonal_m;  // shoots as one beyond this
  if (b.first_child < 0 || b.uniform || (r.center - b.center).squaredNorm() > far_m * far_m) {
    if ((b.highest_w_m2 == 0).all()) return out;
    ConvexPolygon poly;
    for (int k = 0; k < b.corner_count; ++k) poly.push(b.corners[k]);
    const auto at = [&](const Vec3& p) -> Rgb {
      const double f = visible_form_factor(p, r.normal, poly, shooter_normal, occluders);
      if (f == 0 || b.uniform) return f * b.unshot_w_m2;
      return f * far_field_radiosity(b, p, r.normal, shooter_normal);
    };
    out.at_center = at(r.center);
    const double gap_m = (r.center - b.center).norm() - 0.5 * b.diagonal_m;
    if (r.size_m <= tol::kMidpointReceiverRatio * gap_m) {
      out.mean = out.at_center;
    } else {
      for (int k = 0; k < r.gauss_count; ++k) out.mean += at(r.gauss[k]);
      out.mean /= r.gauss_count;
    }
    return out;
  }
  for (int c = 0; c < b.child_count; ++c) out += gather(tree, tree.block(b.first_child + c), r, shooter_normal, occluders);
  return out;
}

struct Patch {
  size_t surface;
  int i0, j0, i1, j1;
  Rgb unshot_w = Rgb::Zero();  ///< unshot power per channel, W
};

/// Per element of a side, W/m^2: radiosity at the element's centre; unshot radiosity and
/// irradiance as the element's means (Gathered), which carry the power.
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
    // Every patch of the side's patch grid, empty ones beyond a triangle's hypotenuse included
    // (they never shoot: no power), so that patch (pi, pj) is at first_patch + pj * patches_u + pi.
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
        size_t p = first_patch[s] + static_cast<size_t>(j / side.patch_size) * side.patches_u() + i / side.patch_size;
        const auto [first, last] = side.cell_elements(i, j);
        for (size_t e = first; e < last; ++e) patches[p].unshot_w += side.elements[e].area_m2 * state[s].unshot[e];
      }
  };
  for (size_t s = 0; s < mesh.surfaces.size(); ++s) update_patch_power(s);

  Rgb escaped = Rgb::Zero();
  const double emitted_sum = emitted.sum();
  RR_CHECK(emitted_sum > 0, "the scene emits no light");
  size_t shots = 0;
  auto last_report = start;
  std::vector<Gathered> gain;
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
      for (int i = shooter.i0; i < shooter.i1; ++i) {
        const auto [first, last] = shooter_side.cell_elements(i, j);
        for (size_t e = first; e < last; ++e) state[shooter.surface].unshot[e] = Rgb::Zero();
      }
    update_patch_power(shooter.surface);

    const Block& root = tree.root();
    const Vec3 shooter_normal = shooter_side.normal;
    Rgb delivered = Rgb::Zero();
    for (size_t r = 0; r < mesh.surfaces.size(); ++r) {
      const MeshSurface& receiver = mesh.surfaces[r];
      if (receiver.scene_surface == shooter_side.scene_surface) continue;
      const Surface& receiver_surface = scene.surfaces[receiver.scene_surface];
      if (!quads_face(receiver_surface.corners, receiver.normal, shooter_surface.corners, shooter_normal)) continue;
      // Occluders in the shaft between the two surfaces; then, per receiver element, in the shaft
      // between the element and the shooting patch (solver/bvh.h: the same shadows, fewer tests).
      const std::span<const Vec3> shooter_outline(root.corners.data(), static_cast<size_t>(root.corner_count));
      const std::vector<const Occluder*> blockers =
          bvh.between(shooter_outline, receiver_surface.polygon(), receiver.scene_surface, shooter_side.scene_surface);

      gain.assign(receiver.elements.size(), Gathered{});
      parallel_for(0, static_cast<std::int64_t>(receiver.elements.size()), [&](std::int64_t e) {
        const Receiver element = make_receiver(receiver_surface, receiver.elements[static_cast<size_t>(e)], receiver.normal);
        // gather() looks from the centre and the Gauss points: the shaft from the centre, widened
        // by their farthest distance from it, holds every segment it follows.
        thread_local std::vector<const Occluder*> near;
        near.clear();
        if (!blockers.empty()) {
          double reach_m = 0;
          for (int k = 0; k < element.gauss_count; ++k) reach_m = std::max(reach_m, (element.gauss[k] - element.center).norm());
          bvh.collect(Shaft({&element.center, 1}, shooter_outline, reach_m), receiver.scene_surface,
                      shooter_side.scene_surface, near);
        }
        gain[static_cast<size_t>(e)] = gather(tree, tree.root(), element, shooter_normal, near);
      });
      SideState& st = state[r];
      for (size_t e = 0; e < receiver.elements.size(); ++e) {
        const Gathered& h = gain[e];
        st.irradiance[e] += h.mean;
        st.radiosity[e] += receiver.reflectance * h.at_center;
        st.unshot[e] += receiver.reflectance * h.mean;
        delivered += receiver.elements[e].area_m2 * h.mean;
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
  stats.residual = stats.unshot_w.sum() / emitted_sum;
  stats.converged = converged;
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!options.progress_label.empty())
    std::fprintf(stderr, "%s: %zu shots, unshot %.2e of emitted, %.2f s\n", options.progress_label.c_str(),
                 shots, stats.residual, stats.seconds);
  return sol;
}

}  // namespace radrecon
