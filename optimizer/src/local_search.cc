#include "zhf/optimizer/local_search.h"
#include "zhf/sh/random.h"

#include <chrono>
#include <random>
#include <algorithm>

#include "search_support.h"

namespace zhf::optimizer {
namespace {

using Clock = std::chrono::steady_clock;

// Moves of one lobe along its candidate grid line: same phi other theta, same theta other phi.
class GridMoves {
 public:
  explicit GridMoves(const candidates::CandidateSet& set) {
    const int thetas = static_cast<int>(set.thetas.size());
    const int phis = static_cast<int>(set.phis.size());
    at_.assign(size_t(thetas) * (phis + 1), -1);
    for (size_t c = 0; c < set.directions.size(); ++c) {
      const auto& d = set.directions[c];
      at_[slot(d.theta_index, d.phi_index, phis)] = static_cast<int>(c);
    }
    phis_ = phis;
    thetas_ = thetas;
    set_ = &set;
  }

  void moves(int c, std::vector<int>& out) const {
    out.clear();
    const auto& d = set_->directions[c];
    const int phi = d.phi_index < 0 ? 0 : d.phi_index;  // from a pole, walk down the phi = 0 meridian
    for (int t = 0; t < thetas_; ++t) {
      int target = at_[slot(t, phi, phis_)];
      if (target < 0) target = at_[slot(t, -1, phis_)];  // a pole
      if (target >= 0 && target != c) out.push_back(target);
    }
    if (d.phi_index < 0) return;
    for (int p = 0; p < phis_; ++p)
      if (p != d.phi_index) out.push_back(at_[slot(d.theta_index, p, phis_)]);
  }

 private:
  static size_t slot(int t, int p, int phis) { return size_t(t) * (phis + 1) + size_t(p + 1); }
  std::vector<int> at_;
  int phis_ = 0, thetas_ = 0;
  const candidates::CandidateSet* set_ = nullptr;
};

bool allowed(const std::vector<std::vector<int>>& per_gene, int gene, int c) {
  if (per_gene.empty()) return true;
  const auto& list = per_gene[gene];
  return std::find(list.begin(), list.end(), c) != list.end();
}

}  // namespace

SearchResult iterated_local_search(const LobeEvaluator& evaluator, const Genome& start, const Fitness& start_fitness,
                                   const LocalSearchOptions& options) {
  const auto t0 = Clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - t0).count(); };
  const GridMoves grid(evaluator.candidates());
  const int genes = evaluator.genes();
  const int total = static_cast<int>(evaluator.candidates().directions.size());
  std::mt19937_64 rng(options.seed);

  SearchResult result;
  result.best = start;
  result.fitness = start_fitness;

  std::vector<int> targets;
  auto descend = [&](Genome genome, Fitness fitness) {
    for (;;) {
      std::vector<Genome> batch;
      for (int g = 0; g < genes; ++g) {
        grid.moves(genome[g], targets);
        for (int c : targets) {
          if (!allowed(options.gene_candidates, g, c)) continue;
          batch.push_back(genome);
          batch.back()[g] = c;
        }
      }
      for (int i = 0; i < genes; ++i)
        for (int j = i + 1; j < genes; ++j) {
          if (genome[i] == genome[j] || !allowed(options.gene_candidates, i, genome[j]) ||
              !allowed(options.gene_candidates, j, genome[i]))
            continue;
          batch.push_back(genome);
          std::swap(batch.back()[i], batch.back()[j]);
        }
      // In chunks, so an interrupt or the time limit stops even one step of a large order
      // (order 32 has thousands of moves per gene); the best of what was evaluated is kept.
      constexpr size_t kChunk = 4096;
      std::vector<Fitness> fitness_of_batch, chunk_fitness;
      bool stopped = false;
      for (size_t begin = 0; begin < batch.size() && !stopped; begin += kChunk) {
        stopped = detail::interrupted_or_out_of_time(options.stop, options.time_limit_seconds, elapsed(), result);
        if (stopped) break;
        const std::vector<Genome> chunk(batch.begin() + begin, batch.begin() + std::min(batch.size(), begin + kChunk));
        evaluate_all(evaluator, chunk, chunk_fitness, options.threads);
        fitness_of_batch.insert(fitness_of_batch.end(), chunk_fitness.begin(), chunk_fitness.end());
      }
      result.evaluations += static_cast<long>(fitness_of_batch.size());
      int best = -1;
      for (size_t k = 0; k < fitness_of_batch.size(); ++k)
        if (evaluator.better(fitness_of_batch[k], best < 0 ? fitness : fitness_of_batch[best])) best = static_cast<int>(k);
      if (best >= 0) {
        genome = batch[best];
        fitness = fitness_of_batch[best];
      }
      if (best < 0 || stopped) return std::make_pair(genome, fitness);
    }
  };

  auto [genome, fitness] = descend(start, start_fitness);
  if (evaluator.better(fitness, result.fitness)) {
    result.best = genome;
    result.fitness = fitness;
    if (options.on_improvement) options.on_improvement(0, result.fitness, result.evaluations);
  }
  int since_improvement = 0;
  for (int kick = 1; options.stall_kicks > 0; ++kick) {
    if (detail::interrupted_or_out_of_time(options.stop, options.time_limit_seconds, elapsed(), result)) break;
    if (options.max_kicks > 0 && kick > options.max_kicks) break;
    if (since_improvement >= options.stall_kicks) break;
    Genome kicked = result.best;
    for (int k = 0; k < options.kick_genes; ++k) {
      const int g = sh::uniform_index(rng, genes);
      kicked[g] = options.gene_candidates.empty()
                      ? sh::uniform_index(rng, total)
                      : options.gene_candidates[g][sh::uniform_index(rng, static_cast<int>(options.gene_candidates[g].size()))];
    }
    const Fitness kicked_fitness = evaluator.evaluate(kicked);
    ++result.evaluations;
    auto [improved, improved_fitness] = descend(kicked, kicked_fitness);
    result.generations = kick;
    if (evaluator.better(improved_fitness, result.fitness)) {
      result.best = improved;
      result.fitness = improved_fitness;
      since_improvement = 0;
      if (options.on_improvement) options.on_improvement(kick, result.fitness, result.evaluations);
    } else {
      ++since_improvement;
    }
  }
  result.seconds = elapsed();
  return result;
}

}  // namespace zhf::optimizer
