// Exhaustive search for small orders. Permuting the lobes a band adds (lobes 2l-1, 2l under
// sharing, or all of a band's own lobes without) permutes columns of A_l and rows of Y_l:
// zero counts and conditions of every band are unchanged, so only sorted index tuples per
// band group are enumerated.
#pragma once

#include <atomic>
#include <cstdint>

#include "zhf/optimizer/genetic.h"

namespace zhf::optimizer {

struct ExhaustiveResult {
  SearchResult search;
  bool complete = false;      // every lobe set was evaluated: search.best is optimal
  double sets_total = 0;      // lobe sets up to the permutation symmetry
  double sets_evaluated = 0;
  int upper_bound = 0;        // no lobe set has more zeros than this
};

ExhaustiveResult exhaustive_search(const LobeEvaluator& evaluator, double time_limit_seconds, int threads,
                                   const std::atomic<bool>* stop = nullptr);

}  // namespace zhf::optimizer
