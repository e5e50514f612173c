#pragma once
// The sides of a scene's surfaces: a one-sided surface has one side (its front), a two-sided
// one two ("NAME/front", "NAME/back"). Solvers, solutions, reconstructions and renderers are
// all per side; this is the one place that names, numbers and describes them.

#include <optional>
#include <string>

#include "scene/scene.h"

namespace radrecon {

/// One side of a scene surface.
struct SideRef {
  size_t surface = 0;
  bool back_side = false;

  /// The side's slot in per-side tables of size side_slots(scene): 2 * surface + back_side
  /// (the back slot of a one-sided surface stays unused).
  size_t slot() const { return 2 * surface + (back_side ? 1 : 0); }
  static SideRef from_slot(size_t slot) { return {slot / 2, slot % 2 == 1}; }
};

/// Size of a per-side table indexed by SideRef::slot().
inline size_t side_slots(const Scene& scene) { return 2 * scene.surfaces.size(); }

/// The name of one side: the surface's name, or "NAME/front" and "NAME/back" for the sides of a
/// two-sided surface.
std::string side_name(const Surface& surface, bool back_side);

/// The side named `name` (side_name()), if the scene has it.
std::optional<SideRef> find_side(const Scene& scene, const std::string& name);

/// The names of every side of the scene, comma separated (for messages).
std::string side_names(const Scene& scene);

/// Unit normal of one side: the surface's, reversed on a back side.
Vec3 side_normal(const Surface& surface, bool back_side);

/// Emitted exitance of one side, W/m^2: only fronts emit.
Rgb side_emission(const Surface& surface, bool back_side);

}  // namespace radrecon
