// parallel_chunks: the runtime's one way of spreading a batch over threads.
#pragma once

#include <algorithm>
#include <cstddef>
#include <system_error>
#include <thread>
#include <vector>

namespace zhf::runtime {

// Below this many vectors a batch runs on the calling thread.
inline constexpr std::size_t kParallelBatchThreshold = 4096;

// Runs work(begin, end) over [0, count) in contiguous chunks, one per worker (threads = 0: all
// cores); below kParallelBatchThreshold items, or when no thread can be started, on the calling
// thread alone.
template <class Work>
void parallel_chunks(std::size_t count, int threads, Work&& work) {
  int workers = threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (count < kParallelBatchThreshold) workers = 1;
  std::vector<std::thread> pool;
  const std::size_t chunk = (count + workers - 1) / workers;
  std::size_t started = chunk;  // [0, chunk) is the calling thread's
  try {
    for (int t = 1; t < workers && started < count; ++t) {
      pool.emplace_back(work, started, std::min(count, started + chunk));
      started = std::min(count, started + chunk);
    }
  } catch (const std::system_error&) {
    // No more threads (a process limit): the calling thread does the rest.
  }
  work(std::size_t(0), std::min(count, chunk));
  work(started, count);
  for (std::thread& t : pool) t.join();
}

}  // namespace zhf::runtime
