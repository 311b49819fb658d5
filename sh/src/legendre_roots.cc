#include <cmath>
#include <stdexcept>
#include <string>

#include "zhf/runtime/limits.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/legendre.h"

namespace zhf::sh {

double legendre_q_derivative(int l, int m, double z) {
  if (m >= l) return 0.0;
  return std::sqrt(double(l + m + 1) * double(l - m)) * runtime::legendre_q<double>(l, m + 1, z);
}

namespace {

// f(theta) = Q_l^m(cos theta): same roots in (0, pi) as P_l^m(cos theta).
double q_of_theta(int l, int m, double theta) { return runtime::legendre_q<double>(l, m, std::cos(theta)); }

double polish_root(int l, int m, double lo, double hi) {
  double f_lo = q_of_theta(l, m, lo);
  for (int it = 0; it < 200 && hi - lo > zhf::tolerance::kRootBracket; ++it) {
    const double mid = 0.5 * (lo + hi);
    const double f_mid = q_of_theta(l, m, mid);
    if ((f_mid < 0) == (f_lo < 0)) {
      lo = mid;
      f_lo = f_mid;
    } else {
      hi = mid;
    }
  }
  // Newton in long double: cos(theta) rounded to double alone would cost a few ulps of theta
  // near the poles. d/dtheta Q(cos theta) = -sin(theta) sqrt((l+m+1)(l-m)) Q_l^{m+1}.
  using Wide = long double;
  Wide theta = 0.5L * (Wide(lo) + Wide(hi));
  const Wide derivative_scale = std::sqrt(Wide(l + m + 1) * Wide(l - m));
  for (int it = 0; it < 6; ++it) {
    const Wide z = std::cos(theta);
    const Wide f = runtime::legendre_q<Wide>(l, m, z);
    const Wide df = -std::sin(theta) * derivative_scale * runtime::legendre_q<Wide>(l, m + 1, z);
    if (f == 0 || df == 0) break;
    const Wide step = f / df;
    if (!(std::abs(step) < zhf::tolerance::kRootPolishStep)) break;  // only a polish: never leave the bracket
    theta -= step;
  }
  return static_cast<double>(theta);
}

}  // namespace

std::vector<double> legendre_roots_theta(int l, int m) {
  if (l < 0 || m < 0 || m > l || l > runtime::kMaxShOrder) {
    throw std::invalid_argument("legendre_roots_theta: need 0 <= m <= l <= " + std::to_string(runtime::kMaxShOrder));
  }
  // P_l^m(cos theta) has parity (-1)^(l-m) about the equator, so the roots are found in
  // (0, pi/2), mirrored exactly, and pi/2 itself is a root when l-m is odd.
  const double half_pi = 1.57079632679489661923;
  const double pi = 2 * half_pi;
  const int expected_half = (l - m) / 2;
  std::vector<double> half;
  // Neighbouring roots are about pi/(l+1) apart; refine until every one is bracketed.
  for (int samples = 16 * (l + 1); expected_half > 0 && samples <= 1 << 20; samples *= 4) {
    half.clear();
    double prev_theta = 0;
    double prev = q_of_theta(l, m, prev_theta);
    for (int i = 1; i < samples; ++i) {
      const double theta = half_pi * i / samples;
      const double value = q_of_theta(l, m, theta);
      if (value == 0.0) {
        half.push_back(theta);
      } else if (prev != 0.0 && (value < 0) != (prev < 0)) {
        half.push_back(polish_root(l, m, prev_theta, theta));
      }
      prev = value;
      prev_theta = theta;
    }
    if (static_cast<int>(half.size()) == expected_half) break;
  }
  if (static_cast<int>(half.size()) != expected_half) {
    throw std::runtime_error("legendre_roots_theta: could not bracket all roots of P_" + std::to_string(l) + "^" +
                             std::to_string(m));
  }
  std::vector<double> roots(half);
  if ((l - m) % 2 == 1) roots.push_back(half_pi);
  for (auto it = half.rbegin(); it != half.rend(); ++it) roots.push_back(pi - *it);
  return roots;
}

}  // namespace zhf::sh
