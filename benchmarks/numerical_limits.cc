// The README's "Numerical limits" table: per order and precision, the worst lobe-matrix
// condition and the max abs error over 10^4 random rotations of random unit-norm vectors
// against the double reference. Orders 2..8 through the generated kernels, above that through
// the runtime's table path (every table present in generated/lobes).
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>

#include "zhf/runtime/limits.h"
#include "zhf/runtime/rotator.h"
#include "zhf_kernels.h"
#include "zhf/runtime/table_io.h"
#include "zhf/sh/random.h"
#include "zhf/sh/reference_rotation.h"

namespace {

template <class T>
double max_error(const zhf::runtime::Rotator<T>& rotator, int order, int trials) {
  std::mt19937_64 rng(order);
  zhf::sh::Normal<> normal;
  const int n = order * order;
  double worst = 0;
  std::vector<T> r(9), in(n), out(n);
  for (int k = 0; k < trials; ++k) {
    const zhf::sh::RotationMatrix m = zhf::sh::random_rotation(rng);
    Eigen::VectorXd f(n);
    for (int i = 0; i < n; ++i) f[i] = normal(rng);
    f.normalize();
    const Eigen::VectorXd g = zhf::sh::apply_band_matrices(zhf::sh::ivanic_ruedenberg(m, order), f);
    for (int i = 0; i < 9; ++i) r[i] = static_cast<T>(m(i / 3, i % 3));
    for (int i = 0; i < n; ++i) in[i] = static_cast<T>(f[i]);
    rotator.rotate(r.data(), in.data(), out.data());
    for (int i = 0; i < n; ++i) worst = std::max(worst, std::abs(double(out[i]) - g[i]));
  }
  return worst;
}

}  // namespace

int main(int argc, char** argv) {
  const int trials = argc > 1 ? std::atoi(argv[1]) : 10000;
  const std::string lobes = std::string(ZHF_SOURCE_DIR) + "/generated/lobes/";
  std::printf("| order | path | worst condition | float max error | double max error |\n| --- | --- | --- | --- | --- |\n");
  int highest_float = 0, highest_double = 0;
  for (int order = 2; order <= zhf::runtime::kMaxTableOrder; ++order) {
    const std::string path = zhf::runtime::table_path(lobes, order);
    if (order > 2 && !std::filesystem::exists(path)) continue;
    const double condition = order == 2 ? 1.0 : zhf::runtime::read_lobe_table(path, order).worst_condition();
    const bool generated = order <= zhf::runtime::kMaxGeneratedOrder;
    auto make = [&](auto tag) {
      using T = decltype(tag);
      return generated ? zhf::runtime::Rotator<T>::with(zhf::gen::scalar_kernels<T>(order))
                       : zhf::runtime::Rotator<T>::from_table(zhf::runtime::read_lobe_table(path, order));
    };
    const double e_float = max_error(make(float{}), order, trials);
    const double e_double = max_error(make(double{}), order, trials);
    std::printf("| %d | %s | %.2f | %.2e | %.2e |\n", order, generated ? "generated" : "runtime table", condition, e_float,
                e_double);
    std::fflush(stdout);
    if (e_float < zhf::runtime::tolerance::kRuntimeOrdersFloat) highest_float = order;
    if (e_double < zhf::runtime::tolerance::kDouble) highest_double = order;
  }
  std::printf("\nhighest order with float error < %g: %d; with double error < %g: %d (of the orders above)\n",
              zhf::runtime::tolerance::kRuntimeOrdersFloat, highest_float, zhf::runtime::tolerance::kDouble, highest_double);
}
