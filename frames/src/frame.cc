#include "zhf/frames/frame.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <Eigen/Dense>

#include "zhf/frames/limits.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/tolerances/tolerances.h"

namespace zhf::frames {
namespace {

void check(const std::vector<Point>& directions, int lmin, int lmax) {
  if (directions.empty()) throw std::invalid_argument("a frame needs at least one direction");
  if (lmin < 0 || lmax < lmin || lmax > frames::kMaxFrameBand)
    throw std::invalid_argument("bands " + std::to_string(lmin) + ".." + std::to_string(lmax) + " are not within 0.." +
                                std::to_string(frames::kMaxFrameBand));
}

// Phi: row i holds y_l^m(w_i) for the bands of the range.
Eigen::MatrixXd analysis(const std::vector<Point>& directions, int lmin, int lmax) {
  const int first = lmin * lmin, dimension = (lmax + 1) * (lmax + 1) - first;
  Eigen::MatrixXd phi(directions.size(), dimension);
  std::vector<double> y((lmax + 1) * (lmax + 1));
  for (size_t i = 0; i < directions.size(); ++i) {
    runtime::eval_sh(lmax + 1, directions[i].data(), y.data());
    for (int k = 0; k < dimension; ++k) phi(i, k) = y[first + k];
  }
  return phi;
}

}  // namespace

bool FrameBounds::parseval() const { return tight() && std::abs(lower - 1) <= zhf::tolerance::kTightFrame && std::abs(upper - 1) <= zhf::tolerance::kTightFrame; }

double FrameBounds::condition() const {
  return frame() ? std::sqrt(upper / lower) : std::numeric_limits<double>::infinity();
}

FrameBounds frame_bounds(const std::vector<Point>& directions, int lmin, int lmax) {
  check(directions, lmin, lmax);
  const Eigen::MatrixXd phi = analysis(directions, lmin, lmax);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(phi.transpose() * phi, Eigen::EigenvaluesOnly);
  FrameBounds b;
  b.lmin = lmin;
  b.lmax = lmax;
  b.directions = static_cast<int>(directions.size());
  b.dimension = static_cast<int>(phi.cols());
  // Rounding can leave a singular operator's smallest eigenvalue a hair below zero.
  b.lower = std::max(0.0, eigen.eigenvalues().minCoeff());
  b.upper = eigen.eigenvalues().maxCoeff();
  return b;
}

}  // namespace zhf::frames
