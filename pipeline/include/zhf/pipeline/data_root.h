// The data root: where zhf's own data lives, the checked-in lobe tables and kernels (generated/), the
// runtime's headers (the lanes kernels verify compiles) and the tools in tools/node. One place knows,
// so the CLI, the benchmarks and the tests all find the same files.
#pragma once

#include <string>

#include "zhf/runtime/lobe_table.h"

namespace zhf::pipeline {

struct DataRoot {
  std::string root;             // holds generated/
  std::string runtime_include;  // holds zhf/runtime/*.h

  std::string generated() const { return root + "/generated"; }
  std::string lobes() const { return root + "/generated/lobes"; }
  std::string paths() const { return root + "/generated/paths"; }
  std::string designs() const { return root + "/generated/designs"; }
  // The naga-wasm package scripts/setup.sh installs into a checkout's tools/node (verify turns
  // WGSL into SPIR-V with it): root's when it has one, else the source tree's.
  std::string naga_wasm() const;
  // web/browser, the scripts that run WGSL in headless Chromium (with tools/node's puppeteer-core,
  // scripts/setup_web.sh): root's when it has them, else the source tree's.
  std::string browser_scripts() const;
  // generated/lobes/order_N.json (order 2: the lobe-free table).
  runtime::LobeTable table(int order) const;
};

// The first of: the working directory when it holds a non-empty generated/lobes (a checkout, or
// a copy made to change the tables); the installed data beside the running binary
// (<prefix>/share/zhf after `cmake --install`); the source tree zhf was built from.
DataRoot data_root();

}  // namespace zhf::pipeline
