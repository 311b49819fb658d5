// Where zhf's own data lives: the checked-in lobe tables and kernels (generated/), the runtime's
// headers (the lanes kernels verify compiles), and the benchmark's extra tables. One place knows,
// so the CLI, the benchmarks and the tests all find the same files.
#pragma once

#include <string>

#include "zhf/runtime/lobe_table.h"

namespace zhf::pipeline {

struct Project {
  std::string root;  // holds generated/, runtime/include and bench/tables

  std::string generated() const { return root + "/generated"; }
  std::string lobes() const { return root + "/generated/lobes"; }
  std::string runtime_include() const { return root + "/runtime/include"; }
  std::string bench_tables() const { return root + "/bench/tables"; }
  // generated/lobes/order_N.json (order 2: the lobe-free table).
  runtime::LobeTable table(int order) const;
};

// The working directory when it holds a non-empty generated/ (a checkout, or a copy made to
// change the tables), else the source tree zhf was built from.
Project project();

}  // namespace zhf::pipeline
