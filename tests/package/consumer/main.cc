// Rotates SH vectors through the installed headers and checks the result as a function:
// g(w) = f(R^T w) at a few directions. Order 4 through its generated kernels, and the order of
// the lobe table given on the command line (an installed one) through the table path.
#include <cmath>
#include <cstdio>
#include <vector>

#include "zhf/dispatch/rotator.h"
#include "zhf/runtime/table_io.h"
#include "zhf/runtime/rotation.h"
#include "zhf/runtime/rotator.h"
#include "zhf/runtime/tolerances.h"
#include "zhf_order4.h"

namespace rt = zhf::runtime;

// Unit-norm coefficients, so a coefficient error e moves f(w) by at most e sqrt(N^2 / 4 pi).
template <class T>
std::vector<T> unit_vector(int n, double phase) {
  std::vector<T> f(n);
  double norm = 0;
  for (int i = 0; i < n; ++i) norm += std::cos(1.7 * i + phase) * std::cos(1.7 * i + phase);
  for (int i = 0; i < n; ++i) f[i] = T(std::cos(1.7 * i + phase) / std::sqrt(norm));
  return f;
}

// max over directions of |g(w) - f(R^T w)|.
template <class T>
double function_error(int order, const double r[9], const std::vector<T>& f, const std::vector<T>& g) {
  double worst = 0;
  const int n = order * order;
  std::vector<double> yw(n), yrw(n);
  for (int k = 0; k < 7; ++k) {
    double w[3] = {std::sin(0.9 * k + 0.3) * std::cos(2.1 * k), std::sin(0.9 * k + 0.3) * std::sin(2.1 * k),
                   std::cos(0.9 * k + 0.3)};
    double rtw[3];  // R^T w
    for (int i = 0; i < 3; ++i) rtw[i] = r[i] * w[0] + r[3 + i] * w[1] + r[6 + i] * w[2];
    rt::eval_sh(order, w, yw.data());
    rt::eval_sh(order, rtw, yrw.data());
    double gw = 0, frtw = 0;
    for (int i = 0; i < n; ++i) {
      gw += yw[i] * double(g[i]);
      frtw += yrw[i] * double(f[i]);
    }
    worst = std::fmax(worst, std::fabs(gw - frtw));
  }
  return worst;
}

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: consumer LOBE_TABLE.json\n");
    return 2;
  }
  const double axis[3] = {0.48, 0.6, 0.64};
  const rt::Matrix3 r = rt::rotation_about_unit_axis(axis, 1.1);
  float rf[9];
  for (int i = 0; i < 9; ++i) rf[i] = float(r[i]);

  const std::vector<float> f4 = unit_vector<float>(16, 0.2);
  std::vector<float> g4(16);
  rt::Rotator<float>::of<4>().rotate(rf, f4.data(), g4.data());
  const double error4 = function_error(4, r.data(), f4, g4);

  const rt::LobeTable table = rt::read_lobe_table(argv[1]);
  const int n = table.order * table.order;
  const std::vector<double> ft = unit_vector<double>(n, 0.4);
  std::vector<double> gt(n);
  rt::Rotator<double>::from_table(table).rotate(r.data(), ft.data(), gt.data());
  const double error_table = function_error(table.order, r.data(), ft, gt);

  // The compiled library, on the CPU's fastest path.
  const auto fastest = zhf::dispatch::Rotator<float>::make(6);
  const std::vector<float> f6 = unit_vector<float>(36, 0.3);
  std::vector<float> g6(36);
  fastest.rotate(rf, f6.data(), g6.data());
  const double error6 = function_error(6, r.data(), f6, g6);

  std::printf("order 4 (float kernels): %.2e; order %d (table): %.2e; order 6 (%s, %s): %.2e\n", error4, table.order, error_table,
              zhf::dispatch::isa_name(fastest.isa()), fastest.path().c_str(), error6);
  const double scale4 = std::sqrt(16 / (4 * rt::kPi)), scale6 = std::sqrt(36 / (4 * rt::kPi)), scale_table = std::sqrt(n / (4 * rt::kPi));
  const bool ok = error4 <= rt::tolerance::kFloatRotation * scale4 && error_table <= rt::tolerance::kDouble * scale_table &&
                  error6 <= rt::tolerance::kFloatRotation * scale6;
  return ok ? 0 : 1;
}
