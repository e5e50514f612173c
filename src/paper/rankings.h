#pragma once
// Rankings of reconstruction methods by an error norm: ours beside the paper's published ones,
// the best entry of each table column, and a paragraph, generated from the numbers, on where the
// two rankings agree and differ (the report's "honest tables", issue 15).

#include <array>
#include <string>
#include <vector>

namespace radrecon {

/// One method's entries in a table: its name, our norms (L1, L2, Linf) and the paper's (NaN
/// where the paper has none).
struct RankedMethod {
  std::string name;
  std::array<double, 3> ours, paper;
};

/// The names of the norms ranked, in order: "L1", "L2", "Linf".
inline constexpr std::array<const char*, 3> kRankedNorms = {"L1", "L2", "Linf"};

/// 1-based ranks of `values` (smallest first; a tie shares the better rank, the next rank skips:
/// 1, 1, 3). NaN ranks last (after every number) and gets rank 0 ("no rank").
std::vector<int> ranks_ascending(const std::vector<double>& values);

/// The comparison of the two rankings of one norm over the methods both rank.
struct RankingComparison {
  std::vector<std::string> methods;  ///< the methods that have a paper entry, in the table's order
  std::vector<int> ours, paper;      ///< their ranks among themselves, 1 = smallest error
  /// Spearman's rank correlation of the two rankings, in [-1, 1]; NaN for fewer than 2 methods.
  double spearman = 0;
};

/// Our ranking and the paper's of norm `norm` (0: L1, 1: L2, 2: Linf) over the methods with a
/// paper entry.
RankingComparison compare_rankings(const std::vector<RankedMethod>& table, int norm);

/// Index of the best (smallest, or largest if `larger_is_better`) finite value; -1 if none.
int best_index(const std::vector<double>& values, bool larger_is_better = false);

/// One paragraph (plain text) on where our ranking and the paper's agree and differ for each norm
/// of `table` (named `table_name`, e.g. "Table 1"): the best method of each, the methods in the
/// same place, the rank correlation.
std::string ranking_paragraph(const std::string& table_name, const std::vector<RankedMethod>& table);

/// The known reasons the values and rankings differ from the paper's, in words, for a reference
/// solution on a grid of `reference_grid` ("400 x 400") elements on the ground.
std::string ranking_reasons(const std::string& reference_grid);

}  // namespace radrecon
