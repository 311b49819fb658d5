// The continuous alternative (the method's first attempt): minimise
//   sum_l sum_ij log(|A_l,ij| + 1) + log(|Y_l,ij| + 1)
// over continuous (theta, phi) per lobe with a derivative-free nlopt algorithm from random
// starts, then snap each lobe to its nearest candidate direction.
#pragma once

#include <cstdint>
#include <vector>

#include "zhf/optimizer/objective.h"

namespace zhf::optimizer {

struct ContinuousOptions {
  std::uint64_t seed = 1;
  int starts = 16;
  int max_evaluations_per_start = 4000;
};

struct ContinuousStart {
  double objective = 0;  // at the continuous optimum
  Genome snapped;
  Fitness fitness;       // of the snapped set
};

std::vector<ContinuousStart> continuous_search(const LobeEvaluator& evaluator, const ContinuousOptions& options);

}  // namespace zhf::optimizer
