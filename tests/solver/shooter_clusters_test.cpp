// Clusters of small shooters (solver/shooter_clusters.h) against independent answers: a light
// made of hundreds of triangles against the closed form of the whole rectangle, an occluder's
// shadow against exact visibility (the same scene solved with every triangle shooting alone),
// a closed room of triangles against its energy balance, shadow rays against the ray caster of
// tests/support, and the same bits on any number of threads.

#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "mesh/grid_mesh.h"
#include "solver/bvh.h"
#include "solver/closed_room.h"
#include "solver/progressive.h"
#include "solver/shooter_clusters.h"
#include "support/closed_forms.h"
#include "support/ray_scene.h"
#include "support/scenes.h"
#include "support/threads.h"

namespace radrecon {
namespace shooter_clusters_test {

using testing_support::quad;

/// The quad c0 c1 c2 c3 cut into k x k cells, each into two triangles: surfaces NAME.i.j.a/b.
void add_tessellated(Scene& scene, const std::string& name, const Vec3& c0, const Vec3& c1, const Vec3& c2,
                     const Vec3& c3, int k, double rho, double emission = 0) {
  const auto at = [&](int i, int j) {
    const double u = static_cast<double>(i) / k, v = static_cast<double>(j) / k;
    return Vec3((1 - u) * (1 - v) * c0 + u * (1 - v) * c1 + u * v * c2 + (1 - u) * v * c3);
  };
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i) {
      Surface a = quad(name + "." + std::to_string(i) + "." + std::to_string(j) + ".a", c0, c1, c2, c3, rho, emission);
      Surface b = a;
      b.name.back() = 'b';
      a.set_triangle(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      b.set_triangle(at(i, j), at(i + 1, j + 1), at(i, j + 1));
      scene.surfaces.push_back(a);
      scene.surfaces.push_back(b);
    }
}

/// A 4 x 4 m floor (reflectance 0.5) under a 1 x 1 m light at 1.5 m, facing down, of 2 x 12 x 12
/// triangles emitting 40 W/m^2; with `occluder`, a black 0.6 x 0.6 m square half way down, or
/// with `shade`, a black 0.9 x 0.9 m square of 2 x 9 x 9 triangles 0.3 m under the light, each
/// one element: in the light's clusters.
Scene light_of_triangles(bool occluder, bool shade = false) {
  Scene scene;
  scene.name = "triangle-light";
  scene.surfaces.push_back(quad("floor", {0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, 0.5));
  add_tessellated(scene, "light", {1.5, 1.5, 1.5}, {1.5, 2.5, 1.5}, {2.5, 2.5, 1.5}, {2.5, 1.5, 1.5}, 12, 0.0, 40.0);
  if (occluder) scene.surfaces.push_back(quad("occluder", {1.7, 1.7, 0.75}, {2.3, 1.7, 0.75}, {2.3, 2.3, 0.75}, {1.7, 2.3, 0.75}, 0.0));
  if (shade) add_tessellated(scene, "shade", {1.55, 1.55, 1.2}, {2.45, 1.55, 1.2}, {2.45, 2.45, 1.2}, {1.55, 2.45, 1.2}, 9, 0.0);
  return scene;
}

constexpr int kDivisions = 40;  // 0.1 m elements: the floor 40 x 40, each light triangle one

Solution solve(const Scene& scene, bool clusters, double residual = 1e-6) {
  ProgressiveOptions po;
  po.residual = residual;
  po.clusters = clusters;
  return solve_progressive(scene, make_grid_mesh(scene, {kDivisions, 2}), po, "grid:" + std::to_string(kDivisions));
}

TEST(ShooterClusters, OnlyManySingleElementSidesAreClustered) {
  const Scene scene = light_of_triangles(false);
  const Mesh mesh = make_grid_mesh(scene, {kDivisions, 2});
  const ShooterClusters clusters = make_shooter_clusters(mesh);
  ASSERT_FALSE(clusters.empty());
  // Every light triangle in exactly one cluster, of at most kClusterMembers; the floor in none.
  std::vector<int> seen(mesh.surfaces.size(), 0);
  for (const int root : clusters.roots) {
    const ShooterClusters::Node& node = clusters.nodes[static_cast<size_t>(root)];
    EXPECT_LE(node.end - node.begin, kClusterMembers);
    for (int m = node.begin; m < node.end; ++m) ++seen[clusters.sides[static_cast<size_t>(m)]];
  }
  for (size_t s = 0; s < mesh.surfaces.size(); ++s) {
    EXPECT_EQ(seen[s], mesh.surfaces[s].elements.size() == 1 ? 1 : 0) << mesh.surfaces[s].name;
    EXPECT_EQ(clusters.cluster_of_side[s] >= 0, seen[s] == 1) << mesh.surfaces[s].name;
  }
  // Every node's radius holds its members' corners.
  for (const ShooterClusters::Node& node : clusters.nodes)
    for (int m = node.begin; m < node.end; ++m)
      for (const Vec3& c : mesh.surfaces[clusters.sides[static_cast<size_t>(m)]].elements[0].corners)
        EXPECT_LE((c - node.center).norm(), node.radius_m * (1 + 1e-12));
  // A handful of small surfaces shoot alone, as they always did.
  Scene few;
  few.surfaces.push_back(quad("floor", {0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}, 0.5));
  add_tessellated(few, "light", {1.5, 1.5, 1.5}, {1.5, 2.5, 1.5}, {2.5, 2.5, 1.5}, {2.5, 1.5, 1.5}, 4, 0.0, 40.0);
  EXPECT_TRUE(make_shooter_clusters(make_grid_mesh(few, {kDivisions, 2})).empty());
}

TEST(ShooterClusters, LightOfTrianglesMatchesTheClosedFormOfTheRectangle) {
  // The floor sees the whole light: its radiosity is rho E F(point -> the 1 x 1 m rectangle).
  // The elements right under the light gather from its near triangles exactly, the others from
  // point kernels: both within the midpoint rule's error, well inside the 1e-3.
  const Solution sol = solve(light_of_triangles(false), true);
  const SurfaceSolution* floor = sol.find("floor");
  ASSERT_NE(floor, nullptr);
  double worst = 0;
  for (const SolutionElement& e : floor->elements) {
    const double expected =
        0.5 * 40.0 * testing_support::floor_to_rectangle(e.center.x(), e.center.y(), 1.5, 1.5, 2.5, 2.5, 1.5);
    worst = std::max(worst, std::abs(e.radiosity_w_m2[0] / expected - 1));
    ASSERT_NEAR(e.radiosity_w_m2[0], expected, 1e-3 * expected) << "at " << e.center.transpose();
  }
  std::printf("light of 288 triangles in clusters: floor radiosity against the closed form, largest error %.2e\n",
              worst);
  // No shot delivers more than it shoots (a kernel that overestimated would), and all was shot.
  EXPECT_GE(sol.stats.escaped_w[0], 0);
  EXPECT_LT(sol.stats.unshot_w[0], 1e-6 * sol.stats.emitted_w[0]);
}

/// The floor of `scene` solved with clusters against every triangle shooting alone with exact
/// shadows (the reference): the exact umbra dark, the elements that see the whole light (at
/// least `least_lit` of them) within 1e-3, and the floor's total (its penumbra drawn by the
/// subtrees' shadow rays) within `total_relative`.
void expect_shadow_as_exact_visibility(const Scene& scene, const char* what, int least_lit, double total_relative) {
  const Solution clustered = solve(scene, true), exact = solve(scene, false);
  const SurfaceSolution *a = clustered.find("floor"), *b = exact.find("floor");
  ASSERT_TRUE(a != nullptr && b != nullptr);
  ASSERT_EQ(a->elements.size(), b->elements.size());
  double sum_a = 0, sum_b = 0, worst_lit = 0;
  int umbra = 0, lit = 0;
  for (size_t e = 0; e < a->elements.size(); ++e) {
    const Vec3& p = a->elements[e].center;
    const double unoccluded = 0.5 * 40.0 * testing_support::floor_to_rectangle(p.x(), p.y(), 1.5, 1.5, 2.5, 2.5, 1.5);
    const double got = a->elements[e].radiosity_w_m2[0], want = b->elements[e].radiosity_w_m2[0];
    sum_a += got;
    sum_b += want;
    if (want == 0) {  // the exact umbra: the clusters' too
      ++umbra;
      EXPECT_EQ(got, 0) << "at " << p.transpose();
    } else if (want >= (1 - 1e-9) * unoccluded) {  // sees all of the light
      ++lit;
      worst_lit = std::max(worst_lit, std::abs(got / want - 1));
      EXPECT_NEAR(got, want, 1e-3 * want) << "at " << p.transpose();
    }
  }
  EXPECT_GE(umbra, 4) << what;
  EXPECT_GE(lit, least_lit) << what;
  EXPECT_NEAR(sum_a, sum_b, total_relative * sum_b) << what;
  std::printf("%s: %d umbra elements dark, %d lit within %.2e, floor total %+.2e against exact visibility\n",
              what, umbra, lit, worst_lit, sum_a / sum_b - 1);
}

TEST(ShooterClusters, ShadowMatchesExactVisibilityOutsideThePenumbra) {
  expect_shadow_as_exact_visibility(light_of_triangles(true), "square half way down", 1000, 2e-3);
}

TEST(ShooterClusters, TrianglesOfTheSameClusterCastTheirShadows) {
  // A shade of triangles under the light of triangles: both in the same clusters. Far from a
  // subtree, the cluster's other members hide it as any surface does: the umbra stays dark (it
  // was lit when a cluster's members were passed over by its shadow rays). No floor element
  // sees all of the light; its penumbra, slivers of the light seen past the shade's edges, is
  // drawn by the subtrees' rays to their centres (measured +8.3% on the floor's total): an
  // occluder this near a light is where clusters cost accuracy (docs/method.md).
  const Scene scene = light_of_triangles(false, true);
  const Mesh mesh = make_grid_mesh(scene, {kDivisions, 2});
  const ShooterClusters clusters = make_shooter_clusters(mesh);
  for (const int root : clusters.roots) {
    const ShooterClusters::Node& node = clusters.nodes[static_cast<size_t>(root)];
    bool light = false, shade = false;
    for (int m = node.begin; m < node.end; ++m) {
      const std::string& name = mesh.surfaces[clusters.sides[static_cast<size_t>(m)]].name;
      light = light || name.starts_with("light");
      shade = shade || name.starts_with("shade");
    }
    EXPECT_TRUE(light && shade) << "a cluster should hold both";
  }
  // The bound: the measured 8.3% and half as much again, so that a change that doubles the
  // clusters' error here fails (0.5 had let six times it pass).
  expect_shadow_as_exact_visibility(scene, "shade in the light's clusters", 0, 0.125);
}

TEST(ShooterClusters, SlowClosedRoomOfTrianglesKeepsItsEnergy) {
  // The closed room of progressive_test, every quad cut into 2 x 6 x 6 triangles: 648 sides of
  // one element each. Absorbed = emitted as in the quads' room.
  const double E = 40, phi = E * testing_support::kClosedRoomLight_m2;
  for (const double rho : {0.5, 0.95}) {
    const Scene quads = testing_support::closed_room(rho, E);
    Scene room;
    room.name = "room-of-triangles";
    for (const Surface& s : quads.surfaces)
      add_tessellated(room, s.name, s.corners[0], s.corners[1], s.corners[2], s.corners[3], 6, rho,
                      s.emission_w_m2[0]);
    ProgressiveOptions po;
    po.residual = 1e-5;
    const Solution sol = solve_progressive(room, make_grid_mesh(room, {1, 2}), po, "grid:1");
    ASSERT_TRUE(sol.stats.converged);
    ASSERT_EQ(sol.stats.elements, room.surfaces.size());
    EXPECT_NEAR(sol.stats.emitted_w[0], phi, 1e-12 * phi);
    EXPECT_NEAR(sol.stats.absorbed_w[0], phi, 1e-3 * phi) << "rho = " << rho;
    std::printf("closed room of triangles in clusters, rho %.2f: absorbed / emitted - 1 = %.2e\n", rho,
                sol.stats.absorbed_w[0] / phi - 1);
  }
}

TEST(ShooterClusters, ResultDoesNotDependOnThreadCount) {
  const Scene scene = light_of_triangles(true);
  const auto [one, many] = testing_support::solved_on_one_and_many_threads([&] { return solve(scene, true, 1e-4); });
  testing_support::expect_same_bits(one, many);
}

TEST(ShooterClusters, ShadowRaysAgreeWithTheRayCaster) {
  // Random polygons, random segments: blocks_segment() against the independent ray caster of
  // tests/support, with no occluder skipped and nothing ignored near the end.
  std::mt19937 rng(20261206);
  std::uniform_real_distribution<double> pos(0, 6), size(0.2, 1.5), unit(-1, 1);
  Scene scene;
  for (int k = 0; k < 120; ++k) {
    const Vec3 c(pos(rng), pos(rng), pos(rng));
    Vec3 u(unit(rng), unit(rng), unit(rng)), w(unit(rng), unit(rng), unit(rng));
    u = u.normalized() * size(rng) / 2;
    w = (w - w.dot(u) / u.squaredNorm() * u).normalized() * size(rng) / 2;
    scene.surfaces.push_back(testing_support::centred_polygon("s" + std::to_string(k), c, u, w, k % 3 == 2));
  }
  const std::vector<Occluder> occluders = make_occluders(scene);
  const OccluderBvh bvh(occluders);
  const size_t none = scene.surfaces.size();
  int blocked = 0;
  for (int k = 0; k < 4000; ++k) {
    const Vec3 p(pos(rng), pos(rng), pos(rng)), q(pos(rng), pos(rng), pos(rng));
    const bool expected = !testing_support::visible(scene, p, q, none, none);
    ASSERT_EQ(bvh.blocks_segment(p, q, 0, none, {}), expected) << k;
    blocked += expected;
  }
  EXPECT_GT(blocked, 400);
  EXPECT_LT(blocked, 3600);
  // Crossings within `ignore_m` of the end passed over: the segment shortened by as much; a
  // surface skipped: the ray caster skips it too.
  for (int k = 0; k < 2000; ++k) {
    const Vec3 p(pos(rng), pos(rng), pos(rng)), q(pos(rng), pos(rng), pos(rng));
    const double ignore_m = 0.5 * (q - p).norm() * std::uniform_real_distribution<double>(0, 1)(rng);
    const size_t skip = static_cast<size_t>(k) % scene.surfaces.size();
    const Vec3 end = q - ignore_m * (q - p).normalized();
    ASSERT_EQ(bvh.blocks_segment(p, q, ignore_m, skip, {}), !testing_support::visible(scene, p, end, skip, none)) << k;
  }
}

}  // namespace shooter_clusters_test
}  // namespace radrecon
