// Each way a rotation kernel can rotate a band (lobes, zxzxz; quadratic at band 2), forced, against the
// double reference at orders 3..8 on the extreme rotations (identity, half turns, gimbal lock at
// beta = 0 and pi, tiny turns, lobes onto the pole) and random ones, in double and in float: the
// graph itself, rounded as the emitted C++ rounds it. `zhf verify` runs the printed kernels.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "graph_eval.h"
#include "test_support.h"
#include "zhf/codegen/kernels.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/runtime/table_io.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/random.h"
#include "zhf/sh/reference_rotation.h"
#include "zhf/sh/rotation_matrix.h"

namespace zhf {
namespace {

constexpr int kRandomRotations = 20;

const codegen::Function& find(const codegen::Module& module, codegen::KernelKind kind) {
  for (const codegen::Function& f : module.functions)
    if (f.kind == kind && f.channels == 1) return f;
  throw std::runtime_error("no such function");
}

TEST(BandMethods, EachMethodForEveryBandMatchesTheReferenceAtExtremeRotations) {
  for (int order = 3; order <= 8; ++order) {
    const runtime::LobeTable table = runtime::read_lobe_table(test::checked_in_table(order));
    std::vector<Eigen::Vector3d> lobes;
    for (const auto& l : table.lobes) lobes.emplace_back(l.xyz[0], l.xyz[1], l.xyz[2]);
    std::vector<std::pair<std::string, sh::RotationMatrix>> rotations = sh::extreme_rotations(lobes);
    std::mt19937_64 rng(700 + order);
    for (int k = 0; k < kRandomRotations; ++k) rotations.push_back({"random " + std::to_string(k), sh::random_rotation(rng)});
    for (codegen::BandMethod method : {codegen::BandMethod::kLobes, codegen::BandMethod::kZxzxz, codegen::BandMethod::kQuadratic}) {
      codegen::ModuleOptions options;
      options.band_method = method;
      options.products = options.sh_eval = options.lobe_multiplies = false;
      const codegen::Module module = codegen::build_module(table, options);
      const bool quadratic = method == codegen::BandMethod::kQuadratic;
      ASSERT_EQ(module.band_methods[2], method);
      for (int l = 3; l < order; ++l) ASSERT_EQ(module.band_methods[l], quadratic ? codegen::BandMethod::kZxzxz : method);
      const codegen::Function& rotate = find(module, codegen::KernelKind::kRotate);
      const codegen::Function& shade = find(module, codegen::KernelKind::kShade);
      const bool in_double = module.rotation_lobe_stage() == runtime::LobeStage::kDouble;
      const double float_tolerance = runtime::tolerance::float_rotation(order, table.worst_condition(), in_double);
      const double float_shading = zhf::tolerance::float_shading(order, table.worst_condition(), in_double);
      sh::Normal<> normal;
      for (const auto& [name, r] : rotations) {
        Eigen::VectorXd f(order * order), t(order * order);
        for (int i = 0; i < f.size(); ++i) f[i] = normal(rng), t[i] = normal(rng);
        f.normalize();
        t.normalize();
        // Inputs exactly floats, so the float and double runs rotate the same vector.
        std::vector<double> rd(9), ff(f.size()), tf(t.size());
        for (int i = 0; i < 9; ++i) rd[i] = r(i / 3, i % 3);
        for (int i = 0; i < f.size(); ++i) ff[i] = float(f[i]), tf[i] = float(t[i]);
        const Eigen::VectorXd fin = Eigen::Map<const Eigen::VectorXd>(ff.data(), f.size());
        const Eigen::VectorXd tin = Eigen::Map<const Eigen::VectorXd>(tf.data(), t.size());
        // Float runs see R rounded, which turns band l by ~l eps_f more: inside float_rotation.
        const Eigen::VectorXd expected = sh::apply_band_matrices(sh::ivanic_ruedenberg(r, order), fin);
        const std::string what = std::string(codegen::band_method_name(method)) + ", order " + std::to_string(order) +
                                 ", rotation '" + name + "'";
        const auto in_double_run = test::evaluate<double>(rotate, {rd, ff, {}});
        const auto in_float_run = test::evaluate<float>(rotate, {rd, ff, {}});
        for (int i = 0; i < f.size(); ++i) {
          const int l = runtime::band_of(i);
          EXPECT_NEAR(in_double_run.at({2, i}), expected[i], runtime::tolerance::kDouble)
              << what << ", double, band " << l << ", index " << i;
          EXPECT_NEAR(in_float_run.at({2, i}), expected[i], float_tolerance) << what << ", float, band " << l << ", index " << i;
        }
        const double shaded = expected.dot(tin);
        EXPECT_NEAR(test::evaluate<double>(shade, {rd, ff, tf, {}}).at({3, 0}), shaded, runtime::tolerance::kDouble)
            << what << ", shade double";
        EXPECT_NEAR(test::evaluate<float>(shade, {rd, ff, tf, {}}).at({3, 0}), shaded, float_shading) << what << ", shade float";
      }
    }
  }
}

}  // namespace
}  // namespace zhf
