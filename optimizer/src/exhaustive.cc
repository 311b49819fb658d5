#include "zhf/optimizer/exhaustive.h"

#include <chrono>
#include <cmath>

namespace zhf::optimizer {
namespace {

using Clock = std::chrono::steady_clock;

// Gene groups whose order is irrelevant: [begin, end) per band, in band order.
std::vector<std::pair<int, int>> symmetric_groups(const LobeEvaluator& evaluator) {
  std::vector<std::pair<int, int>> groups;
  for (int l = 2; l < evaluator.order(); ++l) {
    const int begin = evaluator.lobe_sharing() ? (l == 2 ? 0 : 2 * l - 1) : runtime::lobe_index(l, 0, false);
    const int end = runtime::lobe_index(l, 2 * l, evaluator.lobe_sharing()) + 1;
    groups.push_back({begin, end});
  }
  return groups;
}

double binomial(int n, int k) {
  if (k < 0 || k > n) return 0;
  double result = 1;
  for (int i = 1; i <= k; ++i) result = result * (n - k + i) / i;
  return result;
}

// Advances a sorted k-subset of [0, n) to the next one in lexicographic order.
bool next_combination(int* first, int k, int n) {
  for (int i = k - 1; i >= 0; --i) {
    if (first[i] < n - k + i) {
      ++first[i];
      for (int j = i + 1; j < k; ++j) first[j] = first[j - 1] + 1;
      return true;
    }
  }
  return false;
}

}  // namespace

ExhaustiveResult exhaustive_search(const LobeEvaluator& evaluator, double time_limit_seconds, int threads,
                                   const std::atomic<bool>* stop) {
  const auto start = Clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  const int n = static_cast<int>(evaluator.candidates().directions.size());
  const auto groups = symmetric_groups(evaluator);
  ExhaustiveResult result;
  result.sets_total = 1;
  for (const auto& [begin, end] : groups) result.sets_total *= binomial(n, end - begin);

  // Odometer over groups; each group is a sorted combination. Lobes may repeat across
  // groups: such sets are singular and rejected by the objective, which is cheaper than
  // excluding them here.
  Genome genome(evaluator.genes());
  for (const auto& [begin, end] : groups)
    for (int g = begin; g < end; ++g) genome[g] = g - begin;
  bool more = true;
  const size_t batch_size = 8192;
  while (more) {
    std::vector<Genome> batch;
    while (more && batch.size() < batch_size) {
      batch.push_back(genome);
      more = false;
      for (int k = static_cast<int>(groups.size()) - 1; k >= 0 && !more; --k) {
        const auto [begin, end] = groups[k];
        if (next_combination(&genome[begin], end - begin, n)) {
          more = true;
        } else {
          for (int g = begin; g < end; ++g) genome[g] = g - begin;
        }
      }
    }
    std::vector<Fitness> fitness;
    evaluate_all(evaluator, batch, fitness, threads);
    for (size_t i = 0; i < batch.size(); ++i) {
      if (result.search.best.empty() || evaluator.better(fitness[i], result.search.fitness)) {
        result.search.best = batch[i];
        result.search.fitness = fitness[i];
      }
    }
    result.sets_evaluated += static_cast<double>(batch.size());
    result.search.evaluations += static_cast<long>(batch.size());
    if (stop && stop->load()) {
      result.search.interrupted = true;
      break;
    }
    if (time_limit_seconds > 0 && elapsed() >= time_limit_seconds) {
      result.search.timed_out = true;
      break;
    }
  }
  result.complete = !more;
  // Unfinished: the trivial bound, every row of each A_l keeps one nonzero.
  int trivial = 0;
  for (int l = 2; l < evaluator.order(); ++l) trivial += (2 * l + 1) * (2 * l);
  result.upper_bound = result.complete ? result.search.fitness.zeros : trivial;
  result.search.seconds = elapsed();
  return result;
}

}  // namespace zhf::optimizer
