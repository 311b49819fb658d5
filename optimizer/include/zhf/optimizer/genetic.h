// Genetic search over lobe sets, in the method's published setup: one gene per lobe chosen
// from that lobe's candidates, tournament selection, scattered crossover, mutation that
// re-picks a gene with rate 1/genes, elitism, stop on a stall. Fitness evaluations run in
// parallel; every random choice is made on one thread from one seeded generator, so the
// result for a seed is the same whatever the thread count.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <vector>

#include "zhf/optimizer/objective.h"

namespace zhf::optimizer {

struct GenerationReport {
  int generation = 0;
  Fitness best;
  long evaluations = 0;
  double elapsed_seconds = 0;
};

struct GeneticOptions {
  std::uint64_t seed = 1;
  int population = 500;
  double crossover_fraction = 0.8;
  int elite = 2;
  int tournament_size = 4;
  int stall_generations = 50;
  int max_generations = 0;         // 0: no limit
  double time_limit_seconds = 0;   // 0: no limit (a time limit makes the result machine-dependent)
  int threads = 0;                 // 0: all cores
  // Allowed candidate indices per gene; empty means every gene may take any candidate.
  std::vector<std::vector<int>> gene_candidates;
  std::vector<Genome> initial;     // put into the first population ahead of random members
  const std::atomic<bool>* stop = nullptr;
  std::function<void(const GenerationReport&)> on_generation;
};

struct SearchResult {
  Genome best;
  Fitness fitness;
  int generations = 0;
  long evaluations = 0;
  double seconds = 0;
  bool interrupted = false;
  bool timed_out = false;
};

SearchResult genetic_search(const LobeEvaluator& evaluator, const GeneticOptions& options);

// Baseline: the best of `evaluations` uniformly random genomes.
SearchResult random_search(const LobeEvaluator& evaluator, long evaluations, std::uint64_t seed, int threads = 0);

// Evaluates genomes[i] into out[i] on `threads` threads (0: all cores).
void evaluate_all(const LobeEvaluator& evaluator, const std::vector<Genome>& genomes, std::vector<Fitness>& out,
                  int threads);

}  // namespace zhf::optimizer
