// zhf's one thread pool: every batch, search and design start that runs on several threads goes
// through parallel_chunks (contiguous ranges) or parallel_for (indices taken one at a time), and
// work that overlaps the caller's (file reads and writes beside a batch) through start_beside.
// Both run on the calling thread among the workers, and carry on with the threads they could start
// when the system refuses more (a process limit).
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <future>
#include <mutex>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

#include "zhf/runtime/limits.h"

namespace zhf::runtime {

// Below this many vectors a batch runs on the calling thread.
inline constexpr std::size_t kParallelBatchThreshold = 4096;

// A thread-count option: 0 means all cores; never more than kMaxThreads.
inline int worker_count(int threads) {
  const int asked = threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return std::min(asked, kMaxThreads);
}

// The first exception a pool's work threw, kept to be rethrown on the calling thread once every
// thread of the pool has stopped (the rest are dropped): a throw inside a std::thread would
// otherwise end the process.
class FirstException {
 public:
  // Runs work(), keeping what it throws; false once any work has thrown (so the rest can stop).
  template <class Work>
  bool run(Work&& work) noexcept {
    if (failed_.load(std::memory_order_relaxed)) return false;
    try {
      work();
      return true;
    } catch (...) {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (!first_) first_ = std::current_exception();
      failed_.store(true, std::memory_order_relaxed);
      return false;
    }
  }
  bool failed() const { return failed_.load(std::memory_order_relaxed); }
  void rethrow() const {
    if (first_) std::rethrow_exception(first_);
  }

 private:
  std::atomic<bool> failed_{false};
  std::mutex mutex_;
  std::exception_ptr first_;
};

// Calls work(i) for i in [0, count) on `workers` threads, each taking the next index; results must
// go to per-index slots so the order of completion never shows. An exception thrown by work stops
// the taking of indices and is rethrown here once every thread has stopped.
template <class Work>
void parallel_for(int count, int workers, Work&& work) {
  std::atomic<int> next{0};
  FirstException failure;
  auto run = [&] {
    for (int i = next.fetch_add(1); i < count && failure.run([&] { work(i); }); i = next.fetch_add(1)) {
    }
  };
  std::vector<std::thread> pool;
  try {
    for (int t = 1; t < workers; ++t) pool.emplace_back(run);
  } catch (const std::system_error&) {
    // No more threads: the ones started share the work.
  }
  run();
  for (std::thread& t : pool) t.join();
  failure.rethrow();
}

// Runs work(begin, end) over [0, count) in contiguous chunks, one per worker (threads = 0: all
// cores); below kParallelBatchThreshold items, or when no thread can be started, on the calling
// thread alone. An exception thrown by work is rethrown here once every chunk has stopped.
template <class Work>
void parallel_chunks(std::size_t count, int threads, Work&& work) {
  int workers = worker_count(threads);
  if (count < kParallelBatchThreshold) workers = 1;
  FirstException failure;
  auto chunk_of = [&](std::size_t begin, std::size_t end) { failure.run([&] { work(begin, end); }); };
  std::vector<std::thread> pool;
  const std::size_t chunk = (count + workers - 1) / workers;
  std::size_t started = chunk;  // [0, chunk) is the calling thread's
  try {
    for (int t = 1; t < workers && started < count; ++t) {
      pool.emplace_back(chunk_of, started, std::min(count, started + chunk));
      started = std::min(count, started + chunk);
    }
  } catch (const std::system_error&) {
    // No more threads (a process limit): the calling thread does the rest.
  }
  chunk_of(std::size_t(0), std::min(count, chunk));
  if (started < count) chunk_of(started, count);
  for (std::thread& t : pool) t.join();
  failure.rethrow();
}

// Starts work() on a thread of its own while the caller goes on, and returns its future; when no
// thread can be started, work() runs on the calling thread at the future's get().
template <class Work>
auto start_beside(Work&& work) -> std::future<decltype(work())> {
  return std::async(std::launch::async | std::launch::deferred, std::forward<Work>(work));
}

}  // namespace zhf::runtime
