#include "healpix_method.h"

#include <cmath>

#include <alm.h>
#include <alm_powspec_tools.h>
#include <rotmatrix.h>
#include <xcomplex.h>

namespace zhf::bench {

struct HealpixRotator::State {
  int order;
  mutable Alm<xcomplex<double>> alm;
  explicit State(int n) : order(n), alm(n - 1, n - 1) {}

  // zhf's real y_l^{+-m} (no Condon-Shortley phase) against complex Y_lm (with it):
  // y_{l,m} = sqrt2 (-1)^m Re Y_lm, y_{l,-m} = sqrt2 (-1)^m Im Y_lm, so a real function's
  // a_lm = (-1)^m (f_m - i f_-m) / sqrt2 for m > 0 and a_l0 = f_0.
  void to_complex(const double* f) const {
    for (int l = 0; l < order; ++l) {
      const double* band = f + l * l + l;
      alm(l, 0) = xcomplex<double>(band[0], 0);
      for (int m = 1; m <= l; ++m) {
        const double s = (m % 2 ? -1.0 : 1.0) / std::sqrt(2.0);
        alm(l, m) = xcomplex<double>(s * band[m], -s * band[-m]);
      }
    }
  }
  void to_real(double* f) const {
    for (int l = 0; l < order; ++l) {
      double* band = f + l * l + l;
      band[0] = alm(l, 0).real();
      for (int m = 1; m <= l; ++m) {
        const double s = (m % 2 ? -1.0 : 1.0) * std::sqrt(2.0);
        band[m] = s * alm(l, m).real();
        band[-m] = -s * alm(l, m).imag();
      }
    }
  }
};

HealpixRotator::HealpixRotator(int order) : state_(std::make_unique<State>(order)) {}
HealpixRotator::~HealpixRotator() = default;

void HealpixRotator::rotate(const double r[9], const double* in, double* out) const {
  state_->to_complex(in);
  rotate_alm(state_->alm, rotmatrix(r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7], r[8]));
  state_->to_real(out);
}

void HealpixRotator::convert_only(const double*, const double* in, double* out) const {
  state_->to_complex(in);
  state_->to_real(out);
}

}  // namespace zhf::bench
