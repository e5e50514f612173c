#pragma once
// What a receiving element gathers from a shooting patch (solver/shooter_tree.h) in one shot of
// progressive refinement: the patch's blocks that may shoot as one (solver/far_field.h) by an
// error budget, their form factors at the element's centre and Gauss points, shadows included.

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/tolerances.h"
#include "solver/shooter_tree.h"
#include "solver/shadow_subtraction.h"
#include "solver/visibility.h"

namespace radrecon {

/// A receiving element as gather() sees it: its centre, and the points of a Gauss rule over it
/// for the blocks it is near to.
struct Receiver {
  Vec3 center, normal;
  double size_m = 0;  ///< the longer diagonal, metres
  std::array<Vec3, 4> gauss;
  int gauss_count = 0;
};

/// The Gauss rule's points over a cell, in (u, v), equal weights: exact for cubics on a box
/// (2 x 2 points), for quadratics on a triangle (3 points at barycentric (2/3, 1/6, 1/6) and its
/// permutations); the surface's Jacobian taken as constant over the cell (exact for
/// parallelograms and triangles).
struct GaussPoints {
  std::array<Vec2, 4> uv;
  int count = 0;
};
GaussPoints gauss_points(const ParamCell& cell);

/// The element as a receiver: its centre and its Gauss points on the surface.
Receiver make_receiver(const Surface& surface, const MeshElement& e, const Vec3& normal);
/// Every element of the mesh as a receiver, side by side: [side][element].
std::vector<std::vector<Receiver>> make_receivers(const Scene& scene, const Mesh& mesh);

/// An upper bound of the unoccluded form factor from a differential area at p (unit normal n)
/// to the block: A cos_x cos_y / (pi r^2) with r no less than p's distance d to the block's
/// bounding sphere, cos_y = h / r (h: p's height over the shooter's plane) and cos_x no more
/// than the largest height of a corner over p's plane divided by d. Infinite when p is inside
/// the bounding sphere; 0 when p cannot see the block's front.
double form_factor_bound(const Block& b, const Vec3& p, const Vec3& n, const Vec3& shooter_normal);

/// An upper bound of the form factor from a differential area at p, of any orientation, to the
/// block, wherever p lies (form_factor_bound() is infinite within the block's bounding sphere):
/// min(1, A / (pi h^2)), h p's height over the shooter's plane, as the kernel
/// cos_x cos_y / (pi r^2) = cos_x h / (pi r^3) is at most 1 / (pi h^2) there; 0 when p is not in
/// front of the plane.
double form_factor_ceiling(const Block& b, const Vec3& p, const Vec3& shooter_normal);

/// Whether the receiving element gathers from the block at its centre alone (the midpoint rule):
/// its size is small against its distance to the block (tol::kMidpointReceiverRatio); else its
/// mean is gathered at its Gauss points. See gather().
bool gathers_at_centre(const Block& b, const Receiver& r);

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

/// The occluders' shadow volumes (visibility.h) as a receiving element's centre (point 0) and
/// Gauss points (1 to gauss_count) see them: each point's made on first use and kept for every
/// polygon it looks at (the blocks of a shooting patch, the whole patch). Given the shooting
/// patch's outline, a point that sees many shadows on it (tol::kKeptFragmentsShadows) keeps the
/// patch's visible fragments too (VisibleFragments), for each block it looks at. The volumes and
/// fragments live in buffers of the calling thread: one at a time per thread. Receiver,
/// occluders and outline must outlive it.
class ReceiverShadows {
 public:
  ReceiverShadows(const Receiver& r, const std::vector<const Occluder*>& occluders) : r_(r), occluders_(occluders) {}
  /// The occluders found on first need: find() fills `occluders` before the first volume is
  /// made (a gather that needs no shadow, such as a late shot's patch shooting whole with its
  /// form factor known, then never searches for them). `find` is held by reference, as
  /// ThreadJob holds its callable: it must outlive this. `patch`: the shooting patch's outline,
  /// of which every polygon given to visible_form_factor() is a part; null: none.
  template <typename Find>
  ReceiverShadows(const Receiver& r, const std::vector<const Occluder*>& occluders, const Find& find,
                  const ConvexPolygon* patch = nullptr)
      : r_(r), occluders_(occluders), find_(&find), call_find_([](const void* f) { (*static_cast<const Find*>(f))(); }),
        patch_(patch) {}
  std::span<const ShadowVolume> at(int point) const;
  /// visible_form_factor_past() of `polygon` (unit normal `shooter_normal`) at the point with
  /// at(point)'s volumes, and whether the point sees it in part: through the patch's kept
  /// fragments when the point sees many shadows on the patch (the same values to round-off),
  /// else as visible_form_factor_past() gives it, bit for bit.
  /// `alone`: unless the point has found the patch's fragments already, by
  /// visible_form_factor_past() without finding them (a block new to the element in a later shot:
  /// gather() with BlockViews).
  double visible_form_factor(int point, const ConvexPolygon& polygon, const Vec3& shooter_normal,
                             bool* partly_seen = nullptr, bool alone = false) const;
  /// Whether visible_form_factor() at the point, with `alone`, goes through the patch's kept
  /// fragments: the patch given, and tol::kKeptFragmentsShadows or more shadows on it from there
  /// (found on the first call, for the polygons of this shooter; with `alone`, only if found
  /// already). gather() batches the other points.
  bool uses_fragments(int point, const Vec3& shooter_normal, bool alone = false) const {
    return alone ? found_fragments(point) : keeps_fragments(point, shooter_normal);
  }
  /// Whether some point has been found to keep the patch's fragments (uses_fragments()): it sees
  /// many shadows there. Asks nothing new.
  bool kept_fragments() const {
    return std::find(fragments_state_.begin(), fragments_state_.end(), Fragments::kept) != fragments_state_.end();
  }

 private:
  /// Whether the point keeps the patch's fragments, found on the first call.
  bool keeps_fragments(int point, const Vec3& shooter_normal) const;
  /// Whether the point has found the patch's fragments already; asks nothing new.
  bool found_fragments(int point) const { return fragments_state_[static_cast<size_t>(point)] == Fragments::kept; }
  const Receiver& r_;
  const std::vector<const Occluder*>& occluders_;
  const void* find_ = nullptr;  ///< null: the occluders are given
  void (*call_find_)(const void*) = nullptr;
  const ConvexPolygon* patch_ = nullptr;
  mutable bool found_ = false;
  mutable std::array<bool, 5> made_{};
  enum class Fragments : std::uint8_t { unknown, kept, not_kept };
  mutable std::array<Fragments, 5> fragments_state_{};
  static thread_local std::array<std::vector<ShadowVolume>, 5> volumes_;
  static thread_local std::array<VisibleFragments, 5> fragments_;
};

/// A polygon's visible form factor at a receiving element's centre, and whether the centre sees
/// it in part (visible_form_factor_past()'s value and `partly_seen`); and, if `gauss` is given,
/// its visible form factors at the element's Gauss points: NaN in gauss[0] until gather()
/// computes them (it then stores them there), else used as they are.
struct SeenFromCentre {
  double form_factor;
  bool partly;
  double* gauss = nullptr;  ///< Receiver::gauss_count values
};

/// What a receiving element saw of one block of a patch's shooter tree, other than its root
/// (SeenFromCentre holds that), when it last gathered from the patch: the block's visible form
/// factor at its centre and whether the centre sees it in part, and its visible form factors at
/// the Gauss points, each if computed then. Geometry alone, so a later shot of the same patch
/// takes them as they are, bit for bit, without the shadows behind them.
struct BlockView {
  std::uint32_t block = 0;  ///< its index in the tree (ShooterTree::block())
  bool partly = false, centre_known = false, gauss_known = false;
  double centre = 0;
  std::array<double, 4> gauss{};
};

/// The block views of a receiving element: those of its last gather from the patch (`last`,
/// sorted by block), to take values from, and those of this gather (`now`, appended in the order
/// visited), to keep for the next. A block without a view in `last` gets its form factors alone
/// (ReceiverShadows::visible_form_factor()): the same to round-off, its seen-in-part flag by the
/// per-block test.
struct BlockViews {
  std::span<const BlockView> last;
  std::vector<BlockView>* now = nullptr;
  /// The view of the block in `last`, or null.
  const BlockView* find(std::uint32_t block) const;
};

/// Irradiance on the receiving element from the shooter's unshot radiosity: the block as a whole
/// when it is uniform or a single element, or when it may shoot as one; else the sum over its
/// children. With `budget_w_m2` <= 0 a block may shoot as one beyond tol::kFarFieldDiagonals of
/// its diagonal from the element's centre. With a budget, while its error estimate at the
/// centre is at most the budget's share in proportion to its area (the shares of the blocks that
/// shoot as one add up to the budget):
/// - its form factor times the spread of its unshot radiosity (channels summed), a strict bound:
///   the far field and the children's sum both lie in [lowest, highest] times the visible form
///   factor. The form factor is form_factor_bound(), or the visible form factor itself when the
///   element gathers at its centre alone and sees all of the block; or form_factor_ceiling()
///   (the largest at the centre and, off the midpoint rule, the Gauss points) against
///   tol::kNearFieldCeilingShare of the share; or, when smaller,
/// - form_factor_bound() or the visible form factor (not the ceiling) times the spread times
///   far_field_error(): the far field errs to third
///   order for any radiosity over the block; used only if the centre sees the whole block (a
///   block cut by the receiver's horizon or a shadow is seen through part of it only) and the
///   estimate is finite.
/// The element's radiosity is its value at its centre (what reconstructions sample); its power
/// is its mean, the midpoint rule's (the centre's value, relative error of order
/// (size / distance)^2) unless the element is large against its distance to the block
/// (tol::kMidpointReceiverRatio): then by the Gauss rule, so that no power is gained or lost by
/// point collocation next to the shooter.
///
/// `seen`, if given, holds what visible_form_factor_past() gives for the block's outline at the
/// element's centre with shadows.at(0): gather() then does not compute it again. If its `gauss`
/// is given too, gather() takes the block's form factors at the Gauss points from there, or
/// computes them and stores them there (NaN in gauss[0]) when it first needs them.
///
/// `views`, if given, holds what the element saw of the other blocks at its last gather from the
/// patch: gather() takes their form factors from there rather than computing them, and appends
/// what it saw of each block it visits to views->now.
///
/// `strict_share`: the fraction of a block's share within which the strict bound with
/// form_factor_bound() or form_factor_ceiling() lets it shoot as one before its visible form
/// factor is looked at, seen in part or not (tol::kPartlyHiddenStrictShare where occluders may
/// hide part of the patch from the element).
Gathered gather(const ShooterTree& tree, const Block& b, const Receiver& r, const Vec3& shooter_normal,
                const ReceiverShadows& shadows, double budget_w_m2, const SeenFromCentre* seen = nullptr,
                const BlockViews* views = nullptr, double strict_share = 1.0);

}  // namespace radrecon
