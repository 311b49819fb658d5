#include "zhf/healpix/alm.h"

#include <cmath>

#include "zhf/runtime/sh_eval.h"

namespace zhf::healpix {

void real_to_alm(const double* f, ComplexAlm& alm) {
  for (int l = 0; l <= alm.Lmax(); ++l) {
    alm(l, 0) = xcomplex<double>(f[runtime::index(l, 0)], 0);
    for (int m = 1; m <= l; ++m) {
      const double s = (m % 2 ? -1.0 : 1.0) / std::sqrt(2.0);
      alm(l, m) = xcomplex<double>(s * f[runtime::index(l, m)], -s * f[runtime::index(l, -m)]);
    }
  }
}

void alm_to_real(const ComplexAlm& alm, double* f) {
  for (int l = 0; l <= alm.Lmax(); ++l) {
    f[runtime::index(l, 0)] = alm(l, 0).real();
    for (int m = 1; m <= l; ++m) {
      const double s = (m % 2 ? -1.0 : 1.0) * std::sqrt(2.0);
      f[runtime::index(l, m)] = s * alm(l, m).real();
      f[runtime::index(l, -m)] = -s * alm(l, m).imag();
    }
  }
}

}  // namespace zhf::healpix
