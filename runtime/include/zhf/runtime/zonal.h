// The zonal fast path. A function symmetric about a unit axis a is, band by band,
//   f_{l,m} = sqrt(4 pi / (2l+1)) zonal[l] y_l^m(a),
// with zonal[l] its y_l^0 weight when a = +z. Rotating it by R is re-evaluating at R a: N^2
// work, no lobes, no band matrices. The fast choice whenever a signal is zonal (a clamped
// cosine, a Phong lobe, a point light's irradiance); zhf analyze says whether data is.
#pragma once

#include <cmath>
#include <vector>

#include "zhf/runtime/sh_band.h"

namespace zhf::runtime {

template <class T>
class ZonalRotator {
 public:
  explicit ZonalRotator(int order) : order_(order) {
    for (int l = 0; l < order; ++l) {
      bands_.emplace_back(l);
      scale_.push_back(std::sqrt(4 * 3.14159265358979323846 / (2 * l + 1)));
    }
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
    for (int l = 0; l < order_; ++l) {
      T* band = out + l * l;
      bands_[l](axis, band);
      const T w = T(scale_[l]) * zonal[l];
      for (int i = 0; i < 2 * l + 1; ++i) band[i] *= w;
    }
  }

 private:
  int order_;
  std::vector<BandEvaluator<T>> bands_;
  std::vector<double> scale_;
};

}  // namespace zhf::runtime
