#include "zhf/optimizer/continuous.h"

#include <cmath>
#include <random>

#include <Eigen/LU>
#include <nlopt.hpp>

#include "search_support.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/random.h"

namespace zhf::optimizer {
namespace {

using runtime::kPi;
// A singular set gets this instead of an infinite objective, so the simplex can move off it.
constexpr double kSingularPenalty = 1e6;

struct Problem {
  const LobeEvaluator* evaluator;
  int lobes;
};

double log_sparsity(const std::vector<double>& x, const Problem& p) {
  const int order = p.evaluator->order();
  const bool sharing = p.evaluator->lobe_sharing();
  std::vector<std::array<double, 3>> dirs(p.lobes);
  for (int i = 0; i < p.lobes; ++i) runtime::direction_from_angles(x[2 * i], x[2 * i + 1], dirs[i].data());
  double total = 0;
  std::vector<double> row;
  for (int l = 2; l < order; ++l) {
    const int size = 2 * l + 1;
    Eigen::MatrixXd y(size, size);
    row.resize(size);
    for (int d = 0; d < size; ++d) {
      runtime::eval_band(l, dirs[runtime::lobe_index(l, d, sharing)].data(), row.data());
      for (int k = 0; k < size; ++k) y(d, k) = row[k];
    }
    Eigen::PartialPivLU<Eigen::MatrixXd> lu(y);
    if (!(std::abs(lu.determinant()) > zhf::tolerance::kSearchSingularDeterminant)) return kSingularPenalty;
    const Eigen::MatrixXd a = lu.inverse();
    total += (a.cwiseAbs().array() + 1).log().sum() + (y.cwiseAbs().array() + 1).log().sum();
  }
  return total;
}

double objective(const std::vector<double>& x, std::vector<double>&, void* data) {
  return log_sparsity(x, *static_cast<const Problem*>(data));
}

}  // namespace

std::vector<ContinuousStart> continuous_search(const LobeEvaluator& evaluator, const ContinuousOptions& options) {
  const Problem problem{&evaluator, evaluator.genes()};
  std::mt19937_64 rng(options.seed);
  std::vector<ContinuousStart> starts;
  for (int s = 0; s < options.starts; ++s) {
    std::vector<double> x(2 * problem.lobes);
    for (int i = 0; i < problem.lobes; ++i) {
      x[2 * i] = std::acos(2 * sh::uniform01(rng) - 1);
      x[2 * i + 1] = kPi * (2 * sh::uniform01(rng) - 1);
    }
    nlopt::opt opt(nlopt::LN_SBPLX, static_cast<unsigned>(x.size()));
    opt.set_min_objective(objective, const_cast<Problem*>(&problem));
    opt.set_maxeval(options.max_evaluations_per_start);
    opt.set_xtol_rel(zhf::tolerance::kContinuousSearchStep);
    double value = 0;
    try {
      opt.optimize(x, value);
    } catch (const std::exception&) {
      value = log_sparsity(x, problem);  // nlopt gives up on round-off; keep where it got to
    }
    ContinuousStart start;
    start.objective = value;
    for (int i = 0; i < problem.lobes; ++i) {
      double xyz[3];
      runtime::direction_from_angles(x[2 * i], x[2 * i + 1], xyz);
      start.snapped.push_back(candidates::find_direction(evaluator.candidates(), xyz, 4.0));
    }
    start.fitness = evaluator.evaluate(start.snapped);
    starts.push_back(start);
  }
  return starts;
}

}  // namespace zhf::optimizer
