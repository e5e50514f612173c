#pragma once
// What progressive refinement (solver/progressive.cpp) keeps of a shooting patch's geometry from
// its first shot for its later ones: the whole patch's visible form factors at its receiving
// elements, and what the elements behind many shadows saw of its blocks (BlockView).

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "solver/gather.h"

namespace radrecon {

/// A patch's visible form factor at each of its receiving elements' centres, shadows included,
/// whether the centre sees it in part, and its visible form factors at the Gauss points of the
/// elements that gather from it by their Gauss points: what each shot of the patch needs for the
/// elements' budgets, and gather() for the patch shooting whole. Geometry alone, so the values of
/// its first shot serve its later ones, bit for bit; later shots, whose budgets let the patch
/// shoot whole, then need neither the occluders nor their shadows.
struct PatchViews {
  std::vector<double> form_factor;  ///< by receiving element, in the shot's order; NaN: not yet
  std::vector<std::uint8_t> partly;
  /// By receiving element: where its Gauss points' form factors start in `gauss`, or kAtCentre
  /// (it gathers from the whole patch at its centre alone: gathers_at_centre()).
  std::vector<std::uint32_t> gauss_at;
  std::vector<double> gauss;  ///< 4 a slot (Receiver::gauss); NaN: not yet
  /// By receiving element: what it saw of the tree's other blocks at its last gather (BlockView),
  /// sorted by block, for an element behind many shadows; kept if `keep_blocks` (a small tree,
  /// and the most it can hold within kMostBlockViewBytes).
  std::vector<std::vector<BlockView>> blocks;
  bool keep_blocks = false;
  static constexpr std::uint32_t kAtCentre = std::numeric_limits<std::uint32_t>::max();
  /// The bytes of the views of `receivers` elements, `slots` of them off the midpoint rule.
  static size_t bytes(size_t receivers, size_t slots) {
    return receivers * (sizeof(double) + sizeof(std::uint8_t) + sizeof(std::uint32_t)) + slots * 4 * sizeof(double);
  }
};
/// The most bytes of views kept over all patches; the patches that shoot after they are spent
/// compute theirs every shot. The Cornell box at grid:128 keeps 51 MB, the paper's grid:400 20 MB
/// (4 patches along the longest edge).
inline constexpr size_t kMostPatchViewBytes = size_t{128} << 20;
/// The largest shooter tree, in blocks, whose other blocks' views (BlockView) a patch keeps for
/// its later shots, for the receiving elements behind many shadows (ReceiverShadows::
/// kept_fragments()): the Wuson scene's floor patches have 21 blocks; the Cornell box's patches
/// at grid:128 1365, of which a receiver near them sees hundreds.
inline constexpr size_t kMostViewedBlocks = 1024;
/// The most bytes of those block views over all patches, each patch's counted as the most it can
/// hold (every receiving element, every block) before its first shot; a patch that would pass
/// it keeps none. The Wuson scene's 16 floor patches (4 along the longest edge, 21 blocks each)
/// reserve 11 MB each.
inline constexpr size_t kMostBlockViewBytes = size_t{256} << 20;

}  // namespace radrecon
