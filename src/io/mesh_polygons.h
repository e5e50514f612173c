#pragma once
// Polygon work of mesh import (io/mesh_import.h): cutting a modeller's n-gon into triangles, and
// merging coplanar triangle pairs back into the convex quads they came from.

#include <array>
#include <span>
#include <vector>

#include "core/vec.h"
#include "scene/scene.h"

namespace radrecon {

/// Drops each corner that repeats the one before it, cyclically (within
/// tol::kRepeatedCornerRelative of the longest edge, as regularise_surfaces() reads a hand-written
/// quad): `f 1 2 3 1` is a triangle, and a pentagon closed on its first corner a quad.
void drop_repeated_corners(std::vector<Vec3>& corners);

/// The largest distance of a polygon's corner from the plane of its Newell normal through the
/// corners' mean, in units of its longest edge (0 for a planar polygon, and for one of no area).
double polygon_off_plane(std::span<const Vec3> corners);

/// Triangles (index triples into `corners`, counter-clockwise like the polygon) covering a simple
/// planar polygon of 3 or more corners, by ear clipping in the plane of its Newell normal; convex
/// or not. Empty if the polygon has no area or no ear can be cut (self-intersecting).
std::vector<std::array<int, 3>> triangulate_polygon(std::span<const Vec3> corners);

/// Whether the polygon's corners all lie on one line (within tol::kDegenerateAreaRelative of its
/// longest extent), or coincide: it has no area. A polygon that triangulate_polygon() cannot cut
/// and that has area crosses itself.
bool polygon_on_a_line(std::span<const Vec3> corners);

/// Merges pairs of triangles of `surfaces` into quads, in place; returns the number of pairs
/// merged. Two triangles merge when they share an edge (the same two corners, exactly, walked in
/// opposite directions), have the same reflectance, emission, two_sided and mesh setting, and
/// their union is a quad that is planar (every corner within tol::kPlanarityRelative / 2 of the
/// longest edge off its plane, as validate_scene() measures it) and convex with the margin
/// tol::kQuadMergeTurnRelative. Greedy and deterministic: triangles are taken in order, each
/// with the still-unmerged partner across its longest shared edge (the lowest index on a tie);
/// the quad takes the first triangle's name and place, and starts at the first triangle's corner
/// before the shared edge. Quads and unmerged triangles are kept as they are, in order.
size_t merge_coplanar_triangle_pairs(std::vector<Surface>& surfaces);

}  // namespace radrecon
