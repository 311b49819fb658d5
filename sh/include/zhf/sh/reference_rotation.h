// Double-precision reference SH rotations: two independent constructions of the band
// matrices D_l with g_l = D_l f_l for g(w) = f(R^T w).
#pragma once

#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "zhf/sh/rotation_matrix.h"

namespace zhf::sh {

using BandMatrices = std::vector<Eigen::MatrixXd>;  // entry l is (2l+1)^2, rows m'+l, cols m+l

// Ivanic & Ruedenberg's recurrence (J. Phys. Chem. 1996, with the 1998 errata): each band
// from band 1 and the previous band (runtime/band_recurrence.h, as Eigen matrices).
BandMatrices ivanic_ruedenberg(const RotationMatrix& r, int order);

// Projection of f(R^T w) back onto the SH basis with a product quadrature that is exact for
// the band-limited integrands (Gauss-Legendre in z x uniform phi): D_l[m'][m] =
// sum_k w_k y_l^m'(w_k) y_l^m(R^T w_k). Slow, but shares nothing with the recurrence.
BandMatrices quadrature_rotation(const RotationMatrix& r, int order);

// Applies band matrices to a coefficient vector of order matrices.size().
Eigen::VectorXd apply_band_matrices(const BandMatrices& bands, const Eigen::VectorXd& f);

// The largest error of a linear rotation method over all unit inputs, for one rotation with
// exact band matrices `exact`: the error is linear in f up to rounding, so over unit f the
// largest |error_i| is the norm of row i of E = K - D, K's columns the method's outputs for the
// basis vectors (rotate(in, out) on T). A random unit f sees that row about N/3 times smaller.
// Sets *row to the worst row; a NaN anywhere gives infinity.
template <class T, class Rotate>
double worst_unit_input_error(const BandMatrices& exact, Rotate&& rotate, int* row = nullptr) {
  const int n = static_cast<int>(exact.size() * exact.size());
  Eigen::MatrixXd error(n, n);
  std::vector<T> basis(n, T(0)), out(n);
  for (int c = 0; c < n; ++c) {
    basis[c] = T(1);
    rotate(basis.data(), out.data());
    basis[c] = T(0);
    const Eigen::VectorXd column = apply_band_matrices(exact, Eigen::VectorXd::Unit(n, c));
    for (int i = 0; i < n; ++i) error(i, c) = double(out[i]) - column[i];
  }
  int worst_row = 0;
  const double worst = error.rowwise().norm().maxCoeff(&worst_row);
  if (row) *row = worst_row;
  return worst == worst ? worst : INFINITY;
}

// Gauss-Legendre nodes and weights on [-1, 1] (weights sum to 2).
void gauss_legendre(int n, std::vector<double>& nodes, std::vector<double>& weights);

}  // namespace zhf::sh
