#include "zhf/optimizer/genetic.h"
#include "zhf/runtime/parallel.h"
#include "zhf/sh/random.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <numeric>
#include <random>

#include "search_support.h"

namespace zhf::optimizer {
namespace {

using Clock = std::chrono::steady_clock;


class GenePool {
 public:
  GenePool(const LobeEvaluator& evaluator, const std::vector<std::vector<int>>& per_gene)
      : genes_(evaluator.genes()), total_(static_cast<int>(evaluator.candidates().directions.size())),
        per_gene_(per_gene) {}
  int genes() const { return genes_; }
  int random_value(int gene, std::mt19937_64& rng) const {
    if (per_gene_.empty()) return sh::uniform_index(rng, total_);
    const std::vector<int>& allowed = per_gene_[gene];
    return allowed[sh::uniform_index(rng, static_cast<int>(allowed.size()))];
  }
  Genome random_genome(std::mt19937_64& rng) const {
    Genome g(genes_);
    for (int i = 0; i < genes_; ++i) g[i] = random_value(i, rng);
    return g;
  }

 private:
  int genes_;
  int total_;
  const std::vector<std::vector<int>>& per_gene_;
};

// Evaluations already made, so elites and unchanged clones are not evaluated again. Pure
// function values, so the cache changes only the work done, never a result.
class FitnessCache {
 public:
  explicit FitnessCache(size_t limit) : limit_(limit) {}
  // Fills fitness for every genome; returns how many evaluations were computed.
  long evaluate(const LobeEvaluator& evaluator, const std::vector<Genome>& genomes, std::vector<Fitness>& fitness,
                int threads) {
    fitness.assign(genomes.size(), Fitness{});
    std::vector<Genome> todo;
    std::map<Genome, size_t> todo_index;
    for (const Genome& g : genomes)
      if (cache_.find(g) == cache_.end() && todo_index.emplace(g, todo.size()).second) todo.push_back(g);
    std::vector<Fitness> computed;
    evaluate_all(evaluator, todo, computed, threads);
    if (cache_.size() + todo.size() > limit_) cache_.clear();
    for (size_t i = 0; i < todo.size(); ++i) cache_[todo[i]] = computed[i];
    for (size_t i = 0; i < genomes.size(); ++i) fitness[i] = cache_.at(genomes[i]);
    return static_cast<long>(todo.size());
  }

 private:
  size_t limit_;
  std::map<Genome, Fitness> cache_;
};

}  // namespace

void evaluate_all(const LobeEvaluator& evaluator, const std::vector<Genome>& genomes, std::vector<Fitness>& out,
                  int threads) {
  out.assign(genomes.size(), Fitness{});
  const int count = static_cast<int>(genomes.size());
  const int workers = std::min(runtime::worker_count(threads), std::max(1, count / 8));
  runtime::parallel_for(count, workers, [&](int i) { out[i] = evaluator.evaluate(genomes[i]); });
}

SearchResult genetic_search(const LobeEvaluator& evaluator, const GeneticOptions& options) {
  const auto start = Clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  std::mt19937_64 rng(options.seed);
  const GenePool pool(evaluator, options.gene_candidates);
  const int size = std::max(options.population, options.elite + 2);
  FitnessCache cache(4'000'000 / std::max(1, pool.genes()));

  std::vector<Genome> population;
  for (const Genome& g : options.initial)
    if (static_cast<int>(population.size()) < size) population.push_back(g);
  while (static_cast<int>(population.size()) < size) population.push_back(pool.random_genome(rng));

  SearchResult result;
  std::vector<Fitness> fitness;
  auto evaluate_and_sort = [&] {
    result.evaluations += cache.evaluate(evaluator, population, fitness, options.threads);
    std::vector<int> order(population.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return evaluator.better(fitness[a], fitness[b]); });
    std::vector<Genome> sorted_population;
    std::vector<Fitness> sorted_fitness;
    for (int i : order) {
      sorted_population.push_back(std::move(population[i]));
      sorted_fitness.push_back(fitness[i]);
    }
    population.swap(sorted_population);
    fitness.swap(sorted_fitness);
  };
  // Population is sorted best first, so a tournament winner is the smallest index drawn.
  auto tournament = [&] {
    int winner = sh::uniform_index(rng, size);
    for (int k = 1; k < options.tournament_size; ++k) winner = std::min(winner, sh::uniform_index(rng, size));
    return winner;
  };

  evaluate_and_sort();
  result.best = population[0];
  result.fitness = fitness[0];
  int stall = 0;
  const double mutation_rate = 1.0 / pool.genes();
  const int breed = size - options.elite;
  const int crossovers = static_cast<int>(std::lround(options.crossover_fraction * breed));
  for (int generation = 1;; ++generation) {
    if (detail::interrupted_or_out_of_time(options.stop, options.time_limit_seconds, elapsed(), result)) break;
    if (options.max_generations > 0 && result.generations >= options.max_generations) break;
    if (stall >= options.stall_generations) break;

    std::vector<Genome> next(population.begin(), population.begin() + options.elite);
    for (int i = 0; i < breed; ++i) {
      if (i < crossovers) {
        const Genome& a = population[tournament()];
        const Genome& b = population[tournament()];
        Genome child(pool.genes());
        for (int g = 0; g < pool.genes(); ++g) child[g] = (rng() & 1) ? a[g] : b[g];
        next.push_back(std::move(child));
      } else {
        Genome child = population[tournament()];
        for (int g = 0; g < pool.genes(); ++g)
          if (sh::uniform01(rng) < mutation_rate) child[g] = pool.random_value(g, rng);
        next.push_back(std::move(child));
      }
    }
    population.swap(next);
    evaluate_and_sort();
    result.generations = generation;
    if (evaluator.better(fitness[0], result.fitness)) {
      result.best = population[0];
      result.fitness = fitness[0];
      stall = 0;
    } else {
      ++stall;
    }
    if (options.on_generation) {
      options.on_generation({generation, result.fitness, result.evaluations, elapsed()});
    }
  }
  result.seconds = elapsed();
  return result;
}

SearchResult random_search(const LobeEvaluator& evaluator, long evaluations, std::uint64_t seed, int threads) {
  const auto start = Clock::now();
  std::mt19937_64 rng(seed);
  const std::vector<std::vector<int>> all;
  const GenePool pool(evaluator, all);
  SearchResult result;
  const long batch_size = 4096;
  for (long done = 0; done < evaluations; done += batch_size) {
    std::vector<Genome> batch;
    for (long i = done; i < std::min(evaluations, done + batch_size); ++i) batch.push_back(pool.random_genome(rng));
    std::vector<Fitness> fitness;
    evaluate_all(evaluator, batch, fitness, threads);
    for (size_t i = 0; i < batch.size(); ++i) {
      if (result.best.empty() || evaluator.better(fitness[i], result.fitness)) {
        result.best = batch[i];
        result.fitness = fitness[i];
      }
    }
    result.evaluations += static_cast<long>(batch.size());
  }
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

}  // namespace zhf::optimizer
