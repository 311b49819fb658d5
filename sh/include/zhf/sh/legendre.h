// Roots of the normalised associated Legendre functions (candidate lobe polar angles), and the
// derivative Newton needs. Q_l^m itself is runtime::legendre_q (runtime/sh_eval.h).
#pragma once

#include <vector>

namespace zhf::sh {

// dQ_l^m/dz = sqrt((l+m+1)(l-m)) Q_l^{m+1}(z).
double legendre_q_derivative(int l, int m, double z);

// The l-m roots of P_l^m(cos theta) in (0, pi), ascending, to full double precision:
// bracketed on a fine theta grid, bisected, then Newton-polished on the recurrence.
std::vector<double> legendre_roots_theta(int l, int m);

}  // namespace zhf::sh
