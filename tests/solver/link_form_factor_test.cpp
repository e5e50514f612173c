// A link's area-to-area form factor (hierarchical radiosity) across a shadow boundary, against
// an independent adaptive cubature of the same exact point form factor.

#include <gtest/gtest.h>

#include <cmath>

#include "mesh/quadtree.h"
#include "solver/link_form_factor.h"
#include "solver/visibility.h"

namespace radrecon {
namespace link_form_factor_test {

Surface make_surface(const std::string& name, std::array<Vec3, 4> corners, int corner_count = 4) {
  Surface s;
  s.name = name;
  s.corners = corners;
  s.corner_count = corner_count;
  return s;
}

/// A floor (receiver), a small light 1 m above it facing down, and a plate between them whose
/// shadow crosses the floor: the point form factor jumps from 0 (umbra) to its unoccluded value.
Scene shadow_scene(int floor_corners) {
  Scene scene;
  const std::array<Vec3, 4> floor = floor_corners == 4
                                        ? std::array<Vec3, 4>{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)}
                                        : std::array<Vec3, 4>{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 1, 0)};
  scene.surfaces.push_back(make_surface("floor", floor, floor_corners));
  scene.surfaces.push_back(
      make_surface("light", {Vec3(0.4, 0.4, 1), Vec3(0.4, 0.6, 1), Vec3(0.6, 0.6, 1), Vec3(0.6, 0.4, 1)}));
  scene.surfaces.push_back(
      make_surface("plate", {Vec3(0.05, 0.15, 0.45), Vec3(0.55, 0.15, 0.45), Vec3(0.55, 0.6, 0.45), Vec3(0.05, 0.6, 0.45)}));
  return scene;
}

/// The adaptive cubature's tolerance (an absolute error of F per square, visibility.h): far
/// below the link rule's own error.
constexpr double kReferenceTolerance = 1e-7;
/// The link rule's error, relative to the largest point form factor. Across a jump, the midpoint
/// rule on cells of 1/16 of the receiver's edge beside the jump errs by a fraction of the jump
/// over the cells it crosses: at most 7.8e-4 here, where the coarse 4 x 4 rule alone errs by up
/// to 1.0e-2. Elsewhere (penumbrae too gentle to count as jumps) the coarse rule's own error.
constexpr double kAcrossJumpRelativeError = 2e-3;
constexpr double kCoarseRelativeError = 1.5e-2;

void check_links(int floor_corners) {
  const Scene scene = shadow_scene(floor_corners);
  const std::vector<Occluder> occluders = make_occluders(scene);
  const OccluderBvh bvh(occluders);
  const std::vector<const Occluder*> plate{&occluders[2]};
  const Quadtree floor(scene.surfaces[0], false), light(scene.surfaces[1], false);
  const LinkEnd source{&scene.surfaces[1], 1, scene.surfaces[1].normal(), light.node(0)};
  ConvexPolygon light_polygon;
  for (const Vec3& c : scene.surfaces[1].corners) light_polygon.push(c);
  // The floor, its quarters and their quarters.
  std::vector<ParamCell> cells{floor.node(0)};
  for (const ParamCell& q : floor.node(0).quarters()) {
    cells.push_back(q);
    for (const ParamCell& g : q.quarters()) cells.push_back(g);
  }
  int across_jumps = 0;
  for (const ParamCell& cell : cells) {
    const QuadNode node = floor.node_for(cell);
    const LinkEnd receiver{&scene.surfaces[0], 0, scene.surfaces[0].normal(), node};
    const LinkFormFactor link = measure_link(receiver, source, bvh, true);
    const double reference = area_visible_form_factor(node.corners, receiver.normal, light_polygon,
                                                      source.normal, plate, kReferenceTolerance);
    const bool jump = link.f_spread > kDiscontinuousSpread * (link.f + link.f_spread);
    across_jumps += jump ? 1 : 0;
    // The error relative to the largest point form factor seen (f + spread bounds it).
    EXPECT_NEAR(link.f, reference, (jump ? kAcrossJumpRelativeError : kCoarseRelativeError) * (link.f + link.f_spread))
        << "cell [" << cell.u0 << "," << cell.u1 << "] x [" << cell.v0 << "," << cell.v1 << "]"
        << (jump ? " across a jump" : "");
  }
  // The refinement beside jumps is what is under test: the shadow must cross several nodes.
  EXPECT_GE(across_jumps, 4);
}

TEST(LinkFormFactor, AcrossAShadowBoundaryMatchesAdaptiveCubatureOnAQuad) { check_links(4); }
TEST(LinkFormFactor, AcrossAShadowBoundaryMatchesAdaptiveCubatureOnATriangle) { check_links(3); }

}  // namespace link_form_factor_test
}  // namespace radrecon
