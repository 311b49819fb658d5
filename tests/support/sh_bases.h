// Degree <= 3 real SH bases written out as polynomials, from each system's evaluation code
// (docs/conventions.md), independent of zhf's recurrence: the oracles of the convention and
// splat tests.
#pragma once

#include <vector>

namespace zhf::test {

// zhf's, as polynomials (no recurrence): Sloan's real SH without the phase.
inline std::vector<double> zhf_polynomials(double x, double y, double z) {
  const double xx = x * x, yy = y * y, zz = z * z;
  return {0.28209479177387814,
          0.4886025119029199 * y, 0.4886025119029199 * z, 0.4886025119029199 * x,
          1.0925484305920792 * x * y, 1.0925484305920792 * y * z, 0.31539156525252005 * (2 * zz - xx - yy),
          1.0925484305920792 * x * z, 0.5462742152960396 * (xx - yy),
          0.5900435899266435 * y * (3 * xx - yy), 2.890611442640554 * x * y * z, 0.4570457994644658 * y * (4 * zz - xx - yy),
          0.3731763325901154 * z * (2 * zz - 3 * xx - 3 * yy), 0.4570457994644658 * x * (4 * zz - xx - yy),
          1.445305721320277 * z * (xx - yy), 0.5900435899266435 * x * (xx - 3 * yy)};
}

// graphdeco-inria/gaussian-splatting utils/sh_utils.py, eval_sh: C0..C3 and their signs.
inline std::vector<double> gaussian_splatting_basis(double x, double y, double z) {
  const double c1 = 0.4886025119029199;
  const double c2[5] = {1.0925484305920792, -1.0925484305920792, 0.31539156525252005, -1.0925484305920792, 0.5462742152960396};
  const double c3[7] = {-0.5900435899266435, 2.890611442640554, -0.4570457994644658, 0.3731763325901154,
                        -0.4570457994644658, 1.445305721320277, -0.5900435899266435};
  const double xx = x * x, yy = y * y, zz = z * z;
  return {0.28209479177387814, -c1 * y, c1 * z, -c1 * x,
          c2[0] * x * y, c2[1] * y * z, c2[2] * (2 * zz - xx - yy), c2[3] * x * z, c2[4] * (xx - yy),
          c3[0] * y * (3 * xx - yy), c3[1] * x * y * z, c3[2] * y * (4 * zz - xx - yy), c3[3] * z * (2 * zz - 3 * xx - 3 * yy),
          c3[4] * x * (4 * zz - xx - yy), c3[5] * z * (xx - yy), c3[6] * x * (xx - 3 * yy)};
}

}  // namespace zhf::test
