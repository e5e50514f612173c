#pragma once
// The parts of a surface that others lying flat on it hide (scene/contacts.h lies_on(): a lamp
// placed on a ceiling). They neither receive nor shoot light: the solvers scale what an element
// absorbs, reflects and emits by the fraction of it left exposed, so that a closed room keeps its
// energy (docs/method.md, "Covered parts").

#include <cstddef>
#include <span>
#include <vector>

#include "scene/scene.h"
#include "solver/polygon.h"

namespace radrecon {

/// By scene surface: the indices of the surfaces covering it (scene/contacts.h covers(): lying
/// flat on it, either side of it, not the other face of a sheet) and overlapping its bounding
/// box, in surface order. Pairs are found by a sweep over the boxes, not all n^2 of them (a model
/// of 11,000 triangles: 1.2 s of lies_on() tests before).
std::vector<std::vector<size_t>> covering_surfaces(const Scene& scene);

/// By scene surface: the polygons of covering_surfaces().
std::vector<std::vector<ConvexPolygon>> covers_by_surface(const Scene& scene);

/// The fraction of the convex polygon of corners `part` (an element, a quadtree node), in the
/// plane of a surface with unit normal `normal`, that `covers` (convex, in the same plane) leave
/// exposed: 1 - the sum of its overlaps with each over its area, in [0, 1] (covers that overlap
/// each other count twice).
double exposed_fraction(std::span<const Vec3> part, const Vec3& normal, std::span<const ConvexPolygon> covers);

}  // namespace radrecon
