#pragma once
// The tolerances of scattered-data reconstruction (reconstruct/: regular grids, natural
// neighbours, barriers, border samples, fitted gradients, radial basis functions), named, with
// the reason for each value. Included by core/tolerances.h, the one include for every tolerance.

namespace radrecon::tol {

/// Scattered samples count as the nodes of a regular grid when their coordinates lie within
/// this fraction of the samples' extent from the grid lines: far above the round-off of
/// coordinates printed with 10+ digits, far below any intended offset.
inline constexpr double kGridCoordinateRelative = 1e-9;
// ... or within kCoordinateRounding of the coordinates' magnitude (64 ulps), when that is more:
// a 1 cm grid at a UTM northing of 5e6 m lies 1 ulp (9.3e-10 m, 9.3e-9 of its 0.1 m extent) off
// its lines, which the relative tolerance alone refused.

/// Natural neighbours with barriers: a local triangulation's Sibson coordinates are certified
/// when the next visible sample lies beyond the bound rho + max(rho, r) by this relative margin
/// (the bound's own round-off is some 1e-15).
inline constexpr double kSibsonCertificateRelative = 1e-9;
/// A natural-neighbour query reuses the previous query's conflict zone (nn::ConflictZone) when
/// each in-circle test s(q) = a |q|^2 + b qx + c qy + d of the zone's faces has the zone's sign
/// and a magnitude above this fraction of a bound on the sum of its terms' magnitudes (from the
/// zone's extent): some 5,000 times the test's round-off (a few units of 2^-53 of that sum), so
/// that a reused zone is the zone CGAL's exact conflict search finds; closer calls take that
/// search.
inline constexpr double kConflictZoneTestRelative = 1e-12;
/// Natural neighbours over a raster, face by face (reconstruct/sibson_raster.h): a point is left
/// to the query-by-query path when it lies within this fraction of the samples' extent of their
/// hull's boundary (there the hull rules apply, and the zone's slivers have huge circles)...
inline constexpr double kSibsonRasterHullMarginRelative = 1e-9;
/// ...or when a bound on the magnitudes that its sums round (their terms, the powers and cross
/// products inside them) exceeds its weight by more than this factor: the sums then cancel,
/// next to a sample or under a sliver's circle, and the rounding could reach 1e-10 of the value.
inline constexpr double kSibsonRasterCancellation = 1e5;
/// A face's circle and its chords along a raster row are widened by this fraction of its squared
/// radius (of its radius, for the circle): far above the in-circle test's rounding (a few units
/// of 2^-53 of the squared radius), so that every point the test finds inside is visited.
inline constexpr double kSibsonRasterChordSlack = 1e-12;
/// A query's visibility tests are skipped when no barrier comes within its farthest neighbour's
/// distance enlarged by this fraction of that distance plus the coordinates' magnitude
/// (Barriers::none_within()): far above the distance's round-off (some 1e-15 of those), so that
/// a barrier the exact test would find is never skipped.
inline constexpr double kBarrierReachRelative = 1e-9;

/// Border samples (reconstruct/border_samples.h): a barrier's samples stand this fraction of the
/// domain's longer side from it (one on each side), and an added sample within this distance of
/// an interior sample, of an earlier added one or (a border sample) of a barrier is not added.
/// Far above the round-off of coordinates (1e-16 relative: 1e10 ulps away, so the side of a
/// barrier a sample is on never depends on rounding), far below any sample spacing (a million
/// samples along a side), and the values extrapolated to the barrier move by only 1e-6 of the
/// domain times the function's slope.
inline constexpr double kBorderOffsetRelative = 1e-6;
/// A border side or barrier whose length is within this fraction of a whole number of spacings
/// gets that many parts: a length of 1 at a spacing of 0.09999999999999999 (the distance of two
/// cell centres 0.1 apart) gets 10, not 11.
inline constexpr double kBorderSpacingRelative = 1e-9;
/// A border sample's plane fit counts its neighbours as collinear (and takes the nearest one's
/// value instead) when they all lie within this fraction of their extent of one line: far above
/// the round-off of coordinate differences (1e-16 of the coordinates, 1e-10 of the extent for
/// neighbours a millionth of the domain apart), while a fit across a sliver that thin would
/// extrapolate any noise in the values without bound.
inline constexpr double kFitCollinearRelative = 1e-8;

/// The multiquadric's exponent mu must stay this far (relative) from a positive integer k, where
/// (d^2 + r^2)^mu is a polynomial and the system singular: its conditioning degrades as
/// 1 / |mu - k| (on 7 samples the values at the samples erred by 5e-10 at 1e-6 from 1, 2e-8 at
/// 1e-8, 1.6e-6 at 1e-10, without the condition estimate noticing).
inline constexpr double kMultiquadricIntegerGap = 1e-6;

/// sibson-c1's gradient fit: the weighted normal matrix H of a sample's plane counts as singular
/// when det H is below this fraction of trace(H)^2 (det / trace^2 is 1/4 for neighbours spread
/// evenly around, and scales like the square of the spread's aspect ratio). Ill-conditioned
/// with the neighbours weighted by their coordinates (kGradientFitConditionRelative, below),
/// they are weighted by distance alone; singular so too (the visible neighbours on one line
/// through the sample), the plane is fitted along that line alone, with no gradient across it.
inline constexpr double kGradientFitSingularRelative = 1e-12;

/// sibson-c1's gradient fit weights a sample's neighbours by their Sibson coordinates over their
/// squared distances (Sibson's weights) while the normal matrix H of that fit has det H above
/// this fraction of trace(H)^2 (about the reciprocal of its condition number; 1/4 for neighbours
/// spread evenly around), and by distance alone below it. The fitted slope errs by about the
/// data's curvature times that condition number: a sample 0.1 m inside a 6.5 km hull edge gave
/// its Sibson weights almost all to the edge's far ends (det / trace^2 = 7e-7) and a slope of
/// 0.77 /m where the data's largest is 0.002 /m; its distance weights give 0.12 and a slope off
/// by 0.3 of that largest. Among those 100,000 uniform samples 69 fall below 1e-3 (the 0.1%
/// quantile is 1.8e-3; nearly all of them within a few metres of the hull); with Sibson's
/// weights those between 1e-4 and 1e-3 still erred by up to twice the data's largest slope,
/// those between 1e-3 and 3e-3 by 0.56 of it, those above by less.
inline constexpr double kGradientFitConditionRelative = 1e-3;

/// sibson-c1's two gradient fits are blended where the Sibson-weighted fit's det H / trace(H)^2
/// lies between kGradientFitConditionRelative and this many times it: the Sibson fit's share
/// rises smoothly in the logarithm from 0 to 1 (a gradient that switched at one threshold moved
/// a sample's gradient by a step under the rounding of a change of units).
inline constexpr double kGradientFitBlendRelative = 4;

/// RBFs with a linear polynomial (reconstruct/multiquadric_basis.h): a subset of samples whose
/// spread across its principal axis is below this fraction of its spread along it counts as
/// lying on one line, and its polynomial drops the term across (linear along the line, constant
/// across). The term across is then determined only by offsets this thin: it would extrapolate
/// the values' noise by the inverse of the ratio, and sit at the round-off of the coordinates
/// (1e-16 of them) for samples on an exact line. 1e-8 keeps every subset with a real width.
inline constexpr double kRbfFlatSubsetRelative = 1e-8;
/// RBF fits derived from a nearby subset's factorisation (fit_rbf_near()): the largest backward
/// error accepted, each equation's residual over the sum of its terms' magnitudes. A dense LU
/// with partial pivoting gives some 1e-15 here; a derived fit past 1e-10 is solved directly.
inline constexpr double kRbfNearFitBackwardError = 1e-10;

/// Gouraud (reconstruct/gouraud.h): cell corners within this fraction of the cells' extent
/// count as one point, and a balanced leaf's midpoints snap onto known corners within it. Far
/// above the round-off of corners computed as u * length (1e-16 relative), far below any cell
/// (a quadtree 33 levels deep still has leaves 1.2e-10 of its side).
inline constexpr double kCellSnapRelative = 1e-10;

/// Clough-Tocher's gradients (Nielson's equations) are solved by preconditioned conjugate
/// gradients until the preconditioned residual falls below this fraction of the right-hand
/// side's: with the system's condition (at most 3 after preconditioning) the gradients are then
/// within some 1e-13 relative of the exact solution, far below scipy's default tol = 1e-6 and
/// just above the rounding floor of the sums (some 1e-15).
inline constexpr double kNielsonResidualRelative = 1e-13;

}  // namespace radrecon::tol
