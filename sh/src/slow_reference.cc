#include "zhf/sh/slow_reference.h"

#include <cmath>
#include <cstdlib>

#include "zhf/runtime/sh_eval.h"

namespace zhf::sh::slow {
namespace {

long double binomial(int n, int k) {
  long double result = 1;
  for (int i = 1; i <= k; ++i) result = result * (n - k + i) / i;
  return result;
}

long double falling_factorial(int n, int k) {
  long double result = 1;
  for (int i = 0; i < k; ++i) result *= (n - i);
  return result;
}

}  // namespace

long double closed_form_legendre(int l, int m, long double theta) {
  const long double x = std::cos(theta);
  long double derivative = 0;
  for (int k = 0; 2 * k <= l; ++k) {
    const int power = l - 2 * k;
    if (power < m) continue;
    const long double sign = (k % 2 == 0) ? 1.0L : -1.0L;
    derivative += sign * binomial(l, k) * binomial(2 * l - 2 * k, l) * falling_factorial(power, m) *
                  std::pow(x, power - m);
  }
  derivative /= std::pow(2.0L, l);
  return std::pow(std::sin(theta), m) * derivative;
}

long double recurrence_legendre(int l, int m, long double theta) {
  const long double x = std::cos(theta);
  long double p_mm = std::pow(std::sin(theta), m);
  for (int k = 1; k <= m; ++k) p_mm *= (2 * k - 1);
  if (l == m) return p_mm;
  long double p_prev = p_mm;
  long double p = x * (2 * m + 1) * p_mm;
  for (int n = m + 1; n < l; ++n) {
    const long double next = ((2 * n + 1) * x * p - (n + m) * p_prev) / (n - m + 1);
    p_prev = p;
    p = next;
  }
  return p;
}

long double normalisation(int l, int m) {
  const int am = std::abs(m);
  const long double log_ratio = std::lgamma((long double)(l - am + 1)) - std::lgamma((long double)(l + am + 1));
  long double k = std::sqrt((2 * l + 1) / (4 * runtime::kPiLong) * std::exp(log_ratio));
  if (m != 0) k *= std::sqrt(2.0L);
  return k;
}

long double real_sh(int l, int m, long double theta, long double phi, bool use_closed_form) {
  const int am = std::abs(m);
  const long double p = use_closed_form ? closed_form_legendre(l, am, theta) : recurrence_legendre(l, am, theta);
  long double angular = 1;
  if (m > 0) angular = std::cos(am * phi);
  if (m < 0) angular = std::sin(am * phi);
  return normalisation(l, m) * p * angular;
}

}  // namespace zhf::sh::slow
