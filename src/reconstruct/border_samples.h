#pragma once
// Border samples: extra samples on the border of a patch and on both sides of its barriers, with
// values extrapolated from the samples inside, so that a reconstruction from element centres
// interpolates up to the border instead of extrapolating past the outermost centres (the paper's
// future work: "adding additional sample points along the border"), and a query next to a
// barrier finds a sample of its own side right there.
//
// The rule. Let h be the spacing (settings.spacing_m, or when 0 the median distance from each
// interior sample to its nearest other one at a different point, sought among its 8 nearest;
// with no such distance, a single sample or all at one point, the domain's longer side), and
// delta = tol::kBorderOffsetRelative (1e-6) x the domain's longer side (border_offset_m()).
//   - Border: each side of the domain, of length L, is cut into m = ceil(L / h) equal parts (a
//     length within tol::kBorderSpacingRelative of a whole number of spacings gets that number),
//     m >= 1; the cut points are the candidates, the four corners always among them (each once).
//     Order: counter-clockwise from (x0, y0).
//   - Barriers: each barrier segment is clipped to the domain; the part inside, of length L, gets
//     positions inset delta from both its ends and between them evenly at most h apart
//     (ceil((L - 2 delta) / h) parts; one position at the middle when L <= 2 delta), and at each
//     position two candidates, delta from the segment along its normal: the left side of a -> b
//     first, then the right. So no sample stands on or beyond a barrier's end point: the last
//     ones stand beside the segment, delta before its end, one on each side; around a free end a
//     query sees both sides' samples (light passes around it), and at a joint of a polyline each
//     segment has its own samples. Order: segments in Barriers::segments() order, positions from
//     a to b.
//   - A candidate is dropped when it lies outside the closed domain; when (a border candidate)
//     it lies within delta of a barrier segment (the barrier's own samples stand there, one on
//     each side); when (a barrier candidate) it does not see the point delta / 2 from its
//     segment toward it (another barrier lies between: at a sharp joint); when it lies within
//     delta of an interior sample (the interior sample stands there already) or of an earlier
//     kept candidate (the corner shared by two barriers that meet at a right angle); or when it
//     sees no interior sample among its kMaxVisibleCandidates nearest (a region the barriers cut off).
//   - Value: the fit over its k = settings.fit_neighbours nearest interior samples visible from
//     it (nearest_visible(), barriers.h): with v0 the nearest one's value, the weighted
//     least-squares plane through the differences v_i - v0 with weights 1 / d_i^2 (d_i the
//     distance of sample i from the candidate), evaluated at the candidate, plus v0; per channel.
//     With fewer than 3 neighbours, or neighbours within tol::kFitCollinearRelative of their
//     extent of one line (the line through the nearest and the one farthest from it), the value
//     is v0. Any positive weights reproduce a plane exactly; fitting differences from v0 makes
//     constant data come back exactly (no round-off: a step across a barrier stays a step).

#include "core/result.h"
#include "reconstruct/barriers.h"
#include "reconstruct/samples.h"

namespace radrecon {

struct BorderSampleSettings {
  /// Distance between border samples along the border and along each barrier, metres, > 0;
  /// 0: the interior samples' typical spacing (the median nearest-neighbour distance).
  double spacing_m = 0;
  /// Interior samples in each border sample's plane fit (>= 1; below 3 every value is the
  /// nearest visible sample's).
  int fit_neighbours = 6;
  /// Samples on the domain's border; false: along the barriers only.
  bool on_domain_border = true;
  /// Samples on both sides of each barrier; false: on the domain's border only (their values
  /// still fitted from the samples each sees).
  bool beside_barriers = true;
};


/// The distance delta of the rule above: tol::kBorderOffsetRelative x the domain's longer side.
double border_offset_m(const Rect& domain);

/// `interior`, unchanged and first, followed by the border and barrier samples of the rule above
/// (with interior's channels). Interior samples may lie anywhere, inside the domain or not, and
/// may repeat a point. A Failure when there is no interior sample, a sample's coordinates or
/// values are not finite numbers (or coordinates beyond tol::kMaxSampleCoordinate), the domain
/// is not a finite rectangle with positive width and height, the spacing is negative or not
/// finite, fit_neighbours < 1, or the spacing would place more than 10 million samples.
Result<ScatteredSamples> with_border_samples(const ScatteredSamples& interior, const Rect& domain,
                                             const Barriers& barriers, const BorderSampleSettings& settings = {});

}  // namespace radrecon
