// Slow, obviously-correct SH evaluation in long double, sharing no code with runtime/sh_eval.h; used
// only to test the fast paths.
#pragma once

namespace zhf::sh::slow {

// P_l^m(cos theta) (no Condon-Shortley phase) from the explicit sum
// P_l(x) = 2^-l sum_k (-1)^k C(l,k) C(2l-2k,l) x^{l-2k}, differentiated m times, times
// sin^m(theta) (taken from theta, not from 1-x^2, which cancels near the poles).
// Cancellation in the sum grows with l: trustworthy to ~1e-15 relative for l <= 12.
long double closed_form_legendre(int l, int m, long double theta);

// P_l^m(cos theta) from the unnormalised upward recurrence
// (l-m+1) P_{l+1}^m = (2l+1) x P_l^m - (l+m) P_{l-1}^m, P_m^m = (2m-1)!! sin^m(theta);
// long double's range holds (2l)! for l <= 64, so no scaling is needed.
long double recurrence_legendre(int l, int m, long double theta);

// sqrt((2l+1)/(4 pi) (l-|m|)!/(l+|m|)!), times sqrt2 for m != 0.
long double normalisation(int l, int m);

// y_l^m(theta, phi) in zhf's convention (m<0: sin(|m| phi), m>0: cos(m phi)).
long double real_sh(int l, int m, long double theta, long double phi, bool use_closed_form = true);

}  // namespace zhf::sh::slow
