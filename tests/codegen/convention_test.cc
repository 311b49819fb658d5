// Kernels emitted in the Condon-Shortley sign convention (zhf emit --convention 3dgs): every
// function's graph, evaluated in double, equals zhf's function on the arguments taken into zhf's
// terms (R -> K R K, directions -> K d, coefficients -> S f, K = diag(-1, -1, 1), S = (-1)^m),
// and costs the same multiplies. zhf's own functions are verified against the reference by
// `zhf verify`; the printers do not depend on the convention.
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "graph_eval.h"
#include "test_support.h"
#include "zhf/codegen/kernels.h"
#include "zhf/runtime/table_io.h"
#include "zhf/runtime/tolerances.h"
#include "zhf/sh/random.h"
#include "zhf/sh/rotation_matrix.h"

namespace zhf {
namespace {

using Values = test::GraphInputs;
using test::evaluate;

// Negations the simplifier cannot fold (a negated input that is an output, or leads a sum of
// negated terms): measured at most 11 adds at order 5 (rotation_matrices), against 365 to 503
// operations; no extra multiplies ever.
constexpr int kMaxUnfoldedNegations = 12;

bool odd_m(int i) {
  const int l = runtime::band_of(i);
  return (i - l * (l + 1)) % 2 != 0;
}

TEST(Conventions, CondonShortleyKernelsAreZhfsOnTheArgumentsInZhfsTerms) {
  const runtime::LobeTable table = runtime::read_lobe_table(std::string(ZHF_SOURCE_DIR) + "/generated/lobes/order_5.json");
  codegen::ModuleOptions options;
  options.dense_channels = {1};
  options.zonal_channels = {1};
  options.lobe_stage = runtime::LobeStage::kDouble;  // the graph in double throughout
  const codegen::Module zhf_module = codegen::build_module(table, options);
  options.condon_shortley = true;
  const codegen::Module cs_module = codegen::build_module(table, options);
  ASSERT_EQ(zhf_module.functions.size(), cs_module.functions.size());
  std::mt19937_64 rng(31);
  sh::Normal<> normal;
  int checked = 0;
  for (std::size_t k = 0; k < cs_module.functions.size(); ++k) {
    const codegen::Function& cs = cs_module.functions[k];
    const codegen::Function& zhf = zhf_module.functions[k];
    ASSERT_EQ(cs.name, zhf.name);
    if (cs.channels != 1 || cs.batch) continue;
    for (int trial = 0; trial < 5; ++trial) {
      Values system(cs.params.size()), in_zhf_terms(cs.params.size());
      for (std::size_t p = 0; p < cs.params.size(); ++p) {
        const codegen::Param& param = cs.params[p];
        if (param.output) continue;
        std::vector<double>& x = system[p];
        if (param.name == "R") {
          const runtime::Matrix3 r = sh::to_array(sh::random_rotation(rng));
          x.assign(r.begin(), r.end());
        } else if (param.name == "dir" || param.name == "axis") {
          const Eigen::Vector3d d = sh::random_direction(rng);
          x = {d[0], d[1], d[2]};
        } else {
          for (int i = 0; i < param.size; ++i) x.push_back(normal(rng));
        }
        in_zhf_terms[p] = x;
        std::vector<double>& z = in_zhf_terms[p];
        if (param.name == "R") {
          for (int i : {2, 5, 6, 7}) z[i] = -z[i];
        } else if (param.name == "dir" || param.name == "axis") {
          z[0] = -z[0], z[1] = -z[1];
        } else if (cs.kind == codegen::KernelKind::kLobeWeights || cs.kind == codegen::KernelKind::kProduct ||
                   cs.kind == codegen::KernelKind::kSquare || cs.kind == codegen::KernelKind::kShade ||
                   param.name == "transfer") {
          for (int i = 0; i < param.size; ++i)
            if (odd_m(i)) z[i] = -z[i];
        } else if (cs.kind == codegen::KernelKind::kShadeLobes) {  // bands 0 and 1 are coefficients
          for (int i : {1, 3}) z[i] = -z[i];
        }
      }
      const auto got = evaluate(cs, system);
      auto expected = evaluate(zhf, in_zhf_terms);
      if (cs.kind == codegen::KernelKind::kFromSamples || cs.kind == codegen::KernelKind::kProduct ||
          cs.kind == codegen::KernelKind::kSquare)
        for (auto& [where, value] : expected)
          if (odd_m(where.second)) value = -value;
      for (const auto& [where, value] : expected)
        ASSERT_NEAR(got.at(where), value, runtime::tolerance::kDouble)
            << cs.name << ", output " << where.second << " (band " << runtime::band_of(where.second) << "), trial " << trial;
    }
    const codegen::OpCount zhf_ops = zhf.graph.count(zhf.output_nodes()), cs_ops = cs.graph.count(cs.output_nodes());
    EXPECT_EQ(cs_ops.multiplies, zhf_ops.multiplies) << cs.name;
    EXPECT_LE(cs_ops.adds, zhf_ops.adds + kMaxUnfoldedNegations) << cs.name << ": the negations should fold into the sums";
    ++checked;
  }
  EXPECT_GE(checked, 7);  // sh_eval, lobe weights, from samples, rotate, tailored, matrices, apply, zonal
}

}  // namespace
}  // namespace zhf
