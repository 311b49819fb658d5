// zhf's real SH coefficients and the HEALPix C++ library's complex a_lm (Alm<xcomplex<double>>,
// l_max = m_max = N - 1 for order N).
//
// zhf's real y_l^{+-m} have no Condon-Shortley phase; HEALPix's complex Y_lm have it:
// y_{l,m} = sqrt2 (-1)^m Re Y_lm and y_{l,-m} = sqrt2 (-1)^m Im Y_lm for m > 0, so a real
// function's a_lm = (-1)^m (f_{l,m} - i f_{l,-m}) / sqrt2 and a_l0 = f_l0. (Checked against
// healpy, written independently, by crosscheck/healpix_crosscheck.py.) Cost: O(N^2).
#pragma once

#include <alm.h>
#include <xcomplex.h>

namespace zhf::healpix {

using ComplexAlm = Alm<xcomplex<double>>;

// f holds N^2 coefficients, N = alm.Lmax() + 1 (alm.Mmax() == alm.Lmax()).
void real_to_alm(const double* f, ComplexAlm& alm);
void alm_to_real(const ComplexAlm& alm, double* f);

}  // namespace zhf::healpix
