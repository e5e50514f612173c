#pragma once
// What hides a surface's parts: another surface lying flat on it (a lamp on a ceiling, a box's
// bottom on a floor), unless the two are the faces of one sheet of no thickness. The one rule
// for the excluded regions (scene/contacts.h) and the solvers' covered parts (solver/covered.h).

#include <algorithm>
#include <cstddef>
#include <optional>
#include <span>

#include "core/tolerances.h"
#include "core/vec.h"
#include "scene/scene.h"

namespace radrecon {

/// Whether surface `other` lies flat on surface `base` (either side of it): its four corners lie
/// within tol::kContactRelative of its size of base's plane, it faces either way, and its area is
/// below (1 - tol::kLyingSmallerRelative) times base's (of two coplanar overlapping quads the
/// smaller lies on the larger: a plate on a floor covers the floor, the floor does not cover the
/// plate; two equal ones cover neither). Whether they overlap is not asked.
bool lies_on(const Surface& other, const Surface& base);

/// Whether one-sided surface `surface` is one face of a sheet of no thickness modelled as
/// one-sided faces back to back: the one-sided surfaces among `candidates` lying in its plane
/// facing the other way (of any size) cover all of it (each of tol::kSheetProbes x
/// tol::kSheetProbes points over it, cell centres, lies inside or on one of their outlines; a gap
/// narrower than a probe cell may pass unseen). Their faces then cover none of it (covers()):
/// each of a plate's bottom triangles lay on its top quad as a box's bottom lies on a floor, and
/// the lit top took no light (an outside-in trial; two equal quads were already left alone by
/// lies_on()'s "smaller"). `candidates`: surfaces that may touch it (others are ignored).
bool sheet_face(const Scene& scene, size_t surface, std::span<const size_t> candidates);

/// Whether surface `other` covers surface `base`: it lies on it (lies_on()), unless `base` is one
/// face of a sheet (`base_is_sheet_face`: sheet_face()) and `other` is a piece of the sheet's
/// other face: one-sided, back to back with it, and lying on no part of another surface facing
/// its way among `candidates` (a box's bottom standing on the plate lies on the plate's bottom
/// and still covers its top). The one rule of what hides a surface's parts: excluded_regions()
/// and the solvers' covered parts (solver/covered.h).
bool covers(const Scene& scene, size_t other, size_t base, bool base_is_sheet_face, std::span<const size_t> candidates);

/// How near a surface's corners come to another's plane to touch it, metres:
/// tol::kContactRelative of its longer edge.
inline double contact_tolerance_m(const Surface& s) { return tol::kContactRelative * std::max(s.length_u_m(), s.length_v_m()); }

/// Whether surface `other` lies in `base`'s plane: its corners within tol::kContactRelative of
/// its size of it.
bool in_plane_of(const Surface& other, const Surface& base);

/// The outline of surface `t` clipped to surface `s`'s quad, in s's (s, t) metres, if they
/// overlap with some width (more than tol::kContactJoinRelative of s's longer edge): none when
/// they meet only along an edge or not at all.
std::optional<Polyline> overlap_region(const Surface& t, const Surface& s);

}  // namespace radrecon
