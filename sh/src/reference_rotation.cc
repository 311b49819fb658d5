#include "zhf/sh/reference_rotation.h"

#include <cmath>
#include <cstdlib>

#include "zhf/runtime/rotation.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/sh/legendre.h"

namespace zhf::sh {
namespace {

// Band matrix accessor with m, n in [-l, l].
struct BandView {
  Eigen::MatrixXd& m;
  int l;
  double& operator()(int row, int col) { return m(row + l, col + l); }
};
struct ConstBandView {
  const Eigen::MatrixXd& m;
  int l;
  double operator()(int row, int col) const { return m(row + l, col + l); }
};

// Ivanic-Ruedenberg helper P^l_{i,a,b} (their eq. 8.5 with the errata).
double ir_p(int i, int a, int b, int l, const ConstBandView& r1, const ConstBandView& prev) {
  if (b == l) return r1(i, 1) * prev(a, l - 1) - r1(i, -1) * prev(a, -l + 1);
  if (b == -l) return r1(i, 1) * prev(a, -l + 1) + r1(i, -1) * prev(a, l - 1);
  return r1(i, 0) * prev(a, b);
}

double ir_u(int m, int n, int l, const ConstBandView& r1, const ConstBandView& prev) {
  return ir_p(0, m, n, l, r1, prev);
}

double ir_v(int m, int n, int l, const ConstBandView& r1, const ConstBandView& prev) {
  if (m == 0) return ir_p(1, 1, n, l, r1, prev) + ir_p(-1, -1, n, l, r1, prev);
  if (m > 0) {
    const double d = (m == 1) ? 1.0 : 0.0;
    return ir_p(1, m - 1, n, l, r1, prev) * std::sqrt(1 + d) - ir_p(-1, -m + 1, n, l, r1, prev) * (1 - d);
  }
  const double d = (m == -1) ? 1.0 : 0.0;
  return ir_p(1, m + 1, n, l, r1, prev) * (1 - d) + ir_p(-1, -m - 1, n, l, r1, prev) * std::sqrt(1 + d);
}

double ir_w(int m, int n, int l, const ConstBandView& r1, const ConstBandView& prev) {
  if (m > 0) return ir_p(1, m + 1, n, l, r1, prev) + ir_p(-1, -m - 1, n, l, r1, prev);
  return ir_p(1, m - 1, n, l, r1, prev) - ir_p(-1, -m + 1, n, l, r1, prev);
}

}  // namespace

BandMatrices ivanic_ruedenberg(const RotationMatrix& r, int order) {
  BandMatrices bands;
  if (order <= 0) return bands;
  bands.push_back(Eigen::MatrixXd::Ones(1, 1));
  if (order == 1) return bands;
  // Band 1 is c (y, z, x): its matrix is R restricted to the axes in that order.
  const int* axis_of_m = runtime::kBand1Axis;
  Eigen::MatrixXd band1(3, 3);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) band1(i, j) = r(axis_of_m[i], axis_of_m[j]);
  bands.push_back(band1);
  // Views into `bands` would dangle when it grows: band 1 is read from its own copy.
  const ConstBandView r1{band1, 1};
  for (int l = 2; l < order; ++l) {
    Eigen::MatrixXd band(2 * l + 1, 2 * l + 1);
    BandView out{band, l};
    const ConstBandView prev{bands[l - 1], l - 1};
    for (int m = -l; m <= l; ++m) {
      for (int n = -l; n <= l; ++n) {
        const int am = std::abs(m);
        const double denom = (std::abs(n) == l) ? (2.0 * l) * (2.0 * l - 1) : double(l + n) * (l - n);
        const double delta_m0 = (m == 0) ? 1.0 : 0.0;
        const double u = std::sqrt(double(l + m) * (l - m) / denom);
        const double v = 0.5 * std::sqrt((1 + delta_m0) * double(l + am - 1) * (l + am) / denom) * (1 - 2 * delta_m0);
        const double w = -0.5 * std::sqrt(double(l - am - 1) * (l - am) / denom) * (1 - delta_m0);
        double value = 0;
        if (u != 0) value += u * ir_u(m, n, l, r1, prev);
        if (v != 0) value += v * ir_v(m, n, l, r1, prev);
        if (w != 0) value += w * ir_w(m, n, l, r1, prev);
        out(m, n) = value;
      }
    }
    bands.push_back(std::move(band));
  }
  return bands;
}

void gauss_legendre(int n, std::vector<double>& nodes, std::vector<double>& weights) {
  nodes.clear();
  weights.clear();
  // Nodes are cos of the roots of P_n(cos theta); P_n'(z) from Q_n^1 (see legendre.h).
  const std::vector<double> thetas = legendre_roots_theta(n, 0);
  const double to_p = std::sqrt(4 * 3.14159265358979323846 / (2 * n + 1));  // P_n = to_p Q_n^0
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
  const double pi = 3.14159265358979323846;
  std::vector<double> y_at(runtime::coefficient_count(order)), y_back(runtime::coefficient_count(order));
  for (size_t k = 0; k < nodes.size(); ++k) {
    const double sin_theta = std::sqrt(std::max(0.0, 1 - nodes[k] * nodes[k]));
    for (int j = 0; j < phi_count; ++j) {
      const double phi = 2 * pi * j / phi_count;
      const Eigen::Vector3d w(sin_theta * std::cos(phi), sin_theta * std::sin(phi), nodes[k]);
      const Eigen::Vector3d back = r.transpose() * w;
      runtime::eval_sh(order, w.data(), y_at.data());
      runtime::eval_sh(order, back.data(), y_back.data());
      const double weight = weights[k] * 2 * pi / phi_count;
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
