#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/analysis.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Eigenvalues>

#include "zhf/runtime/sh_eval.h"
#include "zhf/sh/reference_rotation.h"
#include "zhf/sh/rotation_matrix.h"

namespace zhf::sh {
namespace {

using runtime::kPi;

int order_of(const Eigen::VectorXd& f) {
  const int order = static_cast<int>(std::lround(std::sqrt(static_cast<double>(f.size()))));
  if (order * order != f.size()) throw std::invalid_argument("fit_zonal: coefficient count is not a square");
  return order;
}

}  // namespace

std::vector<Eigen::MatrixXd> band_generators(int l) {
  const int size = 2 * l + 1;
  // About z: g(phi) = f(phi - t) turns each (cos m phi, sin m phi) pair by m t, so
  // d/dt at 0 sends the m > 0 weight a and the -m weight b to (-m b, m a).
  Eigen::MatrixXd lz = Eigen::MatrixXd::Zero(size, size);
  for (int m = 1; m <= l; ++m) {
    lz(l + m, l - m) = -m;
    lz(l - m, l + m) = m;
  }
  // About x and y: conjugate by fixed quarter turns carrying z onto x (about y) and onto y
  // (about x), since rot(Q e_z, t) = Q rot(e_z, t) Q^T and D is a representation.
  const RotationMatrix z_to_x = rotation_about_axis(Eigen::Vector3d::UnitY(), kPi / 2);
  const RotationMatrix z_to_y = rotation_about_axis(Eigen::Vector3d::UnitX(), -kPi / 2);
  const Eigen::MatrixXd qx = ivanic_ruedenberg(z_to_x, l + 1)[l];
  const Eigen::MatrixXd qy = ivanic_ruedenberg(z_to_y, l + 1)[l];
  return {qx * lz * qx.transpose(), qy * lz * qy.transpose(), lz};
}

ZonalFit fit_zonal(const Eigen::VectorXd& f) {
  const int order = order_of(f);
  ZonalFit fit;
  fit.weights.assign(order, 0.0);
  fit.weights[0] = f[0];  // y_0^0 is constant: f_00 = sqrt(4 pi) zonal[0] y_0^0 = zonal[0]
  const double energy = f.size() > 1 ? f.tail(f.size() - 1).squaredNorm() : 0.0;
  if (energy == 0) {
    fit.constant = true;
    return fit;
  }
  std::vector<Eigen::MatrixXd> moved;  // per band: L_x f_l, L_y f_l, L_z f_l as columns
  Eigen::Matrix3d gram = Eigen::Matrix3d::Zero();
  for (int l = 1; l < order; ++l) {
    const Eigen::VectorXd band = f.segment(l * l, 2 * l + 1);
    const std::vector<Eigen::MatrixXd> gen = band_generators(l);
    moved.emplace_back(2 * l + 1, 3);
    for (int k = 0; k < 3; ++k) moved.back().col(k) = gen[k] * band;
    gram += moved.back().transpose() * moved.back();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(gram);
  fit.axis = eigen.eigenvectors().col(0).normalized();
  // |sum_k a_k L_k f| directly: sqrt(lambda_min) would carry sqrt(eps) of rounding.
  double moved_energy = 0;
  for (const Eigen::MatrixXd& m : moved) moved_energy += (m * fit.axis).squaredNorm();
  fit.residual = std::sqrt(moved_energy / energy);
  // Orient: y_l(-a) = (-1)^l y_l(a), so an odd band's weight fixes the sign.
  auto weight = [&](int l) {
    std::vector<double> y(static_cast<size_t>(order) * order);
    runtime::eval_sh(order, fit.axis.data(), y.data());
    double dot = 0;
    for (int m = -l; m <= l; ++m) dot += f[runtime::index(l, m)] * y[runtime::index(l, m)];
    return dot * std::sqrt(4 * kPi / (2 * l + 1));
  };
  bool oriented = false;
  for (int l = 1; l < order && !oriented; l += 2) {
    const double w = weight(l);
    if (std::abs(w) > zhf::tolerance::kOrientingWeight * std::sqrt(energy)) {
      if (w < 0) fit.axis = -fit.axis;
      oriented = true;
    }
  }
  if (!oriented) {
    int largest = 0;
    for (int k = 1; k < 3; ++k)
      if (std::abs(fit.axis[k]) > std::abs(fit.axis[largest])) largest = k;
    if (fit.axis[largest] < 0) fit.axis = -fit.axis;
  }
  for (int l = 1; l < order; ++l) fit.weights[l] = weight(l);
  return fit;
}

EnergyReport analyze_energy(const std::vector<Eigen::VectorXd>& signals, double tolerance) {
  EnergyReport r;
  if (signals.empty()) return r;
  r.order = order_of(signals.front());
  r.band_energy.assign(r.order, 0.0);
  for (const Eigen::VectorXd& f : signals)
    for (int l = 0; l < r.order; ++l) r.band_energy[l] += f.segment(l * l, 2 * l + 1).squaredNorm();
  double total = 0;
  for (double e : r.band_energy) total += e;
  const double budget = tolerance * tolerance * total;
  // tail[N] = energy of bands N..order-1.
  std::vector<double> tail(r.order + 1, 0.0);
  for (int l = r.order - 1; l >= 0; --l) tail[l] = tail[l + 1] + r.band_energy[l];
  r.smallest_order = 0;
  for (int n = 1; n <= r.order; ++n) {
    r.truncation_error.push_back(total > 0 ? std::sqrt(tail[n] / total) : 0.0);
    if (r.smallest_order == 0 && tail[n] <= budget) r.smallest_order = n;  // tail[order] = 0 always qualifies
  }
  // Drop the quietest bands below that order while the whole error stays within tolerance.
  std::vector<int> bands;
  for (int l = 0; l < r.smallest_order; ++l) bands.push_back(l);
  std::sort(bands.begin(), bands.end(), [&](int a, int b) { return r.band_energy[a] < r.band_energy[b]; });
  double dropped = tail[r.smallest_order];
  for (int l : bands) {
    if (dropped + r.band_energy[l] > budget || static_cast<int>(r.zero_bands.size()) + 1 == r.smallest_order) break;
    dropped += r.band_energy[l];
    r.zero_bands.push_back(l);
  }
  std::sort(r.zero_bands.begin(), r.zero_bands.end());
  return r;
}

}  // namespace zhf::sh
