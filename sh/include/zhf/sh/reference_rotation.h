// Double-precision reference SH rotations: two independent constructions of the band
// matrices D_l with g_l = D_l f_l for g(w) = f(R^T w).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "zhf/sh/rotation_matrix.h"

namespace zhf::sh {

using BandMatrices = std::vector<Eigen::MatrixXd>;  // entry l is (2l+1)^2, rows m'+l, cols m+l

// Ivanic & Ruedenberg's recurrence (J. Phys. Chem. 1996, with the 1998 errata): each band
// from band 1 and the previous band.
BandMatrices ivanic_ruedenberg(const Matrix3& r, int order);

// Projection of f(R^T w) back onto the SH basis with a product quadrature that is exact for
// the band-limited integrands (Gauss-Legendre in z x uniform phi): D_l[m'][m] =
// sum_k w_k y_l^m'(w_k) y_l^m(R^T w_k). Slow, but shares nothing with the recurrence.
BandMatrices quadrature_rotation(const Matrix3& r, int order);

// Applies band matrices to a coefficient vector of order matrices.size().
Eigen::VectorXd apply_band_matrices(const BandMatrices& bands, const Eigen::VectorXd& f);

// Gauss-Legendre nodes and weights on [-1, 1] (weights sum to 2).
void gauss_legendre(int n, std::vector<double>& nodes, std::vector<double>& weights);

}  // namespace zhf::sh
