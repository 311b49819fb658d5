// One Newton step toward a nearly orthonormal R's polar factor, Q = R (3 I - R^T R) / 2, in a
// wider type W. A float R is orthonormal to eps_f only, and a lobe fit amplifies its symmetric
// part by the band's condition number; after the step what remains is O(eps_f^2). The generated
// kernels whose lobe stage runs in double do the same step (codegen/src/kernels.cc).
#pragma once

namespace zhf::runtime {

template <class W, class T>
inline void polar_step(const T r[9], W q[9]) {
  W step[9];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      W gram = 0;
      for (int k = 0; k < 3; ++k) gram += W(r[3 * k + i]) * W(r[3 * k + j]);
      step[3 * i + j] = (i == j ? W(1.5) : W(0)) - W(0.5) * gram;
    }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      W sum = 0;
      for (int k = 0; k < 3; ++k) sum += W(r[3 * i + k]) * step[3 * k + j];
      q[3 * i + j] = sum;
    }
}

}  // namespace zhf::runtime
