// The sparsity objective: how many entries of A_l = Y_l^-1 vanish for a lobe set, with the
// conditioning bound and tie-breaks that decide between equally sparse sets.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "zhf/candidates/candidates.h"

namespace zhf::optimizer {

// An entry of A_l is a structural zero when |a| <= kZeroRelative * max|A_l|; it is then
// stored as an exact 0.
inline constexpr double kZeroRelative = 1e-10;
inline constexpr double kDefaultMaxCondition = 50;
// Beyond this a lobe matrix is treated as singular: zero detection at 1e-10 is meaningless
// once rounding (condition x 1e-16) reaches it.
inline constexpr double kSingularCondition = 1e6;

// Lobe d of band l is genes[lobe_index(l, d)]: with sharing band l uses lobes 0..2l of one
// list of 2N-1; without, each band has its own 2l+1 lobes (N^2 - 4 in all).
int lobe_count(int order, bool lobe_sharing);
int lobe_index(int l, int d, bool lobe_sharing);

using Genome = std::vector<int>;  // one candidate index per lobe

struct Fitness {
  bool invertible = false;    // every Y_l has condition <= kSingularCondition
  bool feasible = false;      // ... and <= the bound
  int zeros = 0;              // summed over bands 2..N-1
  double worst_condition = 0;
  int multiplies = 0;         // cost model: see multiply_cost()
};

// Strict order: feasible first, then more zeros, lower worst condition, fewer multiplies.
// Between two sets outside the condition bound, the lower worst condition wins.
bool better(const Fitness& a, const Fitness& b);

// Cost model for z = A^T f until code generation reports real counts: one multiply per
// distinct nonzero magnitude in each column of A (equal magnitudes share a multiply after
// adding or subtracting their inputs).
int multiply_cost(const Eigen::MatrixXd& inverse);

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
  static constexpr size_t kMaxTabulatedValues = size_t(1) << 27;  // 1 GiB
  LobeEvaluator(const candidates::CandidateSet& set, bool lobe_sharing, double max_condition,
                size_t max_tabulated_values = kMaxTabulatedValues);

  int order() const { return order_; }
  bool lobe_sharing() const { return lobe_sharing_; }
  int genes() const { return lobe_count(order_, lobe_sharing_); }
  double max_condition() const { return max_condition_; }
  const candidates::CandidateSet& candidates() const { return candidates_; }

  // Fast path for the search: eigenvalues of Y^T Y for the condition, LU for the inverse.
  Fitness evaluate(const Genome& genes) const;
  // Slow path for tables and tests: SVD condition, exact zeros.
  std::vector<BandAnalysis> analyze(const Genome& genes) const;
  Fitness fitness_of(const std::vector<BandAnalysis>& bands) const;

 private:
  Eigen::MatrixXd band_matrix(const Genome& genes, int l) const;

  const candidates::CandidateSet& candidates_;
  int order_;
  bool lobe_sharing_;
  double max_condition_;
  std::vector<double> sh_;  // y at every candidate: sh_[c * N^2 + index(l, m)]; empty: on demand
};

// Exact zeros: entries at or below kZeroRelative * max|A| set to 0; returns their count.
int zero_small_entries(Eigen::MatrixXd& inverse);

}  // namespace zhf::optimizer
