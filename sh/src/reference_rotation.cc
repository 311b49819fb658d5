#include "zhf/sh/reference_rotation.h"

#include <cmath>
#include <cstdlib>

#include "zhf/runtime/band_recurrence.h"
#include "zhf/runtime/rotation.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/sh/legendre.h"

namespace zhf::sh {

BandMatrices ivanic_ruedenberg(const RotationMatrix& r, int order) {
  const std::vector<std::vector<double>> flat = runtime::recurrence_band_matrices(r.data(), order);
  BandMatrices bands;
  for (std::size_t l = 0; l < flat.size(); ++l) {
    const int side = 2 * int(l) + 1;
    bands.push_back(Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(flat[l].data(), side, side));
  }
  return bands;
}

void gauss_legendre(int n, std::vector<double>& nodes, std::vector<double>& weights) {
  nodes.clear();
  weights.clear();
  // Nodes are cos of the roots of P_n(cos theta); P_n'(z) from Q_n^1 (see legendre.h).
  const std::vector<double> thetas = legendre_roots_theta(n, 0);
  const double to_p = std::sqrt(4 * runtime::kPi / (2 * n + 1));  // P_n = to_p Q_n^0
  for (auto it = thetas.rbegin(); it != thetas.rend(); ++it) {
    const double z = std::cos(*it);
    const double dp = to_p * legendre_q_derivative(n, 0, z);
    nodes.push_back(z);
    weights.push_back(2.0 / ((1 - z * z) * dp * dp));
  }
}

BandMatrices quadrature_rotation(const RotationMatrix& r, int order) {
  BandMatrices bands;
  for (int l = 0; l < order; ++l) bands.push_back(Eigen::MatrixXd::Zero(2 * l + 1, 2 * l + 1));
  // Integrands are products of two band-l functions: degree <= 2(order-1) in z and in phi.
  std::vector<double> nodes, weights;
  gauss_legendre(order, nodes, weights);
  const int phi_count = 2 * order;
  std::vector<double> y_at(runtime::coefficient_count(order)), y_back(runtime::coefficient_count(order));
  for (size_t k = 0; k < nodes.size(); ++k) {
    const double sin_theta = std::sqrt(std::max(0.0, 1 - nodes[k] * nodes[k]));
    for (int j = 0; j < phi_count; ++j) {
      const double phi = 2 * runtime::kPi * j / phi_count;
      const Eigen::Vector3d w(sin_theta * std::cos(phi), sin_theta * std::sin(phi), nodes[k]);
      const Eigen::Vector3d back = r.transpose() * w;
      runtime::eval_sh(order, w.data(), y_at.data());
      runtime::eval_sh(order, back.data(), y_back.data());
      const double weight = weights[k] * 2 * runtime::kPi / phi_count;
      for (int l = 0; l < order; ++l) {
        for (int a = -l; a <= l; ++a) {
          const double wa = weight * y_at[runtime::index(l, a)];
          for (int b = -l; b <= l; ++b) bands[l](a + l, b + l) += wa * y_back[runtime::index(l, b)];
        }
      }
    }
  }
  return bands;
}

Eigen::VectorXd apply_band_matrices(const BandMatrices& bands, const Eigen::VectorXd& f) {
  Eigen::VectorXd g(f.size());
  for (size_t l = 0; l < bands.size(); ++l) {
    const int start = static_cast<int>(l * l);
    const int size = static_cast<int>(2 * l + 1);
    g.segment(start, size) = bands[l] * f.segment(start, size);
  }
  return g;
}

}  // namespace zhf::sh
