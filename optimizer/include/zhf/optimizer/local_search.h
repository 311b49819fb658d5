// Iterated local search: the polish that takes the genetic search's best set to the
// sparsest sets zhf has found. A descent repeatedly takes the best single move among
//   - re-pick one lobe's theta (same phi) or one lobe's phi (same theta), and
//   - swap two lobes' positions (which band first uses a lobe matters under sharing),
// then a kick re-picks a few random lobes of the best set and the descent runs again.
// Every stop is a count, so the result for a seed is reproducible.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>

#include "zhf/optimizer/genetic.h"

namespace zhf::optimizer {

struct LocalSearchOptions {
  std::uint64_t seed = 1;
  int stall_kicks = 100;         // stop after this many kicks without improvement (0: descend once)
  int max_kicks = 0;             // 0: no limit
  int kick_genes = 2;
  double time_limit_seconds = 0; // 0: no limit (machine-dependent when it triggers)
  int threads = 0;
  // Allowed candidate indices per gene (empty: any), as in GeneticOptions.
  std::vector<std::vector<int>> gene_candidates;
  const std::atomic<bool>* stop = nullptr;
  std::function<void(int kick, const Fitness& best, long evaluations)> on_improvement;
};

// Starts from `start` (already evaluated as `start_fitness`); never returns anything worse.
SearchResult iterated_local_search(const LobeEvaluator& evaluator, const Genome& start, const Fitness& start_fitness,
                                   const LocalSearchOptions& options);

}  // namespace zhf::optimizer
