#pragma once
// Where the direct light's derivatives jump: the D1 and D2 discontinuities that the edges of
// occluders cast from the vertices and edges of each light (Heckbert 1992, "Discontinuity
// meshing for radiosity"; Lischinski, Tampieri and Greenberg 1992). Radiosity is continuous
// across them (the contact lines of contacts.h are its jumps), but its slope or curvature is not:
// they bound the umbrae and penumbrae.

#include <vector>

#include "scene/contacts.h"
#include "scene/scene.h"
#include "scene/side.h"

namespace radrecon {

/// The critical lines of the direct light on `side`, in its (s, t) metres, clipped to the side:
///   - vertex-edge (VE) events: each edge of every other non-emitting surface projected from
///     each vertex of every emitter onto the side's plane;
///   - edge-vertex (EV) events: each edge of every emitter projected through each corner of every
///     other non-emitting surface onto the side's plane.
/// Only emitters in front of the side, and occluder points strictly between an emitter's point
/// and the side's plane, cast lines; an edge lying on the side casts none (it is a contact line).
/// No visibility test: a line inside another occluder's umbra is listed too (the light is
/// continuous there, so such a line is harmless to a reconstruction that uses it as structure).
/// Zero-length and duplicate segments are dropped; each runs from its lexicographically smaller
/// end.
std::vector<Segment2> shadow_lines(const Scene& scene, SideRef side);

}  // namespace radrecon
