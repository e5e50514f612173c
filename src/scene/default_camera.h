#pragma once
// A camera for a scene that brings none (a model file: OBJ, glTF and PLY scenes have no cameras
// radrecon reads).

#include "scene/scene.h"

namespace radrecon {

/// The camera "default": looking at the centre of the scene's bounding box from the direction
/// (1, -2, 1) (front right, above, with +z up: radrecon's convention), far enough that the
/// box's bounding sphere fits the vertical field of view of 45 degrees (and so any wider
/// horizontal one). From outside: a closed room is seen from without (its walls' backs, black);
/// a scene JSON's "cameras" give a view inside. Requires a scene with some surface of finite,
/// not all coincident corners.
Camera default_camera(const Scene& scene);

}  // namespace radrecon
