// The objectives of the lobe search: how many entries of A_l = Y_l^-1 vanish for a lobe set
// (sparsity), or how many multiplies it costs as emitted (operations), with the conditioning
// bound and tie-breaks that decide between equal sets.
#pragma once

#include <functional>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "zhf/candidates/candidates.h"
#include "zhf/candidates/limits.h"
#include "zhf/runtime/lobe_table.h"
#include "zhf/tolerances/tolerances.h"

namespace zhf::optimizer {

// The default bound on each band's condition number (--max-condition).
inline constexpr double kDefaultMaxCondition = 50;

// One candidate index per lobe: lobe d of band l is genes[runtime::lobe_index(l, d, sharing)].
using Genome = std::vector<int>;

struct Fitness {
  bool invertible = false;    // every Y_l has condition <= tolerance::kSingularCondition
  bool feasible = false;      // ... and <= the bound
  int zeros = 0;              // summed over bands 2..N-1
  double worst_condition = 0;
  int multiplies = 0;         // see Scoring::lobe_set_multiplies
};

// What a search ranks first after the condition bound.
enum class Ranking {
  kMostZeros,        // sparsity: more zeros, then lower worst condition, then fewer multiplies
  kFewestMultiplies  // operations: fewer multiplies, then more zeros, then lower worst condition
};

// Strict order: feasible first, then the ranking's keys. Between two sets outside the condition
// bound, the lower worst condition wins.
bool better(const Fitness& a, const Fitness& b, Ranking ranking);

// A model of z = A^T f's multiplies: one per distinct nonzero magnitude in each column of A
// (equal magnitudes share a multiply after adding or subtracting their inputs). The code
// generator's count (codegen::lobe_weight_multiplies) is exact and at most this: it also shares
// sums that recur across columns.
int multiply_cost(const Eigen::MatrixXd& inverse);

struct Scoring {
  Ranking ranking = Ranking::kMostZeros;
  // A lobe set's multiplies, given as its table (lobes, each band's A_l with its exact zeros and
  // condition; no provenance); must be safe to call from several threads at once. Unset: the sum
  // of multiply_cost over the bands. zhf's pipeline passes the code generator's count of the lobe
  // rotation's multiplies that depend on the lobe set for the operations objective.
  std::function<int(const runtime::LobeTable& table)> lobe_set_multiplies;
};

struct BandAnalysis {
  int l = 0;
  std::vector<int> lobes;     // positions in the lobe list
  Eigen::MatrixXd y;          // Y_l[d][m+l]
  Eigen::MatrixXd inverse;    // A_l, rows m+l, columns d; structural zeros exact
  int zeros = 0;
  double condition = 0;       // 2-norm, from the SVD
};

class LobeEvaluator {
 public:
  // Candidates' SH values are tabulated up front when they fit in max_tabulated_values doubles,
  // else evaluated on demand (same results, slower).
  LobeEvaluator(const candidates::CandidateSet& set, bool lobe_sharing, double max_condition, Scoring scoring = {},
                size_t max_tabulated_values = candidates::kMaxTabulatedValues);

  int order() const { return order_; }
  bool lobe_sharing() const { return lobe_sharing_; }
  int genes() const { return runtime::lobe_count(order_, lobe_sharing_); }
  double max_condition() const { return max_condition_; }
  Ranking ranking() const { return scoring_.ranking; }
  // better() under this evaluator's ranking.
  bool better(const Fitness& a, const Fitness& b) const { return optimizer::better(a, b, scoring_.ranking); }
  const candidates::CandidateSet& candidates() const { return candidates_; }

  // Fast path for the search: eigenvalues of Y^T Y for the condition, LU for the inverse.
  Fitness evaluate(const Genome& genes) const;
  // Slow path for tables and tests: SVD condition, exact zeros.
  std::vector<BandAnalysis> analyze(const Genome& genes) const;
  Fitness fitness_of(const Genome& genes, const std::vector<BandAnalysis>& bands) const;

 private:
  Eigen::MatrixXd band_matrix(const Genome& genes, int l) const;
  // Scoring's count for the set: the bands' A_l and conditions as analysed.
  int multiplies(const Genome& genes, const std::vector<BandAnalysis>& bands) const;

  const candidates::CandidateSet& candidates_;
  int order_;
  bool lobe_sharing_;
  double max_condition_;
  Scoring scoring_;
  std::vector<double> sh_;  // y at every candidate: sh_[c * N^2 + index(l, m)]; empty: on demand
};

// The table of a lobe set: the lobes' angles, directions and sources, each band's A_l with its
// exact zeros and condition, and the provenance given (an object).
runtime::Matrix to_matrix(const Eigen::MatrixXd& m);
runtime::LobeTable make_table(const LobeEvaluator& evaluator, const Genome& genes, const nlohmann::json& provenance);

// Exact zeros: entries at or below tolerance::kZeroRelative * max|A| set to 0; returns their count.
int zero_small_entries(Eigen::MatrixXd& inverse);

}  // namespace zhf::optimizer
