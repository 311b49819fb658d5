// The thread pool (runtime/parallel.h): an exception thrown by a worker's work reaches the calling
// thread, once every thread has stopped, instead of ending the process.
#include <atomic>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "zhf/runtime/parallel.h"

namespace zhf::runtime {
namespace {

TEST(Parallel, AWorkersExceptionIsRethrownOnTheCallingThread) {
  for (int workers : {1, 2, 4}) {
    std::atomic<int> done{0};
    try {
      parallel_for(1000, workers, [&](int i) {
        if (i == 577) throw std::invalid_argument("item 577");
        ++done;
      });
      ADD_FAILURE() << workers << " workers: no exception";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()), "item 577") << workers << " workers";
    }
    EXPECT_LT(done.load(), 1000) << workers << " workers";
  }
  // Each chunk in turn throws: the worker threads' chunks and the calling thread's own.
  const std::size_t count = 4 * kParallelBatchThreshold;
  for (std::size_t throwing : {std::size_t(0), count / 2, count - 1}) {
    try {
      parallel_chunks(count, 4, [&](std::size_t begin, std::size_t end) {
        if (begin <= throwing && throwing < end) throw std::runtime_error("chunk at " + std::to_string(begin));
      });
      ADD_FAILURE() << "splat " << throwing << ": no exception";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("chunk at"), std::string::npos) << e.what();
    }
  }
  // And no exception, no change: every item once.
  std::atomic<std::size_t> sum{0};
  parallel_chunks(count, 3, [&](std::size_t begin, std::size_t end) { sum += end - begin; });
  EXPECT_EQ(sum.load(), count);
}

}  // namespace
}  // namespace zhf::runtime
