#pragma once
// Every numerical tolerance of the library, named, with the reason for its value.

#include <cstddef>

namespace radrecon::tol {

/// Largest distance (relative to the quad's size) of a corner from the plane of the other three
/// for a quad to count as planar. Scenes are written by hand or exported in single precision,
/// so 1e-6 of the size accepts float round-off and refuses real warps.
inline constexpr double kPlanarityRelative = 1e-6;

/// Largest coordinate magnitude of a scene (metres) and largest emission (W/m^2): beyond them
/// areas, powers and form factors would overflow or lose all precision in double.
inline constexpr double kMaxCoordinate_m = 1e6;
inline constexpr double kMaxEmission_w_m2 = 1e12;

/// How far from 1 a glTF node's rotation quaternion may be in length. The glTF schema asks for
/// unit quaternions and exporters write them in single precision (within ~1e-7); assimp 5.2
/// applies one of any length as it stands, scaling the mesh by its squared length.
inline constexpr double kGltfUnitQuaternion = 1e-3;

/// Smallest area (relative to the squared longest edge) of a non-degenerate quad.
inline constexpr double kDegenerateAreaRelative = 1e-9;

/// A point counts as lying in a plane when its signed distance is within this many metres.
/// Scenes are metre-scale; 1e-9 m is far below any feature and far above double round-off.
inline constexpr double kPlaneDistance_m = 1e-9;

/// Smallest extent (the diagonal of the box around every corner) of a scene, metres. The
/// geometric tolerances of visibility (kPlaneDistance_m, kShaftSlack_m) are absolute, for
/// metre-scale scenes: a scene a millimetre across keeps them a million times below its size.
/// (A box scene reads identically down to 1e-7 m and loses its shadows below 3e-8 m.)
inline constexpr double kMinSceneExtent_m = 1e-3;

/// Two directions whose angle has a sine below this count as parallel (a camera's up vector and
/// view direction): 1e-6 rad is far below any intended tilt.
inline constexpr double kParallelSine = 1e-6;

/// Adaptive shooting: a shooter block is used as a whole when its distance from the receiver
/// point exceeds this multiple of its diagonal; closer, it is split into its elements. At 2
/// diagonals the point-collocated form factor of a block differs from the sum over its parts
/// by well under 1% for smoothly varying radiosity. This rule (`solve --far-field-error 0`) has
/// no error bound: a wall's back side is 6% too bright in the paper scene (docs/method.md);
/// ProgressiveOptions::far_field_error, the default, bounds the error instead.
inline constexpr double kFarFieldDiagonals = 2.5;

/// The far field's error bound (ProgressiveOptions::far_field_error) is made for no less
/// irradiance than this fraction of the shot's power spread over the scene's area: a receiver in
/// the dark would otherwise split every block down to its elements for light it barely gets.
inline constexpr double kFarFieldLeastIrradianceFraction = 1e-2;
/// Near a block, where form_factor_bound() (solver/gather.h) grows without bound, a block may
/// still shoot as one when form_factor_ceiling() times its spread is within this fraction of its
/// share of the budget. Any value in the block's range then errs by at most the ceiling times
/// the spread, but near the block that error has one sign over the elements around it: with the
/// whole share, the closed room with a lamp on its ceiling gained 3.0e-3 of its power at
/// reflectance 0.95 (the issue allows 1e-3), with 0.3 of it 8.2e-4, with a tenth -2.8e-4
/// (-6.0e-4 without the ceiling; all with 2 patches along the longest edge and the ceiling at the
/// element's centre alone); the paper's reference took 7-10% less processor time.
inline constexpr double kNearFieldCeilingShare = 0.1;
/// Where an element sees the shooting patch in part and occluders stand between its side and the
/// patch, a block may shoot as one by form_factor_bound() or form_factor_ceiling() alone, before
/// its visible form factor is known, only within this fraction of its share (of that test's
/// share). Such a block may be partly hidden, and shot whole it shoots the mean of all of it; an
/// occluder hides from many elements the very region it darkens, so that error has one sign.
/// The Cornell box at grid:32 against a 20 times finer bound (4 patches along the longest edge):
/// the box's ceiling (the surface) is -0.48% off on average with the whole share, -0.14% with a
/// quarter, -0.06% with a tenth; at grid:128 it solves in 6.6, 7.4 and 10.7 s.
inline constexpr double kPartlyHiddenStrictShare = 0.25;
/// An element whose gathered irradiance falls below this fraction of the estimate its budget was
/// made for (the whole patch's, at its centre) gathers again with the budget of what it got.
inline constexpr double kFarFieldRegatherRatio = 0.5;
/// The far field (solver/far_field.h far_field_radiosity()) is of second order while the
/// kernel's second-order term over the block, relative to the kernel, is at most this; beyond,
/// the orders it leaves out are no longer small (and 1 / shape could change sign): first order.
/// Its error estimate (far_field_error()) is trusted while R^2 (|g_t|^2 + 4 / |d|^2) / 2 is at
/// most this too (R the block's radius, g_t the kernel's log-gradient in the shooter's plane, d
/// the distance): beyond, the block splits.
inline constexpr double kFarFieldCurvatureLimit = 0.25;
/// far_field_error() reads the kernel's remainder at a box's corners and edge midpoints; its
/// largest value over the box is at most this many times the largest read there, for the
/// leading (cubic) remainder: 1.631 at worst for a cubic form (any box: stretching maps the
/// points onto each other; 1.25 for a quadratic one, the first-order far field's) ...
inline constexpr double kFarFieldRemainderSamplingBox = 1.65;
/// ... and, read at each edge's quarters, on a triangle or a box cut by a triangle's hypotenuse:
/// 1.22 at worst found for cubic forms on a right triangle (random forms, then hill climbing),
/// 1.14 on a box with a corner cut. (Corners and midpoints alone lie on a triangle's medians,
/// where a cubic form can vanish.)
inline constexpr double kFarFieldRemainderSamplingOther = 1.3;

/// A contact line lies on a boundary of a side's cells (solver/shooter_tree.h shooter_splits())
/// when it is within this fraction of a cell of it, along its whole length.
inline constexpr double kSplitAlignRelative = 1e-6;

/// Two values of unshot radiosity (W/m^2) within this relative difference count as equal, so a
/// block of uniform unshot radiosity (an emitter's first shot) is never split: by additivity of
/// form factors that is exact.
inline constexpr double kUniformRelative = 1e-12;

/// Smallest element of hierarchical radiosity, as a fraction of the scene's longest edge (1/256:
/// 1.6 cm on the paper's 4 m ground, finer than its 1 cm reference only by a factor of 1.6).
inline constexpr double kMinElementFraction = 1.0 / 256;

/// Multiquadric interpolation warns when the reciprocal condition estimate of its matrix falls
/// below this: about 4 of double precision's 16 digits then survive in the coefficients.
inline constexpr double kPoorConditioning = 1e-12;

/// Inverse quad mapping (Surface::parameters): a point whose (u, v) lies within this of [0,1]
/// is on the quad (rays that hit an edge between two quads are not lost to round-off).
inline constexpr double kQuadEdgeParameter = 1e-12;
/// ... and a quad counts as a parallelogram (the mapping's quadratic term vanishes) when that
/// term is below this fraction of the linear one.
inline constexpr double kParallelogramRelative = 1e-12;

/// Largest magnitude of a sample or query coordinate: squared distances then stay below 1e201,
/// far from double overflow (1.8e308), with room for the products the methods form. Beyond it
/// distances overflow and neighbour searches lose points.
inline constexpr double kMaxSampleCoordinate = 1e100;
/// Largest magnitude of a sample's value: the methods' weighted sums, gradient estimates and
/// their products with distances then stay far from overflow. Beyond it, values near the
/// largest double (1e308) made Shepard's sums infinite and the C1 methods' gradients NaN.
inline constexpr double kMaxSampleValue = 1e100;

/// A raster written through GDAL is read back (io/gdal_raster.h): a value may differ from what
/// was written by this fraction of the band's largest magnitude, with a warning (a text format's
/// decimal digits: ZMap writes 7 significant ones, about a 32-bit float's), and no more (a format
/// that rounds to bytes or integers).
inline constexpr double kRasterReadBackRelative = 1e-6;

/// A grid solution's element (i, j) must start within this of (i / nu, j / nv) in (u, v): the
/// files hold 17 significant digits, so only a misplaced element is farther.
inline constexpr double kSolutionGridParameter = 1e-9;

/// The local multiquadric's patch grid over the samples' bounding box: a box of no width (samples
/// on a line) gets this fraction of its length as width, and at least this fraction of its
/// squared length as area, so that the patch size (from the area per sample) stays finite and
/// the patches along the line still hold about k samples each.
inline constexpr double kFlatBoxWidthRelative = 1e-12;
inline constexpr double kFlatBoxAreaRelative = 1e-6;

/// A solution's side belongs to a scene's surface when their edge lengths agree to this fraction:
/// both come from the same corners (solution files hold 17 digits), so a larger difference
/// means another scene.
inline constexpr double kSolutionLengthRelative = 1e-9;

/// A solution's element lies on its scene surface when its stored centre is within this fraction
/// of the surface's size plus its distance from the origin of the point the surface puts at the
/// element's (u, v) centroid: solution files hold centres to 9 digits (5e-9 of a coordinate), so
/// a larger distance means the surface has moved.
inline constexpr double kSolutionCentreRelative = 1e-7;

/// A surface touches another's plane (a wall standing on the ground) when its corners lie within
/// this fraction of its own size of that plane: scenes written by hand or exported in single
/// precision put them there to round-off, far below any real gap.
inline constexpr double kContactRelative = 1e-6;

/// A contact line whose ends lie within this of the same edge of a quad's (u, v) square runs
/// along that edge: it bounds the side and is no barrier inside it. A point outside a surface's
/// (u, v) domain by at most this lies on its border (Surface::parameters(),
/// SurfaceSolution::contains_st()).
inline constexpr double kOnBorderParameter = 1e-9;

/// Contact lines and covered regions of a side (scene/contacts.h), in its (s, t) metres: two
/// points within this fraction of the side's longer edge are one point (the ends of two contact
/// lines meet there and chain into a loop; two lines with such ends are one line), a polygon's
/// vertex this close to the line through its neighbours is dropped, and a region no wider than
/// this is no region. The ends come from the corners of different surfaces, equal up to the
/// round-off of scenes written by hand or exported in single precision (6e-8 relative): far
/// below 1e-6, and 1e-6 of the side is far below any real gap or sliver.
inline constexpr double kContactJoinRelative = 1e-6;
/// A surface lying flat on a side covers it only when its area is below (1 - this) times the
/// side's: of two coplanar overlapping quads the smaller lies on the larger (a plate on a floor,
/// never the floor on the plate), and two equal ones up to round-off (a duplicated quad, its
/// corners listed in another order) cover neither.
inline constexpr double kLyingSmallerRelative = 1e-6;
/// An area enclosed by surfaces standing on a side, one of which faces it (or is two-sided), is
/// hidden only if no light reaches it: the solver keeps it excluded while every element of the
/// side inside it has a radiosity at most this fraction of the solution's brightest (exact
/// shadows give 0 inside a closed box, up to round-off), solver/solve.cpp.
inline constexpr double kEnclosedLitRelative = 1e-9;

/// A point of an excluded region within the side's frame bend of its outline takes the value at
/// the nearest point of the outline moved this fraction of the side's longer length out across it
/// (sampling/solution_reconstruction.h, SideSampling::outline_band_m): beyond the outline as a
/// barrier, so it sees the samples outside, and far below any element.
inline constexpr double kExcludedOutlineNudgeRelative = 1e-9;

/// A surface is one face of a sheet of no thickness when the coplanar surfaces facing the other
/// way cover each of this many x this many points over it (scene/contacts.cpp): their faces then
/// cover none of it.
inline constexpr int kSheetProbes = 16;

/// A coordinate's rounding, as a fraction of its magnitude (64 ulps): the rounding part of a hull
/// edge's band (kHullEdgeBandRelative), a regular grid's least tolerance (kGridCoordinateRelative),
/// a query within rounding of a sample (kNearSampleRelative).
inline constexpr double kCoordinateRounding = 64 * 2.220446049250313e-16;

/// The renderer's ray casting (render/renderer.h): an emitting side hit within this fraction of
/// the coordinates' magnitude there (|o| + t for the ray o + t d) of the nearest hit wins the
/// tie, so that a light in the plane of a ceiling is seen. The two planes' computed distances
/// differ by the round-off of their corners: some 1e-16 of the coordinates for the same plane
/// written twice, 1e-7 for corners from single-precision model files, more at grazing angles.
/// 1e-6 covers both and is far below any intended offset (a micrometre in a scene a metre
/// across); a light that little behind a surface is drawn in front of it.
inline constexpr double kEmitterTieRelative = 1e-6;

/// `export` writes positions as 32-bit floats, relative to an origin near the model kept by the
/// nodes' translation when the model's centre lies farther from (0, 0, 0) than this many of its
/// extents (beyond, a float's rounding of the centre's magnitude, 2^-24 of it, would pass 1e-6 of
/// the extent: a 0.45 m lamp at x = 300 km came out 0.4375 m wide).
inline constexpr double kExportOriginFreeExtents = 16;

/// An exported surface covering part of another (a lamp lying on a ceiling) is raised off it
/// along its normal by this fraction of its own longer side (export/gltf.h, export_raise_m()):
/// 0.13 mm for the Cornell box's 13 cm lamp, 1 mm for a 1 m window, above a viewer's depth
/// resolution where such a surface is seen whole (6e-7 m at 1 m, 6e-5 m at 10 m, with a 24-bit
/// depth buffer and a 0.1 m near plane), far below anything the eye takes for a gap.
inline constexpr double kExportRaisedRelative = 1e-3;

/// `render` warns of pixels whose radiosity lies below 0 by more than this fraction of the
/// picture's largest (a method overshooting its samples), not of round-off below 0.
inline constexpr double kRenderNegativeRelative = 1e-9;

/// The renderer's surface hierarchy (render/surface_bvh.h) widens every surface's box by this
/// fraction of (1 m + the scene's size and coordinates): far above the round-off of a ray's hit
/// on an edge (Surface::parameters() accepts one within tol::kOnBorderParameter), so no hit the
/// brute-force search finds is missed.
inline constexpr double kRayBoxSlackRelative = 1e-7;

/// A quad corner within this fraction of the quad's longest edge of the next corner repeats it:
/// the quad is read as the triangle of the other three (scene/scene.h regularise_surfaces()).
inline constexpr double kRepeatedCornerRelative = 1e-9;

/// Progressive refinement gathers a receiving element's irradiance at its centre (the midpoint
/// rule, relative error of order (size / distance)^2) while its size is below this fraction of
/// its distance to the shooting block's bounding sphere, and as the element's mean by a Gauss
/// rule (solver/gather.h gather()) when it is nearer: point collocation near a
/// shooter gains or loses power with every bounce (0.4% of the shot in a closed room at grid:12).
/// Not larger: at 1/8 (a third of the Gauss points in the paper's reference) the closed room still
/// kept its energy to 3.3e-4, but the Cornell box's block sides erred by up to 6.5% on their row
/// next to the floor, whose power near the blocks' feet the midpoint rule misjudges (1/16 and
/// 1/32 agree there to 0.5%).
inline constexpr double kMidpointReceiverRatio = 1.0 / 16;

/// A polygon's ear-clipped triangles (io/mesh_polygons.h triangulate_polygon()) must add up to its
/// area (Newell's) within this fraction: else it crosses itself and is refused.
inline constexpr double kTriangulationAreaRelative = 1e-9;

/// The far-field correction of progressive refinement (solver/far_field.cpp
/// far_field_radiosity()) divides by the cosines at both ends of the kernel: at grazing angles,
/// below this cosine, the block shoots with its mean radiosity alone.
inline constexpr double kKernelCosine = 1e-3;

/// Clusters of small shooters (solver/shooter_clusters.h): a receiving element at least this
/// many of a subtree's radii from its centre gathers from it as from its members' sources, past
/// one shadow ray to the centre; nearer, from its two halves. A ratio: the ray draws a penumbra
/// as a step where the subtree is wide against its distance. A light of 288 triangles, half way
/// above a black square, lit the floor 1.1% too dark in all at 3 radii, 0.06% at 8
/// (shooter_clusters_test.cpp).
inline constexpr double kClusterFarRadii = 8.0;
/// The same ratio for a single member, below which it shoots with exact shadows, as a patch: its
/// penumbra is its own size.
inline constexpr double kClusterMemberFarRadii = 3.0;
/// Within a far subtree, a member at least this many of its own radii from the receiving point
/// shoots as its point kernel B A cos cos / (pi d^2), which errs by about (radius / d)^2; nearer,
/// as its exact (Lambert) form factor. A ratio.
inline constexpr double kClusterPointKernelRadii = 16.0;

/// Progressive refinement clusters a mesh's sides of a single element (a model's triangles) only
/// when it has at least this many: a scene of a few dozen small surfaces shoots them one by one,
/// with exact shadows, as it always did. A count.
inline constexpr std::size_t kLeastClusteredSides = 256;

/// The boxes by which visibility.cpp rejects a shadow for a fragment of the shooter (the
/// projections from the receiving point onto the shooter's plane of the occluder and of the
/// fragment) are widened by this fraction of (1 m + their extent + their coordinates' size):
/// far above the projections' rounding, so that only fragments clear of the shadow are passed
/// over.
inline constexpr double kShadowTraceRelative = 1e-7;

/// The fewest shadows on a shooting patch, seen from a receiving point, for which the point keeps
/// the patch's visible fragments and clips them to each block it gathers from
/// (solver/shadow_subtraction.h VisibleFragments), rather than subtracting every shadow from each block
/// again. A count, not a length; below it (the paper scene, the Cornell box) the per-block
/// subtraction is cheaper, and the solutions stay bit for bit what they were.
inline constexpr std::size_t kKeptFragmentsShadows = 16;

/// The least fraction of its area that an element wholly enclosed by surfaces standing on its
/// side keeps in the progressive solver (solver/enclosed.h): its power is then nil to 1e-9 of
/// an element's, while its shooter blocks keep an area to take their means over.
inline constexpr double kEnclosedLeastFraction = 1e-9;

/// An element (or quadtree node) whose overlap with the enclosed regions of its side is at most
/// this fraction of its area is not enclosed at all, and one left exposed by at most this
/// fraction wholly enclosed (solver/enclosed.h): it only touches a region's outline, from outside
/// or inside, the difference the clip's round-off.
inline constexpr double kEnclosedOverlapRelative = 1e-9;

/// VisibleFragments: a part of a shooting patch counts as seen in part when the fragments it sees
/// cover less of its front than its area less this fraction of it, and less kPlaneDistance_m
/// times its outline's length: clip() takes a vertex within kPlaneDistance_m of a plane as on it,
/// which can move the part's boundary by as much; the fragments' areas themselves round off at
/// 1e-15 relative. A shadow over less than that slack changes the form factor by less than it.
inline constexpr double kHiddenAreaRelative = 1e-9;

/// Shaft culling (solver/bvh.h): a BVH node or occluder counts as outside the shaft between a
/// receiver and a shooter only when it lies more than this beyond one of the shaft's planes.
/// Far above kPlaneDistance_m, within which the clipping of visibility.cpp treats a point as on
/// a plane (so a polygon touching the shaft to that tolerance still casts its shadow), and far
/// below any gap a scene means (a micrometre): the cull stays conservative and loses nothing.
inline constexpr double kShaftSlack_m = 1e-6;

/// Mesh import (io/mesh_polygons.h): two triangles are merged into one quad only if the quad is
/// convex with a margin, each corner's turn (the cross product of its edges along the normal) at
/// least this fraction of the quad's longest edge squared (about this many radians short of a
/// straight angle). validate_scene() refuses corners at kDegenerateAreaRelative; this margin,
/// 1000 times wider, keeps a merged quad clear of that refusal under the round-off of
/// single-precision model files (1e-7), so two triangles meeting on a straight line stay two.
inline constexpr double kQuadMergeTurnRelative = 1e-6;

/// Natural-neighbour interpolation (and laplace, sibson-c1): a query within this fraction of a
/// hull edge's length of the edge (or of the height of the hull triangle on it, if smaller: a
/// thin strip of samples, whose coordinates change fast across it), plus kCoordinateRounding times
/// its coordinates' magnitude, is on the edge, and gets the linear interpolation along it (the
/// limit of Sibson's coordinates from inside). Points computed on a hull edge land within
/// rounding of it, inside or outside; inside, the Voronoi computation cancels catastrophically
/// there (tests/reconstruct).
inline constexpr double kHullEdgeBandRelative = 1e-9;

/// A Delaunay face (linear, clough-tocher) whose height over its longest edge is below this
/// fraction of that edge is a sliver: a query's barycentric coordinates by the inverse of its
/// matrix err by about eps / (this ratio) (cancellation), projected onto its two short edges (the
/// polyline along the longest) by the ratio itself; the two are equal near sqrt(eps), 1.5e-8.
inline constexpr double kDelaunaySliverRelative = 1e-8;

/// A sample within this fraction of a hull edge's length from its line, between its ends, lies on
/// it up to rounding (reconstruct/hull_chain.h): the edge is split there. Samples computed on one
/// line (a triangle's centroids along its hypotenuse) stray from it by a few ulps, some 1e-16 of
/// its length; a sample a millionth off is no rounding. Whether a query lies on the hull is judged
/// against the unsplit edge, its band (kHullEdgeBandRelative) widened by the depth of the samples
/// it was split at, so that the split takes no query off the hull.
inline constexpr double kHullChainRelative = 1e-12;

/// A natural-neighbour query whose coordinates' sum cancels to nothing (not positive) lies within
/// rounding of a sample when it is within this fraction of its face's longest side of it (or
/// kCoordinateRounding of its own magnitude), and takes that sample's value
/// (reconstruct/natural_neighbour_impl.h); farther, the failed sum's rule stands.
inline constexpr double kNearSampleRelative = 1e-12;


/// `interpolate` warns when Hardy's global multiquadric without a polynomial is given values
/// whose mean exceeds this many times their range (reconstruct/methods.h, make_point_interpolant()):
/// it holds no constant, and bends toward 0 by an amount in proportion to the mean.
inline constexpr double kMultiquadricOffsetWarning = 1;

/// A PNG of a raster (io/raster.h) maps [min, max] of its finite values to black and white; when
/// max - min is no more than this fraction of their magnitude the values are taken as one (the
/// rounding of an interpolant of constant data) and shown at display 0.5, not as speckle.
inline constexpr double kPngFlatRangeRelative = 1e-9;

/// Samples closer than this fraction of their extent (the larger side of their bounding box) to
/// an earlier one are merged with it (reconstruct/sample_set.h): at 1e-12 apart natural
/// neighbour's Sibson areas lost 7e-7 of a linear function and sibson-c1's fitted gradients 4%
/// (tests/hostile: near_duplicates). Far below any spacing that data is sampled at.
inline constexpr double kNearDuplicateRelative = 1e-9;

/// The smallest extent (larger side of the bounding box) of a sample set the scattered methods
/// take: below it squared distances underflow (1e-300 apart gives 0) and the triangulation
/// methods' areas lose all precision, so such data is refused with advice to rescale it.
inline constexpr double kMinSampleExtent = 1e-100;

}  // namespace radrecon::tol

// The tolerances of scattered-data reconstruction: one include for every tolerance.
#include "core/tolerances_reconstruct.h"  // IWYU pragma: export
