// Normalised associated Legendre functions and their roots (candidate lobe polar angles).
#pragma once

#include <vector>

namespace zhf::sh {

// Q_l^m(z) as in eval.h (K_l^m d^m P_l/dz^m), so P_l^m-normalised = (1-z^2)^{m/2} Q_l^m.
double legendre_q(int l, int m, double z);

// dQ_l^m/dz = sqrt((l+m+1)(l-m)) Q_l^{m+1}(z).
double legendre_q_derivative(int l, int m, double z);

// The l-m roots of P_l^m(cos theta) in (0, pi), ascending, to full double precision:
// bracketed on a fine theta grid, bisected, then Newton-polished on the recurrence.
std::vector<double> legendre_roots_theta(int l, int m);

}  // namespace zhf::sh
