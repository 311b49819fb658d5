// The zxzxz method's graph pieces (kernels.h: rotation by zxzxz), composed into kernels by
// kernels.cc: cos and sin of the multiples of R's zyz Euler angles, found without the angles,
// and one band turned by them between two quarter turns.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "zhf/codegen/expr.h"

namespace zhf::codegen {

// cos and sin of m t for m <= the top band marked, t each zyz Euler angle of R (param 0;
// runtime::zyz_multiples does the same steps in double); empty when no band is marked.
struct EulerTurns {
  std::vector<int> cos_a, sin_a, cos_b, sin_b, cos_g, sin_g;
};
EulerTurns euler_turns(Graph& g, const std::vector<bool>& bands);

// Band l (v[m + l]) rotated by zxzxz: Z(a) X^T Z(b) X Z(g) v, with x = X_l = D_l(Rx(+90 deg)).
std::vector<int> zxzxz_band(Graph& g, int l, const EulerTurns& t, const Eigen::MatrixXd& x, std::vector<int> v);

}  // namespace zhf::codegen
