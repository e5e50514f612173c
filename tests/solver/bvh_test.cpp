// Shaft culling through the occluder BVH (solver/bvh.h) against the all-occluders scan: the same
// visible form factors, and every occluder it drops provably off every segment it could block
// (checked with the independent ray caster of tests/support).

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <random>
#include <span>

#include "solver/bvh.h"
#include "solver/form_factor.h"
#include "solver/visibility.h"
#include "support/occluder_lists.h"
#include "support/ray_scene.h"
#include "support/scenes.h"

namespace radrecon {
namespace bvh_test {

using testing_support::intersect_quad;

/// A scene of `count` random polygons in a 6 m cube, a third of them triangles: rectangles and
/// triangles of 0.2 to 1.5 m, randomly oriented, crossing each other freely.
Scene random_scene(std::mt19937& rng, int count) {
  std::uniform_real_distribution<double> pos(0, 6), size(0.2, 1.5), angle(0, 2 * std::numbers::pi), unit(-1, 1);
  Scene scene;
  for (int k = 0; k < count; ++k) {
    const Vec3 c(pos(rng), pos(rng), pos(rng));
    Vec3 axis(unit(rng), unit(rng), unit(rng));
    if (axis.norm() < 1e-3) axis = Vec3::UnitZ();
    const Eigen::Matrix3d rot = Eigen::AngleAxisd(angle(rng), axis.normalized()).toRotationMatrix();
    const Vec3 u = rot * Vec3(size(rng) / 2, 0, 0), v = rot * Vec3(0, size(rng) / 2, 0);
    scene.surfaces.push_back(testing_support::centred_polygon("s" + std::to_string(k), c, u, v, k % 3 == 2));
  }
  return scene;
}

/// A random point of the surface (barycentric on a triangle, bilinear on a quad), off its border.
Vec3 random_point(std::mt19937& rng, const Surface& s) {
  std::uniform_real_distribution<double> t(0.02, 0.98);
  double a = t(rng), b = t(rng);
  if (s.is_triangle()) {
    if (a + b > 1) a = 1 - a, b = 1 - b;
    return s.corners[0] + a * (s.corners[1] - s.corners[0]) + b * (s.corners[2] - s.corners[0]);
  }
  return s.point(a, b);
}

using testing_support::all_but;
using testing_support::polygon_of;

struct Case {
  size_t receiver, shooter;
  Vec3 p, n;
};

/// Random (receiver point, shooter) cases with the point in front of the shooter and the
/// receiver's normal turned towards it (so most form factors are positive).
std::vector<Case> random_cases(std::mt19937& rng, const Scene& scene, int count) {
  std::uniform_int_distribution<size_t> pick(0, scene.surfaces.size() - 1);
  std::vector<Case> out;
  while (static_cast<int>(out.size()) < count) {
    Case c{pick(rng), pick(rng), Vec3::Zero(), Vec3::Zero()};
    if (c.receiver == c.shooter) continue;
    const Surface& s = scene.surfaces[c.shooter];
    c.p = random_point(rng, scene.surfaces[c.receiver]);
    if (s.normal().dot(c.p - s.corners[0]) <= 1e-3) continue;
    c.n = scene.surfaces[c.receiver].normal();
    if (c.n.dot(s.corners[0] + s.corners[2] - 2 * c.p) < 0) c.n = -c.n;
    out.push_back(c);
  }
  return out;
}

TEST(OccluderBvh, PointShaftGivesTheSameFormFactorAsAllOccluders) {
  std::mt19937 rng(1991);
  const Scene scene = random_scene(rng, 300);
  const std::vector<Occluder> occ = make_occluders(scene);
  const OccluderBvh bvh(occ);
  int occluded = 0, culled = 0;
  for (const Case& c : random_cases(rng, scene, 1500)) {
    const Surface& s = scene.surfaces[c.shooter];
    const ConvexPolygon shooter = polygon_of(s);
    std::vector<const Occluder*> near;
    bvh.collect(Shaft({&c.p, 1}, s.polygon()), c.receiver, c.shooter, near);
    const std::vector<const Occluder*> all = all_but(occ, c.receiver, c.shooter);
    const double f_all = visible_form_factor(c.p, c.n, shooter, s.normal(), all);
    const double f_bvh = visible_form_factor(c.p, c.n, shooter, s.normal(), near);
    ASSERT_NEAR(f_bvh, f_all, 1e-12) << "receiver " << c.receiver << ", shooter " << c.shooter;
    if (f_all < 0.99 * lambert_form_factor(c.p, c.n, clip_to_horizon(c.p, c.n, shooter))) ++occluded;
    culled += static_cast<int>(all.size() - near.size());
  }
  EXPECT_GE(occluded, 150) << "the random cases should often be partly hidden";
  EXPECT_GT(culled, 1500 * 250) << "the shaft should drop most of the 298 occluders";
}

TEST(OccluderBvh, PolygonShaftGivesTheSameFormFactorsAndIsWithinTheBoxScan) {
  std::mt19937 rng(1992);
  const Scene scene = random_scene(rng, 200);
  const std::vector<Occluder> occ = make_occluders(scene);
  const OccluderBvh bvh(occ);
  for (const Case& c : random_cases(rng, scene, 300)) {
    const Surface& r = scene.surfaces[c.receiver];
    const Surface& s = scene.surfaces[c.shooter];
    const std::vector<const Occluder*> pair = bvh.between(r.polygon(), s.polygon(), c.receiver, c.shooter);
    const std::vector<const Occluder*> boxed = occluders_between(occ, r.corners, s.corners, c.receiver, c.shooter);
    for (const Occluder* o : pair)
      ASSERT_NE(std::find(boxed.begin(), boxed.end(), o), boxed.end()) << "beyond the common box";
    const ConvexPolygon shooter = polygon_of(s);
    for (int k = 0; k < 3; ++k) {  // points all over the receiver share the pair's shaft
      const Vec3 p = random_point(rng, r);
      if (s.normal().dot(p - s.corners[0]) <= 1e-3) continue;
      ASSERT_NEAR(visible_form_factor(p, c.n, shooter, s.normal(), pair),
                  visible_form_factor(p, c.n, shooter, s.normal(), all_but(occ, c.receiver, c.shooter)), 1e-12);
    }
  }
}

TEST(OccluderBvh, EveryCulledOccluderMissesEverySegmentToTheShooter) {
  std::mt19937 rng(1993);
  const Scene scene = random_scene(rng, 300);
  const std::vector<Occluder> occ = make_occluders(scene);
  const OccluderBvh bvh(occ);
  std::uniform_real_distribution<double> t(0, 1);
  int segments = 0, kept_hit = 0;
  for (const Case& c : random_cases(rng, scene, 200)) {
    const Surface& s = scene.surfaces[c.shooter];
    std::vector<const Occluder*> near;
    bvh.collect(Shaft({&c.p, 1}, s.polygon()), c.receiver, c.shooter, near);
    // Points of the shooter: its corners, its centre and random points.
    std::vector<Vec3> targets(s.polygon().begin(), s.polygon().end());
    targets.push_back(s.is_triangle() ? (s.corners[0] + s.corners[1] + s.corners[2]) / 3 : s.point(0.5, 0.5));
    for (int k = 0; k < 40; ++k) targets.push_back(random_point(rng, s));
    for (const Occluder& o : occ) {
      if (o.scene_surface == c.receiver || o.scene_surface == c.shooter) continue;
      const bool kept = std::find(near.begin(), near.end(), &o) != near.end();
      for (const Vec3& y : targets) {
        // The closed segment p..y, with a margin: a culled occluder must not even touch it.
        const bool hit = intersect_quad(scene.surfaces[o.scene_surface], c.p, y - c.p, -1e-9, 1 + 1e-9).has_value();
        if (!kept) {
          ++segments;
          ASSERT_FALSE(hit) << "culled occluder " << o.scene_surface << " blocks a segment from receiver "
                            << c.receiver << " to shooter " << c.shooter;
        } else if (hit) {
          ++kept_hit;
        }
      }
    }
  }
  EXPECT_GT(segments, 200 * 250 * 40) << "most occluders are culled, and all their segments were checked";
  EXPECT_GT(kept_hit, 100) << "the kept occluders do block segments: the test exercises shadows";
}

TEST(OccluderBvh, WidenedPointShaftHoldsTheSegmentsFromNearbyPoints) {
  // The progressive solver gathers at an element's centre and Gauss points through one shaft from
  // the centre widened by their reach: points within the margin see the same shadows.
  std::mt19937 rng(1994);
  const Scene scene = random_scene(rng, 300);
  const std::vector<Occluder> occ = make_occluders(scene);
  const OccluderBvh bvh(occ);
  std::uniform_real_distribution<double> unit(-1, 1);
  const double reach_m = 0.1;
  int segments = 0;
  for (const Case& c : random_cases(rng, scene, 300)) {
    const Surface& s = scene.surfaces[c.shooter];
    std::vector<const Occluder*> near;
    bvh.collect(Shaft({&c.p, 1}, s.polygon(), reach_m), c.receiver, c.shooter, near);
    const std::vector<const Occluder*> all = all_but(occ, c.receiver, c.shooter);
    for (int k = 0; k < 4; ++k) {
      Vec3 d(unit(rng), unit(rng), unit(rng));
      const Vec3 g = c.p + reach_m * d.normalized() * std::abs(unit(rng));  // within the reach
      if (s.normal().dot(g - s.corners[0]) <= 1e-3) continue;
      ASSERT_NEAR(visible_form_factor(g, c.n, polygon_of(s), s.normal(), near),
                  visible_form_factor(g, c.n, polygon_of(s), s.normal(), all), 1e-12);
      for (const Occluder& o : occ) {
        if (o.scene_surface == c.receiver || o.scene_surface == c.shooter) continue;
        if (std::find(near.begin(), near.end(), &o) != near.end()) continue;
        for (int q = 0; q < 10; ++q) {
          const Vec3 y = random_point(rng, s);
          ++segments;
          ASSERT_FALSE(intersect_quad(scene.surfaces[o.scene_surface], g, y - g, -1e-9, 1 + 1e-9).has_value());
        }
      }
    }
  }
  EXPECT_GT(segments, 300 * 4 * 200 * 10 / 2);
}

TEST(OccluderBvh, WallsThatOnlyTouchTheShaftAreCulledAndShadeNothing) {
  // A room's corner: the back wall shoots to points of the floor. The side wall meets both at
  // their edges, and a light sits in the ceiling's plane, which another ceiling panel shoots
  // from: every segment of either shaft stays on one closed side of these planes. A partition
  // standing across the room is kept.
  Scene scene;
  const auto quad = [&](const std::string& name, std::array<Vec3, 4> c) {
    Surface s;
    s.name = name;
    s.corners = c;
    scene.surfaces.push_back(s);
  };
  quad("back", {Vec3(0, 1, 0), Vec3(0, 1, 1), Vec3(1, 1, 1), Vec3(1, 1, 0)});          // faces -y
  quad("side", {Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(0, 1, 1), Vec3(0, 1, 0)});          // x = 0
  quad("light", {Vec3(0.4, 0.4, 1), Vec3(0.6, 0.4, 1), Vec3(0.6, 0.6, 1), Vec3(0.4, 0.6, 1)});
  quad("panel", {Vec3(0, 0, 1), Vec3(0, 0.3, 1), Vec3(1, 0.3, 1), Vec3(1, 0, 1)});     // faces -z
  quad("partition", {Vec3(0.5, 0.5, 0), Vec3(0.5, 0.5, 0.4), Vec3(0.5, 0.8, 0.4), Vec3(0.5, 0.8, 0)});
  const std::vector<Occluder> occ = make_occluders(scene);
  const OccluderBvh bvh(occ);
  constexpr size_t kFloor = 99;  // the receiver's surface: none of these
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(0.05, 0.95);
  int partition_kept = 0;
  for (int k = 0; k < 200; ++k) {
    const Vec3 p(U(rng), U(rng), 0), n = Vec3::UnitZ();
    const double reach_m = 0.02;  // a receiving element's Gauss points about p
    for (const size_t shooter : {size_t{0}, size_t{3}}) {
      const Surface& s = scene.surfaces[shooter];
      std::vector<const Occluder*> near;
      bvh.collect(Shaft({&p, 1}, s.polygon(), reach_m), kFloor, shooter, near);
      for (const Occluder* o : near) {
        EXPECT_NE(scene.surfaces[o->scene_surface].name, "side") << "at " << p.transpose();
        EXPECT_NE(scene.surfaces[o->scene_surface].name, "light") << "at " << p.transpose();
        partition_kept += scene.surfaces[o->scene_surface].name == "partition" ? 1 : 0;
      }
      // The culled walls shade nothing: the same form factor with every occluder.
      const std::vector<const Occluder*> all = all_but(occ, kFloor, shooter);
      EXPECT_NEAR(visible_form_factor(p, n, polygon_of(s), s.normal(), near),
                  visible_form_factor(p, n, polygon_of(s), s.normal(), all), 1e-15);
    }
  }
  EXPECT_GT(partition_kept, 20);
}

TEST(OccluderBvh, FewBlockersTakenAsTheyAreGiveTheSameShadows) {
  // The progressive solver's receivers take a side's few blockers (solver/progressive.cpp,
  // kFewBlockers), convex solids' faces among them, as they are instead of searching their own
  // widened shaft: the visible form factors of the patch and of its blocks, at the element's
  // centre and at points around it, one at a time and in the batched path of an element's Gauss
  // points, must agree to round-off (an extra volume that meets a block only loosely can change
  // the clipping's path), and whether each is seen in part exactly. Every third trial adds a box,
  // whose faces seen from the back hide nothing (ConvexSolid::face_hides_nothing()): closed and
  // floating, or open at the bottom and standing on the receiver; the side's list, with those
  // faces left out, is also checked against every occluder kept, no solid known (an
  // independent reference: no shafts, no faces left out).
  constexpr double kRoundOff = 1e-12;
  std::mt19937 rng(2026);
  // Element centres kept off the receiver's border by more than the points' offsets: the side's
  // shaft holds the segments from every point of the receiving surface, not from beyond it.
  std::uniform_real_distribution<double> pos(-0.6, 1.6), height(0.2, 1.8), size(0.1, 0.7), inner(0.05, 0.95),
      tilt(-0.4, 0.4);
  int compared = 0, shaded = 0, dropped = 0, equal = 0, solid_faces = 0, left_out = 0;
  double largest = 0;
  for (int trial = 0; trial < 60; ++trial) {
    Scene scene;
    scene.surfaces.push_back(testing_support::quad("receiver", {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, 0.5));
    scene.surfaces.push_back(testing_support::quad("shooter", {0, 0, 2}, {0, 1, 2}, {1, 1, 2}, {1, 0, 2}, 0.5));
    const int blockers = 1 + trial % 4;
    for (int k = 0; k < blockers; ++k) {
      const Vec3 c(pos(rng), pos(rng), height(rng));
      const Vec3 u = Vec3(size(rng), 0, tilt(rng) * 0.3), v = Vec3(0, size(rng), tilt(rng) * 0.3);
      scene.surfaces.push_back(testing_support::centred_polygon("b" + std::to_string(k), c, u, v, k % 2 == 1));
    }
    if (trial % 3 == 2) {
      std::uniform_real_distribution<double> within(0.0, 0.7);  // a box over the receiver, below the shooter
      const bool standing = trial % 2 == 0;
      const Vec3 lo(within(rng), within(rng), standing ? 0.0 : 0.2 + within(rng));
      const Vec3 extent(0.5 * size(rng), 0.5 * size(rng), size(rng));
      for (const Surface& f : testing_support::box_faces(lo, lo + extent))
        if (!standing || f.name != "-z") scene.surfaces.push_back(f);
    }
    const std::vector<Occluder> occ = make_occluders(scene);
    std::vector<Occluder> bare = occ;  // the same occluders, no solid known: every face kept
    for (Occluder& o : bare) o.solid = nullptr;
    const std::vector<const Occluder*> every = testing_support::all_but(bare, 0, 1);
    const OccluderBvh bvh(occ);
    const Surface& shooter = scene.surfaces[1];
    const std::vector<const Occluder*> side = bvh.between(shooter.polygon(), scene.surfaces[0].polygon(), 0, 1);
    for (const Occluder* o : side) solid_faces += o->solid != nullptr ? 1 : 0;
    std::vector<const Occluder*> side_bare;  // the side's list, no solid known
    for (const Occluder* o : side) side_bare.push_back(&bare[static_cast<size_t>(o - occ.data())]);
    // The patch and its quarters and sixteenths, as the shooter tree's blocks.
    std::vector<ConvexPolygon> blocks;
    for (const int n : {1, 2, 4})
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          const double u0 = double(i) / n, u1 = double(i + 1) / n, v0 = double(j) / n, v1 = double(j + 1) / n;
          ConvexPolygon b;
          for (const auto& [u, v] : {std::pair{u0, v0}, {u0, v1}, {u1, v1}, {u1, v0}}) b.push(Vec3(u, v, 2));
          blocks.push_back(b);
        }
    const Vec3 n(0, 0, 1);
    for (int k = 0; k < 20; ++k) {
      const Vec3 centre(inner(rng), inner(rng), 0);
      const double reach_m = 0.05;
      std::vector<const Occluder*> near;
      bvh.collect(Shaft({&centre, 1}, shooter.polygon(), reach_m), 0, 1, near);
      dropped += static_cast<int>(side.size() - near.size());
      const std::array<Vec3, 3> points{centre, Vec3(centre + Vec3(0.03, -0.02, 0)), Vec3(centre + Vec3(-0.035, 0.035, 0))};
      std::array<std::vector<ShadowVolume>, 3> from_side, from_shaft, from_every;
      for (size_t q = 0; q < points.size(); ++q) {
        shadow_volumes(points[q], n, side, from_side[q]);
        shadow_volumes(points[q], n, near, from_shaft[q]);
        shadow_volumes(points[q], n, every, from_every[q]);
        std::vector<ShadowVolume> kept;
        shadow_volumes(points[q], n, side_bare, kept);
        left_out += static_cast<int>(kept.size() - from_side[q].size());
      }
      const std::array<std::span<const ShadowVolume>, 3> side_spans{from_side[0], from_side[1], from_side[2]},
          shaft_spans{from_shaft[0], from_shaft[1], from_shaft[2]};
      for (const ConvexPolygon& b : blocks) {
        std::array<double, 3> batch_side, batch_shaft;
        visible_form_factors_past(points, n, b, -Vec3::UnitZ(), side_spans, batch_side);
        visible_form_factors_past(points, n, b, -Vec3::UnitZ(), shaft_spans, batch_shaft);
        for (size_t q = 0; q < points.size(); ++q) {
          bool partly_side = false, partly_shaft = false;
          const double f_side = visible_form_factor_past(points[q], n, b, -Vec3::UnitZ(), from_side[q], &partly_side);
          const double f_shaft = visible_form_factor_past(points[q], n, b, -Vec3::UnitZ(), from_shaft[q], &partly_shaft);
          ASSERT_NEAR(f_side, f_shaft, kRoundOff) << "trial " << trial << ", point " << points[q].transpose();
          ASSERT_NEAR(batch_side[q], batch_shaft[q], kRoundOff) << "trial " << trial << ", batched";
          ASSERT_NEAR(batch_side[q], f_side, kRoundOff) << "trial " << trial << ", batched against one at a time";
          ASSERT_EQ(partly_side, partly_shaft) << "trial " << trial;
          ASSERT_NEAR(f_side, visible_form_factor_past(points[q], n, b, -Vec3::UnitZ(), from_every[q]), kRoundOff)
              << "trial " << trial << ", against every occluder kept";
          largest = std::max({largest, std::abs(f_side - f_shaft), std::abs(batch_side[q] - batch_shaft[q])});
          equal += f_side == f_shaft && batch_side[q] == batch_shaft[q];
          ++compared;
          shaded += partly_shaft;
        }
      }
    }
  }
  std::printf("%d points' form factors compared (%d seen in part), %d equal bit for bit, largest difference %.1e; "
              "%d blockers off an element's shaft; %d solids' faces among the sides' blockers, %d volumes left out\n",
              compared, shaded, equal, largest, dropped, solid_faces, left_out);
  EXPECT_GT(shaded, compared / 10) << "the blockers should often shade the blocks";
  EXPECT_GT(dropped, 100) << "the elements' shafts should often drop some of the side's blockers";
  EXPECT_GT(solid_faces, 40) << "the boxes' faces should often stand between the surfaces";
  EXPECT_GT(left_out, 100) << "the boxes' faces seen from the back should often be left out";
}

TEST(OccluderBvh, EmptyAndSingleOccluderScenes) {
  const std::vector<Occluder> none;
  const OccluderBvh empty(none);
  const Vec3 p(0, 0, 0);
  const std::array<Vec3, 4> quad = {Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 1, 1), Vec3(0, 1, 1)};
  std::vector<const Occluder*> out;
  empty.collect(Shaft({&p, 1}, quad), 0, 0, out);
  EXPECT_TRUE(out.empty());

  Scene scene;
  Surface blocker;
  blocker.name = "blocker";
  blocker.corners = {Vec3(0.4, 0.4, 0.5), Vec3(0.6, 0.4, 0.5), Vec3(0.6, 0.6, 0.5), Vec3(0.4, 0.6, 0.5)};
  scene.surfaces.push_back(blocker);
  const std::vector<Occluder> one = make_occluders(scene);
  const OccluderBvh bvh(one);
  const Vec3 under(0.5, 0.5, 0), aside(3, 0.5, 0);
  bvh.collect(Shaft({&under, 1}, quad), 7, 8, out);
  EXPECT_EQ(out.size(), 1u) << "the blocker stands in the shaft from the point below it";
  out.clear();
  bvh.collect(Shaft({&aside, 1}, quad), 7, 8, out);
  EXPECT_TRUE(out.empty()) << "the shaft from (3, 0.5, 0) to the quad passes beside the blocker";
  bvh.collect(Shaft({&under, 1}, quad), 0, 8, out);
  EXPECT_TRUE(out.empty()) << "the receiver's and shooter's own surfaces are skipped";
}

}  // namespace bvh_test
}  // namespace radrecon
