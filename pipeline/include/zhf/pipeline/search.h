// From an order to its lobe table: the whole search, composed once for the CLI, the benchmarks
// and the tests. The sparsity and operations objectives run the genetic search then the iterated
// local search (or, exhaustive, enumerate every set), ranking by zeros of A or by the code
// generator's multiplies of z = A^T f; the amplification objective runs the continuous search
// for the lanes tables. The provenance records what reproduces the table: zhf's version, the
// command, the seed and the search's counts (never wall-clock time).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>

#include "zhf/optimizer/genetic.h"
#include "zhf/runtime/lobe_table.h"

namespace zhf::pipeline {

enum class Objective { kSparsity, kOperations, kAmplification };

struct SearchRequest {
  int order = 0;
  Objective objective = Objective::kSparsity;
  std::uint64_t seed = 1;
  double time_limit = 0;  // seconds; 0: none (a limit that triggers makes the result machine-dependent)
  int threads = 0;        // 0: all cores; never changes the result
  int population = 500;
  int generations = 0;    // 0: no limit
  int stall = 50;
  int local_search_stall = 100;
  double max_condition = optimizer::kDefaultMaxCondition;
  bool lobe_sharing = true;
  bool exhaustive = false;
  bool seed_from_continuous = false;
  int starts = 8;         // amplification: random starts
  std::string command;    // recorded in the provenance
  const std::atomic<bool>* stop = nullptr;
  // Progress, when set: one line at a time, without the newline.
  std::function<void(const std::string&)> progress;
};

struct SearchOutcome {
  bool found = false;        // false: nothing to write (no invertible set, or stopped before any)
  runtime::LobeTable table;
  bool interrupted = false;
  bool feasible = true;      // within max_condition
  std::string summary;       // what the search did, one or more lines for the user
};

SearchOutcome search(const SearchRequest& request);

}  // namespace zhf::pipeline
