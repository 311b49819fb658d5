// Lobe sets for the lobe-parallel float rotation (runtime/lanes.h). There A_l s runs as a dense
// SIMD multiply, so zeros of A_l buy nothing; what sets the float error is how much A_l amplifies
// the rounding of the samples s. Per band that is
//   a_l = |row of Y_l| / sigma_min(Y_l) = sqrt((2l+1)/4pi) ||A_l||_2   (1 for an orthogonal Y_l)
// since every row of Y_l has that norm (addition theorem). The search minimises
// 4 max_l a_l^2 + mean_l a_l^2 over continuous (theta, phi) of the 2N-1 shared lobes with nlopt's
// subplex, from seeded random starts; the directions are not SH-zero candidates.
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>
#include "zhf/runtime/limits.h"
#include "zhf/runtime/lobe_table.h"

namespace zhf::optimizer {

struct AmplificationOptions {
  std::uint64_t seed = 1;
  int starts = 8;
  int passes = 3;  // subplex restarts from where the previous pass stopped
  int max_evaluations_per_pass = 20000;
  int threads = 0;  // starts run in parallel (0: all cores); never changes the result
  const std::atomic<bool>* stop = nullptr;  // checked between passes
};

struct AmplificationResult {
  std::vector<double> theta, phi;  // the best set, one entry per lobe
  std::vector<double> amplification;  // a_l, l = 2..N-1
  double objective = 0;
  long evaluations = 0;
  bool interrupted = false;
};

// Order 3..runtime::kMaxShOrder, lobe sharing.
AmplificationResult amplification_search(int order, const AmplificationOptions& options);

// The table of the set found: dense A_l, each lobe's source saying where it came from, and a_l
// per band in the provenance (runtime::band_amplification).
runtime::LobeTable make_amplification_table(int order, const AmplificationResult& result, nlohmann::json provenance);

}  // namespace zhf::optimizer
