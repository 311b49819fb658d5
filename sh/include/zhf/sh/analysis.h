// What a set of SH coefficient vectors needs: per-band energy, truncation error per order,
// known-zero bands, and whether each signal is zonal (and about which axis).
#pragma once

#include <vector>

#include <Eigen/Core>

namespace zhf::sh {

// Zonal test by the rotation generators: f is zonal about a exactly when the generator of
// rotations about a, sum_k a_k L_k, annihilates it. With G_jk = <L_j f, L_k f> (3x3, symmetric,
// positive semi-definite), a is the eigenvector of G's smallest eigenvalue, and
// residual = sqrt(lambda_min) / |f_{l>=1}| is 0 for a zonal f (relative, scale-free).
struct ZonalFit {
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // unit; sign: the lowest odd band's weight > 0, else largest component > 0
  double residual = 0;                              // 0 for an exactly zonal function
  std::vector<double> weights;                      // zonal[l]: y_l^0 weight about the axis
  bool constant = false;                            // bands >= 1 are all zero: any axis
};
ZonalFit fit_zonal(const Eigen::VectorXd& f);

// The rotation generators of band l, (2l+1)^2 each, for axes x, y, z: d/dt D_l(rot(e_k, t)) at 0.
std::vector<Eigen::MatrixXd> band_generators(int l);

struct EnergyReport {
  int order = 0;
  std::vector<double> band_energy;       // summed over signals
  std::vector<double> truncation_error;  // [N-1]: relative L2 error of keeping bands 0..N-1, N = 1..order
  int smallest_order = 0;                // the smallest N with truncation_error <= tolerance
  std::vector<int> zero_bands;           // bands below smallest_order droppable within the remaining budget
};
EnergyReport analyze_energy(const std::vector<Eigen::VectorXd>& signals, double tolerance);

// The relative L2 error within which a band limit or a zonal fit counts as found when the caller
// names none (zhf analyze --tolerance, zhf.analyze): a goal the user may change.
inline constexpr double kDefaultZonalFit = 1e-3;  // an input, not a tolerance

}  // namespace zhf::sh
