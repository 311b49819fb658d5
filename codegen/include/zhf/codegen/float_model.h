// The float error model of a rotation through lobes, shared by the code generator (which decides
// where the lobe stage runs) and verify (which holds kernels to it).
#pragma once

namespace zhf::codegen {

// Float kernels: max abs error target for unit coefficient vectors.
inline constexpr double kFloatRotationTarget = 1e-6;
inline constexpr double kFloatEpsilon = 5.9604644775390625e-08;  // 2^-24

// eps_f (N - 1) k_max: each rotated lobe is rounded to float, band-l SH turn that into about
// l eps_f, and A_l amplifies it by up to its condition number (k_max over the bands).
inline double float_lobe_error_model(int order, double worst_condition) {
  return kFloatEpsilon * (order - 1) * worst_condition;
}

}  // namespace zhf::codegen
