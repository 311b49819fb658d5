// The cost and error models that choose how kernels.cc builds a module: the assignment of methods
// to bands with the fewest operations, the lobe stage a float error model allows, and the
// multiplies the lobe search ranks tables by.
#include <algorithm>

#include "band_lobes.h"
#include "kernel_cost.h"
#include "zhf/codegen/kernels.h"
#include "zhf/codegen/limits.h"
#include "zhf/runtime/rotation.h"
#include "zhf/tolerances/tolerances.h"

namespace zhf::codegen {
namespace {

int operations(const OpCount& c) { return c.multiplies + c.adds + c.others; }

}  // namespace

// Every assignment of methods to bands 2..N-1 up to kMaxExhaustiveMethodBands of them, else
// lobes below a band and zxzxz from it on; band 2 also tries the quadratic form. The one whose
// rotate_orderN has the fewest operations (then multiplies; then the earlier, with more bands
// by lobes). reason says what was compared.
std::vector<BandMethod> cheapest_band_methods(const Module& module, const ModuleOptions& options,
                                              const sh::BandMatrices& quarter_turn, std::string& reason) {
  const int n = module.order, free_bands = std::max(n - 2, 0);
  std::vector<std::vector<BandMethod>> candidates;
  if (free_bands <= codegen::kMaxExhaustiveMethodBands) {
    for (int mask = 0; mask < (1 << free_bands); ++mask) {
      std::vector<BandMethod> m(n, BandMethod::kLobes);
      for (int l = 2; l < n; ++l)
        if (mask >> (l - 2) & 1) m[l] = BandMethod::kZxzxz;
      candidates.push_back(m);
    }
  } else {
    for (int from = n; from >= 2; --from) {
      std::vector<BandMethod> m(n, BandMethod::kLobes);
      for (int l = from; l < n; ++l) m[l] = BandMethod::kZxzxz;
      candidates.push_back(m);
    }
  }
  for (size_t i = 0, plain = candidates.size(); i < plain && n > 2; ++i)
    if (candidates[i][2] == BandMethod::kLobes) {
      candidates.push_back(candidates[i]);
      candidates.back()[2] = BandMethod::kQuadratic;
    }
  std::vector<BandMethod> best;
  OpCount best_count;
  OpCount all_lobes, all_zxzxz;
  for (const std::vector<BandMethod>& m : candidates) {
    const OpCount c = rotation_op_count(module, options, m, quarter_turn);
    const long by_lobes = std::count(m.begin() + std::min(n, 2), m.end(), BandMethod::kLobes);
    if (by_lobes == free_bands) all_lobes = c;
    if (std::count(m.begin() + std::min(n, 2), m.end(), BandMethod::kZxzxz) == free_bands) all_zxzxz = c;
    if (best.empty() || operations(c) < operations(best_count) || (operations(c) == operations(best_count) && c.multiplies < best_count.multiplies)) {
      best = m;
      best_count = c;
    }
  }
  auto describe = [](const OpCount& c) {
    return std::to_string(c.multiplies) + " multiplies, " + std::to_string(c.adds) + " adds" +
           (c.others ? ", " + std::to_string(c.others) + " others" : "");
  };
  reason = "fewest operations in rotate_order" + std::to_string(n) + " among " + std::to_string(candidates.size()) +
           " assignments: " + describe(best_count) + " (every band by lobes: " + describe(all_lobes) +
           "; every band by zxzxz: " + describe(all_zxzxz) + ")";
  return best;
}

runtime::LobeStage automatic_lobe_stage(const runtime::LobeTable& table) {
  using namespace zhf::tolerance;
  return float_lobe_error_model(table.order, table.worst_condition()) > kFloatRotation ? runtime::LobeStage::kDouble
                                                                                       : runtime::LobeStage::kFloat;
}

double lanes_float_error_model(const runtime::LobeTable& table) {
  double worst = 0;
  for (const runtime::TableBand& band : table.bands)
    worst = std::max(worst, runtime::band_amplification(runtime::band_matrix(table, band.l)));
  return zhf::tolerance::kFloatEpsilon * (table.order - 1) * worst;
}

int lobe_weight_multiplies(const runtime::Matrix& inverse) {
  Graph g;
  return g.count(band_sums(g, inverse, /*transpose=*/true, 0)).multiplies;
}

int lobe_rotation_multiplies(const runtime::LobeTable& table) {
  ModuleOptions options;
  options.sh_eval = options.lobe_multiplies = options.batch = options.products = options.shading = false;
  options.standard_channels = {1};
  options.tailored_channels = {};
  options.band_method = BandMethod::kLobes;
  const Module module = build_module(table, options);
  const Function& rotate = module.functions.at(0);
  return rotate.graph.count(rotate.output_nodes()).multiplies;
}

int lobe_dependent_multiplies(const runtime::LobeTable& table) { return lobe_dependent_op_count(table).multiplies; }
}  // namespace zhf::codegen
