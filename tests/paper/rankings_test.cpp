// Rankings against the paper's: ranks with ties and gaps, Spearman's rho against hand-computed
// values, the best entry of a column, and the paragraph's claims.

#include "paper/rankings.h"

#include <gtest/gtest.h>

#include <cmath>

namespace radrecon {
namespace rankings_test {

const double kNan = std::nan("");

TEST(Rankings, RanksShareTiesSkipTheNextAndLeaveNanUnranked) {
  EXPECT_EQ(ranks_ascending({3, 1, 2, kNan, 1}), (std::vector<int>{4, 1, 3, 0, 1}));
  EXPECT_EQ(ranks_ascending({}), std::vector<int>{});
}

TEST(Rankings, SpearmanMatchesHandComputedValues) {
  // Without ties rho = 1 - 6 sum d^2 / (n (n^2 - 1)): ranks (1,2,3,4) against (2,1,4,3) give
  // sum d^2 = 4 and rho = 1 - 24 / 60 = 0.6.
  std::vector<RankedMethod> table = {{"a", {1, 0, 0}, {2, 1, 1}},
                                     {"b", {2, 0, 0}, {1, 1, 1}},
                                     {"c", {3, 0, 0}, {4, 1, 1}},
                                     {"d", {4, 0, 0}, {3, 1, 1}},
                                     {"not in the paper", {0.5, 0, 0}, {kNan, kNan, kNan}}};
  const RankingComparison c = compare_rankings(table, 0);
  EXPECT_EQ(c.methods, (std::vector<std::string>{"a", "b", "c", "d"}));
  EXPECT_EQ(c.ours, (std::vector<int>{1, 2, 3, 4}));
  EXPECT_EQ(c.paper, (std::vector<int>{2, 1, 4, 3}));
  EXPECT_NEAR(c.spearman, 0.6, 1e-15);
  // The same order gives 1, the reverse -1.
  for (RankedMethod& m : table) m.paper[0] = m.ours[0];
  table.back().paper[0] = kNan;
  EXPECT_NEAR(compare_rankings(table, 0).spearman, 1.0, 1e-15);
  for (RankedMethod& m : table) m.paper[0] = 10 - m.ours[0];
  table.back().paper[0] = kNan;
  EXPECT_NEAR(compare_rankings(table, 0).spearman, -1.0, 1e-15);
}

TEST(Rankings, SpearmanGivesTiesTheMeanOfTheRanksTheySpan) {
  // The paper's three Linf values tied at 0.329 (an outside-in trial): mid-ranks (1, 3, 3, 3, 5)
  // against (1, 2, 3, 4, 5), as scipy.stats.spearmanr ranks them: cov 8, variances 10 and 8,
  // rho = 8 / sqrt(80) = 2 / sqrt(5). The shown ranks keep the better rank (1, 2, 2, 2, 5).
  const std::vector<RankedMethod> table = {{"a", {1, 0, 0}, {0.3, 1, 1}},
                                           {"b", {2, 0, 0}, {0.329, 1, 1}},
                                           {"c", {3, 0, 0}, {0.329, 1, 1}},
                                           {"d", {4, 0, 0}, {0.329, 1, 1}},
                                           {"e", {5, 0, 0}, {0.5, 1, 1}}};
  const RankingComparison c = compare_rankings(table, 0);
  EXPECT_EQ(c.paper, (std::vector<int>{1, 2, 2, 2, 5}));
  EXPECT_NEAR(c.spearman, 2 / std::sqrt(5.0), 1e-15);
  // A method without a figure of ours is left out of rho (it would have ranked first): the other
  // four, (1, 2, 3, 4) against mid-ranks (1, 3, 3, 3): cov 3, variances 5 and 3, rho = 3 / sqrt(15).
  std::vector<RankedMethod> missing = table;
  missing[4].ours[0] = kNan;
  EXPECT_NEAR(compare_rankings(missing, 0).spearman, 3 / std::sqrt(15.0), 1e-15);
}

TEST(Rankings, BestIndexSkipsNanAndKnowsWhichEndIsBest) {
  EXPECT_EQ(best_index({0.3, kNan, 0.1, 0.2}), 2);
  EXPECT_EQ(best_index({0.3, kNan, 0.1, 0.2}, true), 0);
  EXPECT_EQ(best_index({kNan, kNan}), -1);
}

TEST(Rankings, ParagraphNamesTheBestOfEachAndTheSamePlaces) {
  // L1: the paper ranks x, y, z; we rank y, x, z (z in the same place). L2: both x, y, z.
  const std::vector<RankedMethod> table = {{"x", {0.2, 0.1, kNan}, {0.1, 0.1, kNan}},
                                           {"y", {0.1, 0.2, kNan}, {0.2, 0.2, kNan}},
                                           {"z", {0.3, 0.3, kNan}, {0.3, 0.3, kNan}}};
  const std::string text = ranking_paragraph("Table 9", table);
  EXPECT_NE(text.find("L1: the paper ranks x best, we rank y best; the same place in both: z"), std::string::npos) << text;
  EXPECT_NE(text.find("L2: both rank x best; every method has the same place in both"), std::string::npos) << text;
  EXPECT_EQ(text.find("Linf"), std::string::npos) << "no norm without paper entries: " << text;
  EXPECT_NE(ranking_paragraph("Table 9", {{"x", {1, 1, 1}, {kNan, kNan, kNan}}}).find("no methods that the paper ranks"),
            std::string::npos);
}

}  // namespace rankings_test
}  // namespace radrecon
