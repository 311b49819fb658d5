// The quadratic method's graph (kernels.h: band 2 as a quadratic form), composed into kernels by
// kernels.cc.
#pragma once

#include <vector>

#include "zhf/codegen/expr.h"

namespace zhf::codegen {

// Band 2 (v[m + 2]) rotated by R (param 0) as a quadratic form: sum_m f_m y_2^m(u) = (K/2) u^T M u
// on the unit sphere (K = sqrt(15 / 4 pi)), M symmetric and traceless (u^T u = 1 absorbs the
// trace), and g(u) = f(R^T u) has M' = R M R^T. 36 multiplies and no square root; zxzxz's band 2
// costs less only where higher bands already pay for the Euler angles.
std::vector<int> quadratic_band(Graph& g, const std::vector<int>& v);

}  // namespace zhf::codegen
