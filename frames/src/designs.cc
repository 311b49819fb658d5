#include "zhf/frames/designs.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <stdexcept>

#include <Eigen/Dense>
#include <nlopt.hpp>

#include "zhf/frames/limits.h"
#include "zhf/runtime/band_recurrence.h"
#include "zhf/runtime/enum_names.h"
#include "zhf/runtime/errors.h"
#include "zhf/io/json.h"
#include "zhf/runtime/limits.h"
#include "zhf/runtime/parallel.h"
#include "zhf/runtime/read_file.h"
#include "zhf/runtime/rotation.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/random.h"

namespace zhf::frames {
namespace {

using runtime::kPi;
// Levenberg-Marquardt steps of one start of whole orbits, and its stall test: every kStallIterations
// steps the residual's norm must have fallen below kStallFactor of what it was.
constexpr int kOrbitIterations = 400;
constexpr int kStallIterations = 25;
// Dampings tried in one Levenberg-Marquardt step before the search gives up.
constexpr int kDampingAttempts = 12;
constexpr double kStallFactor = 0.5;
// Antipodal sets up to here: L-BFGS on the design energy from spiral starts, then polished (the
// smallest known counts at odd t = 11..21 come from it). Above, Levenberg-Marquardt on the pairs
// from random directions, as orbits of x -> -x, which is many times faster there.
constexpr int kLargestAntipodalEnergySearch = 21;

Point normalized(const Point& p) {
  const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
  return {p[0] / n, p[1] / n, p[2] / n};
}

// R p for a row-major 3x3 R.
Point turned(const double* r, const Point& p) {
  return {r[0] * p[0] + r[1] * p[1] + r[2] * p[2], r[3] * p[0] + r[4] * p[1] + r[5] * p[2], r[6] * p[0] + r[7] * p[1] + r[8] * p[2]};
}

// Two unit vectors spanning the tangent plane at x.
void tangents(const Point& x, Point& u, Point& v) {
  const int k = std::abs(x[0]) < std::abs(x[1]) ? (std::abs(x[0]) < std::abs(x[2]) ? 0 : 2) : (std::abs(x[1]) < std::abs(x[2]) ? 1 : 2);
  Point e{0, 0, 0};
  e[k] = 1;
  u = normalized({x[1] * e[2] - x[2] * e[1], x[2] * e[0] - x[0] * e[2], x[0] * e[1] - x[1] * e[0]});
  v = {x[1] * u[2] - x[2] * u[1], x[2] * u[0] - x[0] * u[2], x[0] * u[1] - x[1] * u[0]};
}

// The SH of bands 1..t at one point (all bands; or, for antipodal sets, the even bands only: odd
// ones cancel between x and -x).
class Evaluator {
 public:
  Evaluator(int t, bool symmetric) : t_(t), all_((t + 1) * (t + 1)) {
    for (int l = symmetric ? 2 : 1; l <= t; l += symmetric ? 2 : 1)
      for (int m = -l; m <= l; ++m) rows_.push_back(runtime::index(l, m));
  }
  int size() const { return static_cast<int>(rows_.size()); }
  void at(const Point& x, double* out) {
    runtime::eval_sh(t_ + 1, x.data(), all_.data());
    for (size_t k = 0; k < rows_.size(); ++k) out[k] = all_[rows_[k]];
  }
  // d/ds y(normalize(x + s w)) at s = 0.
  void derivative(const Point& x, const Point& w, double* out) {
    const double h = zhf::tolerance::kDesignDifferenceStep;
    std::vector<double> plus(size()), minus(size());
    at(normalized({x[0] + h * w[0], x[1] + h * w[1], x[2] + h * w[2]}), plus.data());
    at(normalized({x[0] - h * w[0], x[1] - h * w[1], x[2] - h * w[2]}), minus.data());
    for (int k = 0; k < size(); ++k) out[k] = (plus[k] - minus[k]) / (2 * h);
  }

 private:
  int t_;
  std::vector<double> all_;
  std::vector<int> rows_;
};

Eigen::VectorXd residual_vector(const std::vector<Point>& x, Evaluator& e) {
  Eigen::VectorXd r = Eigen::VectorXd::Zero(e.size()), y(e.size());
  for (const Point& p : x) {
    e.at(p, y.data());
    r += y;
  }
  return r;
}

// Energy and gradient over 3M free coordinates (each point normalised inside).
struct EnergyProblem {
  int count;
  Evaluator evaluator;
};

double energy(unsigned n, const double* p, double* gradient, void* data) {
  auto& problem = *static_cast<EnergyProblem*>(data);
  std::vector<Point> x(problem.count);
  for (unsigned i = 0; i < n / 3; ++i) x[i] = normalized({p[3 * i], p[3 * i + 1], p[3 * i + 2]});
  const Eigen::VectorXd r = residual_vector(x, problem.evaluator);
  if (gradient) {
    Eigen::VectorXd du(r.size()), dv(r.size());
    for (unsigned i = 0; i < n / 3; ++i) {
      Point u, v;
      tangents(x[i], u, v);
      problem.evaluator.derivative(x[i], u, du.data());
      problem.evaluator.derivative(x[i], v, dv.data());
      const double gu = 2 * r.dot(du), gv = 2 * r.dot(dv);
      const double length = std::sqrt(p[3 * i] * p[3 * i] + p[3 * i + 1] * p[3 * i + 1] + p[3 * i + 2] * p[3 * i + 2]);
      for (int c = 0; c < 3; ++c) gradient[3 * i + c] = (gu * u[c] + gv * v[c]) / length;
    }
  }
  return r.squaredNorm();
}

// One Levenberg-Marquardt step on points moved in their tangent planes (us, vs): step(lambda)
// gives the move, two coordinates a point; the damping grows tenfold after each move that fails to
// lower |r|, and the first that lowers it is kept (and the damping eased). False: none did.
template <class Step, class Residual>
bool damped_step(std::vector<Point>& x, const std::vector<Point>& us, const std::vector<Point>& vs, Eigen::VectorXd& r, double& lambda, Step&& step,
                 Residual&& residual) {
  for (int attempt = 0; attempt < kDampingAttempts; ++attempt) {
    const Eigen::VectorXd d = step(lambda);
    std::vector<Point> trial(x.size());
    for (std::size_t i = 0; i < x.size(); ++i)
      trial[i] = normalized({x[i][0] + d[2 * i] * us[i][0] + d[2 * i + 1] * vs[i][0], x[i][1] + d[2 * i] * us[i][1] + d[2 * i + 1] * vs[i][1],
                             x[i][2] + d[2 * i] * us[i][2] + d[2 * i + 1] * vs[i][2]});
    const Eigen::VectorXd next = residual(trial);
    if (next.squaredNorm() < r.squaredNorm()) {
      x.swap(trial);
      r = next;
      lambda = std::max(lambda / 10, zhf::tolerance::kDampingFloor);
      return true;
    }
    lambda *= 10;
  }
  return false;
}

// Levenberg-Marquardt on the residual vector, moving each point in its tangent plane.
void polish(std::vector<Point>& x, int t, bool symmetric) {
  Evaluator e(t, symmetric);
  const int m = static_cast<int>(x.size()), rows = e.size(), cols = 2 * m;
  Eigen::VectorXd r = residual_vector(x, e);
  double lambda = zhf::tolerance::kDampingStart;
  // On to the rounding floor, not just below zhf::tolerance::kDesignResidual: integrals of polynomials weigh the
  // residual by up to ~30 (4 pi over the SH normalisation).
  for (int iteration = 0; iteration < 100 && r.cwiseAbs().maxCoeff() > 0; ++iteration) {
    Eigen::MatrixXd j(rows, cols);
    std::vector<Point> us(m), vs(m);
    for (int i = 0; i < m; ++i) {
      tangents(x[i], us[i], vs[i]);
      e.derivative(x[i], us[i], j.col(2 * i).data());
      e.derivative(x[i], vs[i], j.col(2 * i + 1).data());
    }
    // The smaller normal system: J^T (J J^T + lambda I)^-1 r when there are fewer equations.
    const bool wide = rows < cols;
    const Eigen::MatrixXd normal = wide ? Eigen::MatrixXd(j * j.transpose()) : Eigen::MatrixXd(j.transpose() * j);
    const Eigen::VectorXd rhs = wide ? r : Eigen::VectorXd(j.transpose() * r);
    const bool improved = damped_step(x, us, vs, r, lambda, [&](double damping) {
      Eigen::MatrixXd a = normal;
      a.diagonal().array() += damping * (1 + a.diagonal().array());
      return wide ? Eigen::VectorXd(-j.transpose() * a.ldlt().solve(rhs)) : Eigen::VectorXd(-a.ldlt().solve(rhs));
    }, [&](const std::vector<Point>& trial) { return residual_vector(trial, e); });
    if (!improved) break;
  }
}

// Start k: the generalised spiral (equal-area rings), turned by a random rotation and, after the
// first start, jittered in its tangent planes by up to half the spacing.
std::vector<Point> start_points(int count, int k, std::uint64_t seed) {
  std::mt19937_64 rng(seed * 1000003 + static_cast<std::uint64_t>(k));
  sh::Normal<> normal;
  std::vector<Point> x(count);
  const double golden = kPi * (3 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double z = 1 - (2.0 * i + 1) / count, s = std::sqrt(std::max(0.0, 1 - z * z));
    x[i] = {s * std::cos(golden * i), s * std::sin(golden * i), z};
  }
  if (k == 0) return x;
  // A random rotation from a random unit quaternion.
  double q[4];
  double norm = 0;
  for (double& c : q) c = normal(rng), norm += c * c;
  for (double& c : q) c /= std::sqrt(norm);
  const double w = q[0], a = q[1], b = q[2], c = q[3];
  const double r[9] = {1 - 2 * (b * b + c * c), 2 * (a * b - w * c),     2 * (a * c + w * b),
                       2 * (a * b + w * c),     1 - 2 * (a * a + c * c), 2 * (b * c - w * a),
                       2 * (a * c - w * b),     2 * (b * c + w * a),     1 - 2 * (a * a + b * b)};
  const double spacing = std::sqrt(4 * kPi / count);
  for (Point& p : x) {
    p = turned(r, p);
    Point u, v;
    tangents(p, u, v);
    const double du = 0.5 * spacing * normal(rng) / 2, dv = 0.5 * spacing * normal(rng) / 2;
    p = normalized({p[0] + du * u[0] + dv * v[0], p[1] + du * u[1] + dv * v[1], p[2] + du * u[2] + dv * v[2]});
  }
  return x;
}

// One start: count free points (symmetric: count points and their antipodes).
Design run_start(int t, int count, bool symmetric, int k, std::uint64_t seed) {
  std::vector<Point> x = start_points(count, k, seed);
  EnergyProblem problem{count, Evaluator(t, symmetric)};
  nlopt::opt opt(nlopt::LD_LBFGS, 3 * count);
  opt.set_min_objective(energy, &problem);
  opt.set_ftol_abs(zhf::tolerance::kDesignEnergyAbsolute);
  opt.set_ftol_rel(zhf::tolerance::kDesignEnergyRelative);
  opt.set_maxeval(4000);
  std::vector<double> p;
  for (const Point& q : x) p.insert(p.end(), q.begin(), q.end());
  double value = 0;
  try {
    opt.optimize(p, value);
  } catch (const std::exception&) {
    // L-BFGS stops with a roundoff error near the minimum: the point reached is still its best.
  }
  for (int i = 0; i < count; ++i) x[i] = normalized({p[3 * i], p[3 * i + 1], p[3 * i + 2]});
  polish(x, t, symmetric);
  if (symmetric)
    for (int i = 0; i < count; ++i) x.push_back({-x[i][0], -x[i][1], -x[i][2]});
  Design d;
  d.t = t;
  d.residual = design_residual(x, t);
  d.points = std::move(x);
  d.start = d.residual <= zhf::tolerance::kDesignResidual ? k : -1;
  return d;
}

// A rotation group a design is made of whole orbits of, and its orbit sums in a cheap form: the
// SH of bands 1..t summed over an orbit {R g} equal weights (.) sum over copies of y(C g).
struct OrbitGroup {
  std::vector<runtime::Matrix3> rotations;
  std::vector<runtime::Matrix3> copies;
  std::vector<double> weights;  // per row of bands 1..t, in index order
  // The rotations' second half is the first half negated: a design lists its points under the
  // first half, then their negatives (the layout of antipodal designs).
  bool negatives_last = false;
};

// The chiral tetrahedral group: the 12 rotations that map the cube's diagonals to each other, a
// cyclic permutation of the axes times a diagonal of signs with an even number of -1. Its orbit
// sums take three evaluations instead of twelve: over the half turns about the axes each y_l^m
// sums to 4 y_l^m or to 0 (y_l^m(-x, -y, z) = (-1)^m y_l^m, and y_l^m(x, -y, -z) = (-1)^(l+m)
// y_l^m for m >= 0, -(-1)^(l+m) y_l^m for m < 0): 4 when m is even and l is even exactly when
// m >= 0; the copies are the three cyclic permutations.
OrbitGroup tetrahedral_group(int t) {
  OrbitGroup group;
  const double signs[4][3] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  for (int shift = 0; shift < 3; ++shift) {
    runtime::Matrix3 cycle{};
    for (int row = 0; row < 3; ++row) cycle[3 * row + (row + shift) % 3] = 1;
    group.copies.push_back(cycle);
    for (const auto& sign : signs) {
      runtime::Matrix3 r{};
      for (int row = 0; row < 3; ++row) r[3 * row + (row + shift) % 3] = sign[row];
      group.rotations.push_back(r);
    }
  }
  for (int l = 1; l <= t; ++l)
    for (int m = -l; m <= l; ++m) group.weights.push_back(m % 2 == 0 && (l % 2 == 0) == (m >= 0) ? 4.0 : 0.0);
  return group;
}

// The three turns about z by multiples of 120 degrees: over them y_l^m sums to 3 y_l^m when 3
// divides m and to 0 otherwise, so one evaluation an orbit.
OrbitGroup threefold_group(int t) {
  OrbitGroup group;
  const double c = -0.5, s = std::sqrt(3.0) / 2;
  group.rotations = {runtime::kIdentity, {c, -s, 0, s, c, 0, 0, 0, 1}, {c, s, 0, -s, c, 0, 0, 0, 1}};
  group.copies = {runtime::kIdentity};
  for (int l = 1; l <= t; ++l)
    for (int m = -l; m <= l; ++m) group.weights.push_back(m % 3 == 0 ? 3.0 : 0.0);
  return group;
}

// x -> -x alone: orbits of 2, the even bands' harmonics (weights 2), all of them invariant.
OrbitGroup antipodal_group(int t) {
  OrbitGroup group;
  group.rotations = {runtime::kIdentity, {-1, 0, 0, 0, -1, 0, 0, 0, -1}};
  group.copies = {runtime::kIdentity};
  for (int l = 1; l <= t; ++l)
    for (int m = -l; m <= l; ++m) group.weights.push_back(l % 2 ? 0.0 : 2.0);
  group.negatives_last = true;
  return group;
}

// The threefold turns and x -> -x: orbits of 6 (the turns and their negatives; D_l(-R) =
// (-1)^l D_l(R), the band matrices being homogeneous of degree l in R's entries). Over an orbit
// y_l^m sums to 6 y_l^m at the generator when l is even and 3 divides m, and to 0 otherwise.
OrbitGroup antipodal_threefold_group(int t) {
  OrbitGroup group = threefold_group(t);
  const std::size_t turns = group.rotations.size();
  for (std::size_t k = 0; k < turns; ++k) {
    runtime::Matrix3 negative = group.rotations[k];
    for (double& x : negative) x = -x;
    group.rotations.push_back(negative);
  }
  group.negatives_last = true;
  std::size_t row = 0;
  for (int l = 1; l <= t; ++l)
    for (int m = -l; m <= l; ++m, ++row) group.weights[row] = l % 2 ? 0.0 : 2 * group.weights[row];
  return group;
}

// Band l's invariants: the multiplicity of the trivial representation, (1/|G|) sum over the group
// of the band's character. Tetrahedral: (2l + 1 + 3 (-1)^l + 8 c_l) / 12 with c_l = 1, 0, -1 for
// l = 0, 1, 2 mod 3 (identity, three half turns, eight third turns). Threefold: 1 + 2 floor(l / 3)
// (m = 0 and the pairs +-m with 3 | m).
int tetrahedral_invariants(int l) { return (2 * l + 1 + (l % 2 ? -3 : 3) + 8 * (l % 3 == 0 ? 1 : l % 3 == 1 ? 0 : -1)) / 12; }
int threefold_invariants(int l) { return 1 + 2 * (l / 3); }
int antipodal_threefold_invariants(int l) { return l % 2 ? 0 : threefold_invariants(l); }

// Whole orbits with two free parameters each, at least as many as the invariants of bands 1..t;
// with turns_about_z, more than the invariants: the turns about z commute with the group, so the
// whole set turning about z takes one parameter. That is so for the threefold turns with x -> -x
// (at an even sum of invariants the searches one orbit short found nothing: t = 25, 29, 33). The
// threefold turns alone commute with them too, but their sum is odd at odd t, where the default
// takes them, and the one even t tried with one orbit short converged (t = 12, 84 points: the
// tetrahedral design), so their count stays the plain one.
int orbit_count(int t, int group_size, int (*invariants)(int), bool turns_about_z) {
  int sum = 0;
  for (int l = 1; l <= t; ++l) sum += invariants(l);
  return group_size * ((sum + (turns_about_z ? 2 : 1)) / 2);
}

// An orthonormal basis of each band's invariant subspace: the eigenvectors of eigenvalue 1 of the
// projector P_l = (1/|G|) sum_g D_l(g) (band matrices by the recurrence, in long double). An orbit
// sum is |G| P y, so its residual lives in this subspace (about (t+1)^2 / |G| coordinates instead
// of (t+1)^2 - 1), and a derivative needs the SH at the generator only, not at its images.
class InvariantBasis {
 public:
  // Stops early, incomplete, when interrupted() says so (polled about every 0.1 s at t = 100).
  InvariantBasis(const std::vector<runtime::Matrix3>& rotations, int t, const std::function<bool()>& interrupted) {
    std::vector<std::vector<std::vector<long double>>> d;
    for (const runtime::Matrix3& r : rotations) {
      if (interrupted && interrupted()) return;
      d.push_back(runtime::recurrence_band_matrices<long double>(r.data(), t + 1));
    }
    for (int l = 1; l <= t; ++l) {
      if (interrupted && interrupted()) return;
      const int side = 2 * l + 1;
      Eigen::MatrixXd p(side, side);
      for (int i = 0; i < side; ++i)
        for (int k = 0; k < side; ++k) {
          long double sum = 0;
          for (const auto& bands : d) sum += bands[l][i * side + k] + bands[l][k * side + i];
          p(i, k) = static_cast<double>(sum / (2 * d.size()));
        }
      const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(p);
      // Eigenvalues ascending: 0s, then as many 1s as the trace (the subspace's dimension).
      const int count = static_cast<int>(std::lround(p.trace()));
      if (count && !(eigen.eigenvalues()(side - count) > 0.5 && (count == side || eigen.eigenvalues()(side - count - 1) < 0.5)))
        throw std::logic_error("band " + std::to_string(l) + "'s orbit projector has not " + std::to_string(count) + " unit eigenvalues");
      bands_.push_back(eigen.eigenvectors().rightCols(count));
      size_ += count;
    }
  }
  int size() const { return size_; }
  // Coordinates in the basis of the columns of a matrix whose rows are bands 1..t (the
  // Evaluator's rows): one product per band.
  Eigen::MatrixXd reduce(const Eigen::MatrixXd& full) const {
    Eigen::MatrixXd out(size_, full.cols());
    int at = 0;
    for (std::size_t b = 0; b < bands_.size(); ++b) {
      const int l = static_cast<int>(b) + 1, count = static_cast<int>(bands_[b].cols());
      out.middleRows(at, count).noalias() = bands_[b].transpose() * full.middleRows(l * l - 1, 2 * l + 1);
      at += count;
    }
    return out;
  }

 private:
  std::vector<Eigen::MatrixXd> bands_;  // band l: (2l+1) x its invariants
  int size_ = 0;
};

// One start of a design of whole orbits: count / |G| generators from random directions, each
// standing for its orbit (so only the group's invariant harmonics can be non-zero: a square system
// when the count is orbit_count's), then Levenberg-Marquardt on the generators. The residual is
// the exact orbit sums; the Jacobian is |G| Q^T dy at each generator, the derivative of Q^T r up to
// the basis' rounding.
Design run_orbit_start(int t, int count, int k, std::uint64_t seed, const OrbitGroup& group, const InvariantBasis& basis,
                       const std::function<bool()>& interrupted) {
  const int order = static_cast<int>(group.rotations.size()), m = count / order;
  std::mt19937_64 rng(seed * 1000003 + static_cast<std::uint64_t>(k));
  sh::Normal<> normal;
  std::vector<Point> g(m);
  for (Point& p : g) p = normalized({normal(rng), normal(rng), normal(rng)});
  Evaluator e(t, false);
  const int rows = e.size(), cols = 2 * m;
  std::vector<double> y(rows);
  auto residual = [&](const std::vector<Point>& generators) {
    Eigen::VectorXd r = Eigen::VectorXd::Zero(rows);
    for (const Point& p : generators)
      for (const runtime::Matrix3& c : group.copies) {
        e.at(turned(c.data(), p), y.data());
        for (int i = 0; i < rows; ++i) r[i] += group.weights[i] * y[i];
      }
    return r;
  };
  Eigen::VectorXd r = residual(g);
  double lambda = zhf::tolerance::kDampingStart;
  Eigen::MatrixXd dy(rows, cols);  // the SH's derivatives at the generators, reused across steps
  double norm_at_check = r.norm();
  for (int iteration = 0; iteration < kOrbitIterations && r.cwiseAbs().maxCoeff() > 0; ++iteration) {
    if (interrupted && interrupted()) break;
    // A start that stalls in a local minimum is given up: Newton's steps near a design shrink the
    // residual far faster than this.
    if (iteration % kStallIterations == kStallIterations - 1) {
      if (r.norm() > kStallFactor * norm_at_check) break;
      norm_at_check = r.norm();
    }
    std::vector<Point> us(m), vs(m);
    for (int i = 0; i < m; ++i) {
      tangents(g[i], us[i], vs[i]);
      e.derivative(g[i], us[i], dy.col(2 * i).data());
      e.derivative(g[i], vs[i], dy.col(2 * i + 1).data());
    }
    const Eigen::MatrixXd j = order * basis.reduce(dy);
    // J^T J's lower half (all that the Cholesky factorisation reads).
    Eigen::MatrixXd normal_matrix = Eigen::MatrixXd::Zero(cols, cols);
    normal_matrix.selfadjointView<Eigen::Lower>().rankUpdate(j.transpose());
    const Eigen::VectorXd gradient = j.transpose() * basis.reduce(r);
    if (interrupted && interrupted()) break;  // a step takes about a second at t = 100
    const bool improved = damped_step(g, us, vs, r, lambda, [&](double damping) {
      // Damped, J^T J is positive definite: Cholesky, blocked (LDLT's unblocked updates took a
      // quarter of a step at t = 43).
      Eigen::MatrixXd a = normal_matrix;
      a.diagonal().array() += damping * (1 + a.diagonal().array());
      return Eigen::VectorXd(-a.llt().solve(gradient));
    }, residual);
    if (!improved) break;
  }
  Design d;
  d.t = t;
  const std::size_t halves = group.negatives_last ? 2 : 1, per_half = group.rotations.size() / halves;
  for (std::size_t half = 0; half < halves; ++half)
    for (const Point& p : g)
      for (std::size_t q = half * per_half; q < (half + 1) * per_half; ++q) d.points.push_back(turned(group.rotations[q].data(), p));
  d.residual = design_residual(d.points, t);
  d.start = d.residual <= zhf::tolerance::kDesignResidual ? k : -1;
  return d;
}

}  // namespace

double design_residual(const std::vector<Point>& points, int t) {
  Evaluator e(t, false);
  const Eigen::VectorXd r = residual_vector(points, e);
  return r.size() ? r.cwiseAbs().maxCoeff() / static_cast<double>(points.size()) : 0.0;
}

int best_known_count(int t) {
  static const int counts[] = {2, 4, 6, 12, 12, 24, 24, 36, 48, 60, 70, 84, 94, 108, 120, 144, 156, 180, 204, 216, 240};
  return t >= 1 && t <= 21 ? counts[t - 1] : -1;
}

int efficient_count(int t) { return ((t + 1) * (t + 1) + 1) / 2 + 1; }

int symmetric_count(int t) {
  int equations = 0;  // the even bands 2..t
  for (int l = 2; l <= t; l += 2) equations += 2 * l + 1;
  return 2 * ((equations + 3 + 1) / 2);  // 2K - 3 unknowns (the set turns freely) >= equations
}

int tetrahedral_count(int t) { return orbit_count(t, 12, tetrahedral_invariants, false); }
int threefold_count(int t) { return orbit_count(t, 3, threefold_invariants, false); }
int antipodal_threefold_count(int t) { return orbit_count(t, 6, antipodal_threefold_invariants, true); }

int orbit_size(Symmetry symmetry) {
  switch (symmetry) {
    case Symmetry::kFree: return 1;
    case Symmetry::kAntipodal: return 2;
    case Symmetry::kTetrahedral: return 12;
    case Symmetry::kThreefold: return 3;
    case Symmetry::kAntipodalThreefold: return 6;
  }
  return 1;
}

const char* symmetry_name(Symmetry symmetry) {
  static constexpr runtime::EnumName<Symmetry> kNames[] = {{Symmetry::kFree, "free"},
                                                           {Symmetry::kAntipodal, "antipodal"},
                                                           {Symmetry::kTetrahedral, "tetrahedral"},
                                                           {Symmetry::kThreefold, "threefold"},
                                                           {Symmetry::kAntipodalThreefold, "antipodal threefold"}};
  return runtime::enum_name(kNames, symmetry);
}

DesignChoice default_design(int t) {
  if (t <= 10) return {best_known_count(t), Symmetry::kFree};
  if (t % 2 == 0) {
    // Tetrahedral sets are faster (a quarter of the unknowns); threefold ones reach the efficient
    // count where tetrahedral ones miss it.
    if (threefold_count(t) < tetrahedral_count(t)) return {threefold_count(t), Symmetry::kThreefold};
    return {tetrahedral_count(t), Symmetry::kTetrahedral};
  }
  if (t <= 21) return {t == 19 || t == 21 ? symmetric_count(t) : best_known_count(t), Symmetry::kAntipodal};
  // Odd t: antipodal threefold orbits (seconds) where they need no more points than an antipodal
  // set (minutes); at t = 25, 37, 49, ... (every 12th) they need 2 more, and the antipodal set is
  // searched.
  if (antipodal_threefold_count(t) <= symmetric_count(t)) return {antipodal_threefold_count(t), Symmetry::kAntipodalThreefold};
  return {symmetric_count(t), Symmetry::kAntipodal};
}

int symmetry_count(Symmetry symmetry, int t) {
  const DesignChoice choice = default_design(t);
  if (symmetry == choice.symmetry) return choice.points;
  switch (symmetry) {
    case Symmetry::kFree: return efficient_count(t);
    case Symmetry::kAntipodal: return symmetric_count(t);
    case Symmetry::kTetrahedral: return tetrahedral_count(t);
    case Symmetry::kThreefold: return threefold_count(t);
    case Symmetry::kAntipodalThreefold: return antipodal_threefold_count(t);
  }
  return efficient_count(t);
}

Design search_design(const DesignSearch& s) {
  if (s.t < 1 || s.t > frames::kMaxDesignStrength)
    throw std::invalid_argument("t " + std::to_string(s.t) + " is outside 1.." + std::to_string(frames::kMaxDesignStrength));
  if (s.points < 2) throw std::invalid_argument("a design needs at least 2 points (got " + std::to_string(s.points) + ")");
  const int size = orbit_size(s.symmetry);
  if (s.points % size)
    throw std::invalid_argument("a design of this symmetry is whole orbits of " + std::to_string(size) + " points (got " + std::to_string(s.points) + ")");
  const int threads = std::max(1, s.threads);
  std::optional<OrbitGroup> group;
  if (s.symmetry == Symmetry::kTetrahedral) group = tetrahedral_group(s.t);
  if (s.symmetry == Symmetry::kThreefold) group = threefold_group(s.t);
  if (s.symmetry == Symmetry::kAntipodalThreefold) group = antipodal_threefold_group(s.t);
  if (s.symmetry == Symmetry::kAntipodal && s.t > kLargestAntipodalEnergySearch) group = antipodal_group(s.t);
  std::optional<InvariantBasis> basis;
  if (group) basis.emplace(group->rotations, s.t, s.interrupted);
  Design best;
  best.t = s.t;
  // Batches of `threads` starts; the lowest start that converged wins, whatever the thread count,
  // and otherwise the lowest residual (ties: the lower start).
  for (int first = 0; first < s.starts; first += threads) {
    if (s.interrupted && s.interrupted()) break;
    if (s.progress) s.progress(first);
    const int batch = std::min(threads, s.starts - first);
    std::vector<Design> results(batch);
    runtime::parallel_for(batch, batch, [&](int b) {
      const bool antipodal = s.symmetry == Symmetry::kAntipodal;
      results[b] = group ? run_orbit_start(s.t, s.points, first + b, s.seed, *group, *basis, s.interrupted)
                         : run_start(s.t, antipodal ? s.points / 2 : s.points, antipodal, first + b, s.seed);
    });
    for (int b = 0; b < batch; ++b) {
      if (results[b].start >= 0) return results[b];
      if (best.points.empty() || results[b].residual < best.residual) best = results[b];
    }
  }
  return best;
}

std::vector<Point> read_points(const std::string& path) {
  const io::json::Json root = io::json::read_file(path, runtime::kMaxTableBytes);
  io::json::Field top(root, path);
  if (top.is(io::json::Kind::kObject)) {
    const io::json::Field format = top.member("format");
    if (format.string() != kDesignFormat) format.fail("'" + runtime::excerpt(format.string()) + "' is not " + kDesignFormat);
    top = top.member("points");
  }
  std::vector<Point> points;
  for (const io::json::Field& item : top.items(1, frames::kMaxDesignPoints)) {
    const std::vector<io::json::Field> xyz = item.items(3);
    const Point p{xyz[0].number(), xyz[1].number(), xyz[2].number()};
    const double norm = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    if (!(norm > zhf::tolerance::kShortestDirection) || !std::isfinite(norm)) item.fail("not a direction (length " + std::to_string(norm) + ")");
    points.push_back(normalized(p));
  }
  return points;
}

}  // namespace zhf::frames
