// Helpers shared by the searches. Random draws come from sh/random.h and threads from
// runtime/parallel.h, so checked-in tables do not change with the standard library or the
// thread count.
#pragma once

#include <atomic>

#include "zhf/optimizer/genetic.h"

namespace zhf::optimizer::detail {

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
