// The zonal fast path. A function symmetric about a unit axis a is, band by band,
//   f_{l,m} = sqrt(4 pi / (2l+1)) zonal[l] y_l^m(a),
// with zonal[l] its y_l^0 weight when a = +z. Rotating it by R is re-evaluating at R a: N^2
// work, no lobes, no band matrices. The fast choice whenever a signal is zonal (a clamped
// cosine, a Phong lobe, a point light's irradiance); zhf analyze says whether data is.
// Accuracy: that of the SH evaluation (sh_eval.h); tested against the reference rotation up to
// order 16.
#pragma once

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "zhf/runtime/limits.h"
#include "zhf/runtime/sh_eval.h"

namespace zhf::runtime {

template <class T>
class ZonalRotator {
 public:
  // Throws std::invalid_argument for an order outside 1..kMaxShOrder.
  explicit ZonalRotator(int order) : order_(order), legendre_(checked(order)) {
    for (int l = 0; l < order; ++l) scale_.push_back(std::sqrt(4 * kPi / band_size(l)));
  }
  int order() const { return order_; }

  // out (N^2) = the coefficients of the zonal function (axis, zonal[0..N-1]) turned by R.
  void rotate(const T r[9], const T axis[3], const T* zonal, T* out) const {
    const T v[3] = {r[0] * axis[0] + r[1] * axis[1] + r[2] * axis[2], r[3] * axis[0] + r[4] * axis[1] + r[5] * axis[2],
                    r[6] * axis[0] + r[7] * axis[1] + r[8] * axis[2]};
    project(v, zonal, out);
  }

  // out (N^2) = the coefficients of the zonal function about the unit axis.
  void project(const T axis[3], const T* zonal, T* out) const {
    eval_sh<T>(order_, axis, out, legendre_);
    for (int l = 0; l < order_; ++l) {
      const T w = T(scale_[l]) * zonal[l];
      for (int i = l * l; i < (l + 1) * (l + 1); ++i) out[i] *= w;
    }
  }

 private:
  static int checked(int order) {
    if (order < 1 || order > kMaxShOrder)
      throw std::invalid_argument("ZonalRotator: order " + std::to_string(order) + " is outside 1.." + std::to_string(kMaxShOrder));
    return order;
  }

  int order_;
  TabulatedLegendreCoefficients legendre_;
  std::vector<double> scale_;
};

}  // namespace zhf::runtime
