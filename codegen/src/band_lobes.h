// The lobe method's graph pieces (kernels.h: rotation by lobes), composed into kernels by
// kernels.cc: a band's sparse stage, the scaled Legendre recurrences of the homogeneous band
// polynomials, and the lobes rescaled and rotated.
#pragma once

#include <vector>

#include "zhf/codegen/expr.h"
#include "zhf/runtime/lobe_table.h"
#include "zhf/runtime/sh_eval.h"

namespace zhf::codegen {

inline constexpr double kSqrt3Over4Pi = 0.48860251190291992159;  // band 1: c (y, z, x)

struct Vec3 {
  int c[3];
};

// Band l's sparse stage on inputs base.. base + 2l: out_i = sum_k A[k][i] x_k (transpose: the
// lobe weights z = A^T f) or sum_k A[i][k] x_k (coefficients from lobe samples).
std::vector<int> band_sums(Graph& g, const runtime::Matrix& inverse, bool transpose, int base);

// Scaled Legendre recurrences for the homogeneous band-l polynomials (runtime/sh_eval.h, whose
// coefficients they are built from):
//   q_m^m = 1, q_{m+1}^m = z, q_l^m = z q_{l-1}^m - c_{l,m}(r2) q_{l-2}^m,
// with Q_l^m = sigma_{l,m} q_l^m; sigma depends on l, m only, so it moves to the output.
struct Legendre {
  std::vector<std::vector<double>> sigma;  // [l][m]
  explicit Legendre(int order);
  // c_{l,m}(r2) = b r2 sigma_{l-2} / sigma_{l-1}.
  double c(int l, int m, double r2) const;
  // y_l^{+-m} = output_scale * q_l^m * (C_m or S_m).
  double output_scale(int l, int m) const;
};

// H_{l,m}(v) / output_scale for the bands marked at v (given r2 = |v|^2); entry [index(l, m)],
// -1 where not computed.
std::vector<int> homogeneous_sh(Graph& g, const Vec3& v, double r2, int order, const std::vector<bool>& bands,
                                const Legendre& legendre);

// Lobe direction rescaled so R u costs additions only where the components allow.
void scale_lobe(const double w[3], double u[3]);

double norm2(const double u[3]);

// v = M u where M is R (transpose = false) or R^T, R's nine nodes row-major.
Vec3 rotated_lobe(Graph& g, const std::vector<int>& r, const double u[3], bool transpose);

// Param 0 (R) projected onto the rotations by one Newton step toward its polar factor,
// Q = R (3 I - R^T R) / 2. A float R is orthonormal to about eps_f only, and the lobe fit
// amplifies its symmetric part by the band's condition number (1.3e-6 at order 7 with every
// later step exact); after the step, done in the wide type, what remains is O(eps_f^2).
std::vector<int> orthonormalized_rotation(Graph& g);

}  // namespace zhf::codegen
