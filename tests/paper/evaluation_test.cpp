// The paper's evaluation pipeline (evaluation_grid, prepare_data_set, evaluate_method) against
// brute force: the reference judged against itself has no error and an SSIM of 1, and a coarse
// grid's piecewise-constant reconstruction has the norms computed here cell by cell from the two
// solutions, looking up each evaluation point's coarse cell by a scan.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "paper/data_sets.h"
#include "paper/evaluation.h"
#include "solver/solve.h"
#include "support/temp_dir.h"

namespace radrecon {
namespace evaluation_test {

using testing_support::TempDir;

TEST(PaperEvaluation, TheReferenceHasNoErrorAndACoarseGridTheBruteForceNorms) {
  const Scene scene = paper_scene();
  const Solution reference = solve_scene(scene, "grid:40", SolveSettings{}, "test");
  const Solution coarse = solve_scene(scene, "grid:8", SolveSettings{}, "test");
  const EvaluationGrid at = evaluation_grid(reference);
  ASSERT_EQ(at.points.size(), 40u * 40u);
  TempDir figures("evaluation");
  const SideSampling plain{.barriers = false};

  const MethodResult self =
      evaluate_method(prepare_data_set(reference, at, plain), Method::constant, at, MethodParams{}, figures.path(), "self");
  EXPECT_EQ(self.figures.norms.l1, 0.0);
  EXPECT_EQ(self.figures.norms.l2, 0.0);
  EXPECT_EQ(self.figures.norms.linf, 0.0);
  ASSERT_TRUE(self.figures.ssim.has_value());
  EXPECT_NEAR(*self.figures.ssim, 1.0, 1e-12);
  ASSERT_TRUE(self.figures.gradient_l2.has_value());
  EXPECT_EQ(*self.figures.gradient_l2, 0.0);

  // The coarse ground's 8 x 8 cells of 0.5 m, the evaluation points at the 0.1 m cells' centres
  // (never on a coarse cell's edge): each point's value is its coarse cell's.
  const SurfaceSolution& ground = *coarse.find("ground");
  ASSERT_EQ(ground.elements.size(), 64u);
  double sum = 0, sum_sq = 0, largest = 0;
  for (size_t k = 0; k < at.points.size(); ++k) {
    const double u = at.points[k].x() / ground.length_u_m, v = at.points[k].y() / ground.length_v_m;
    const auto cell = std::find_if(ground.elements.begin(), ground.elements.end(), [&](const SolutionElement& e) {
      return e.u0 <= u && u < e.u1 && e.v0 <= v && v < e.v1;
    });
    ASSERT_NE(cell, ground.elements.end()) << "no coarse cell holds point " << k;
    for (int c = 0; c < 3; ++c) {
      const double e = cell->radiosity_w_m2[c] - at.reference_w_m2[3 * k + static_cast<size_t>(c)];
      sum += std::abs(e), sum_sq += e * e, largest = std::max(largest, std::abs(e));
    }
  }
  const double count = 3.0 * static_cast<double>(at.points.size());
  const MethodResult constant =
      evaluate_method(prepare_data_set(coarse, at, plain), Method::constant, at, MethodParams{}, figures.path(), "coarse");
  EXPECT_NEAR(constant.figures.norms.l1, sum / count, 1e-12 * sum / count);
  EXPECT_NEAR(constant.figures.norms.l2, sum_sq / count, 1e-12 * sum_sq / count);
  EXPECT_NEAR(constant.figures.norms.linf, largest, 1e-12 * largest);
  EXPECT_GT(largest, 0.01);  // the coarse grid is visibly coarse: the test can tell
  ASSERT_TRUE(constant.figures.ssim.has_value());
  EXPECT_LT(*constant.figures.ssim, 1.0);
}

}  // namespace evaluation_test
}  // namespace radrecon
