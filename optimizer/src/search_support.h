// Helpers shared by the searches. Random draws use the generator's raw bits:
// std::uniform_*_distribution are implementation-defined, and checked-in tables must not
// change with the standard library.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <limits>
#include <random>
#include <system_error>
#include <thread>
#include <vector>

#include "zhf/optimizer/genetic.h"

namespace zhf::optimizer::detail {

// Uniform integer in [0, n).
inline int pick(std::mt19937_64& rng, int n) {
  constexpr std::uint64_t kMax = std::numeric_limits<std::uint64_t>::max();
  const std::uint64_t limit = kMax - kMax % static_cast<std::uint64_t>(n);
  std::uint64_t x;
  do {
    x = rng();
  } while (x >= limit);
  return static_cast<int>(x % static_cast<std::uint64_t>(n));
}

// Uniform double in [0, 1).
inline double unit(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * (1.0 / 9007199254740992.0); }

// A thread count option: 0 means all cores.
inline int resolve_threads(int threads) {
  return threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

// Calls work(i) for i in [0, count) on `workers` threads (the caller's among them), each taking
// the next index; results must go to per-index slots so the order of completion never shows.
// When the system refuses more threads (a process limit), the ones started share the work.
template <class Work>
void parallel_for(int count, int workers, Work&& work) {
  std::atomic<int> next{0};
  auto run = [&] {
    for (int i = next.fetch_add(1); i < count; i = next.fetch_add(1)) work(i);
  };
  std::vector<std::thread> pool;
  try {
    for (int t = 1; t < workers; ++t) pool.emplace_back(run);
  } catch (const std::system_error&) {
  }
  run();
  for (std::thread& t : pool) t.join();
}

// The stops every search shares: an interrupt, then the time limit (0: none). Marks why.
inline bool interrupted_or_out_of_time(const std::atomic<bool>* stop, double limit_seconds, double elapsed_seconds,
                                       SearchResult& result) {
  if (stop && stop->load()) {
    result.interrupted = true;
    return true;
  }
  if (limit_seconds > 0 && elapsed_seconds >= limit_seconds) {
    result.timed_out = true;
    return true;
  }
  return false;
}

}  // namespace zhf::optimizer::detail
