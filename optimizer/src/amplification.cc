#include "zhf/optimizer/amplification.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include <Eigen/LU>
#include <Eigen/SVD>
#include <nlopt.hpp>

#include "search_support.h"
#include "zhf/candidates/limits.h"
#include "zhf/optimizer/objective.h"
#include "zhf/runtime/parallel.h"
#include "zhf/runtime/sh_eval.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/random.h"

namespace zhf::optimizer {
namespace {

using runtime::kPi;
// A singular set gets this instead of an infinite objective, so the simplex can move off it.
constexpr double kSingularAmplificationScore = 1e12;

std::vector<std::array<double, 3>> directions(const std::vector<double>& x) {
  std::vector<std::array<double, 3>> dirs(x.size() / 2);
  for (size_t i = 0; i < dirs.size(); ++i) runtime::direction_from_angles(x[2 * i], x[2 * i + 1], dirs[i].data());
  return dirs;
}

std::vector<double> amplifications(int order, const std::vector<double>& x) {
  const auto dirs = directions(x);
  std::vector<double> a;
  for (int l = 2; l < order; ++l) a.push_back(runtime::band_amplification(runtime::band_matrix(l, dirs)));
  return a;
}

double score(const std::vector<double>& a) {
  double worst = 0, sum = 0;
  for (double v : a) {
    if (!std::isfinite(v)) return kSingularAmplificationScore;
    worst = std::max(worst, v);
    sum += v * v;
  }
  return std::min(kSingularAmplificationScore, 4 * worst * worst + sum / static_cast<double>(a.size()));
}

struct AmplificationProblem {
  int order;
  long evaluations = 0;
};

double amplification_objective(const std::vector<double>& x, std::vector<double>&, void* data) {
  auto* p = static_cast<AmplificationProblem*>(data);
  ++p->evaluations;
  return score(amplifications(p->order, x));
}

struct StartResult {
  std::vector<double> x;  // the best point of this start's passes; empty if none ended
  double objective = INFINITY;
  long evaluations = 0;
  bool interrupted = false;
};

// Subplex passes from one start point, each from where the previous one stopped.
StartResult descend_from(int order, std::vector<double> x, const AmplificationOptions& options) {
  AmplificationProblem problem{order};
  StartResult result;
  for (int pass = 0; pass < options.passes; ++pass) {
    if (options.stop && options.stop->load()) {
      result.interrupted = true;
      break;
    }
    nlopt::opt opt(nlopt::LN_SBPLX, static_cast<unsigned>(x.size()));
    opt.set_min_objective(amplification_objective, &problem);
    opt.set_maxeval(options.max_evaluations_per_pass);
    opt.set_xtol_rel(zhf::tolerance::kContinuousSearchStep);
    double value = 0;
    try {
      opt.optimize(x, value);
    } catch (const std::exception&) {
      value = score(amplifications(order, x));  // nlopt gives up on round-off; keep where it got to
    }
    if (value < result.objective) {
      result.objective = value;
      result.x = x;
    }
  }
  result.evaluations = problem.evaluations;
  return result;
}

}  // namespace

AmplificationResult amplification_search(int order, const AmplificationOptions& options) {
  if (order < candidates::kMinSearchOrder || order > candidates::kMaxSearchOrder)
    throw std::invalid_argument("amplification_search: order " + std::to_string(order) + " is outside [" +
                                std::to_string(candidates::kMinSearchOrder) + ", " + std::to_string(candidates::kMaxSearchOrder) + "]");
  const int lobes = 2 * order - 1;
  // Every start point is drawn here, on one thread, so a start's result never depends on which
  // worker ran it; the best is then taken in start order (ties: the earlier start).
  std::mt19937_64 rng(options.seed);
  std::vector<std::vector<double>> points(std::max(0, options.starts), std::vector<double>(2 * lobes));
  for (std::vector<double>& x : points)
    for (int i = 0; i < lobes; ++i) {
      x[2 * i] = std::acos(2 * sh::uniform01(rng) - 1);
      x[2 * i + 1] = kPi * (2 * sh::uniform01(rng) - 1);
    }
  const int count = static_cast<int>(points.size());
  std::vector<StartResult> results(count);
  runtime::parallel_for(count, std::min(runtime::worker_count(options.threads), std::max(1, count)),
                       [&](int s) { results[s] = descend_from(order, points[s], options); });

  AmplificationResult best;
  best.objective = INFINITY;
  const StartResult* winner = nullptr;
  for (const StartResult& r : results) {
    best.evaluations += r.evaluations;
    best.interrupted = best.interrupted || r.interrupted;
    if (!r.x.empty() && r.objective < best.objective) {
      best.objective = r.objective;
      winner = &r;
    }
  }
  if (!winner) return best;
  // Canonical angles: theta in [0, pi], phi in (-pi, pi].
  const auto dirs = directions(winner->x);
  std::vector<double> x;
  for (int i = 0; i < lobes; ++i) {
    best.theta.push_back(std::acos(std::clamp(dirs[i][2], -1.0, 1.0)));
    best.phi.push_back(std::atan2(dirs[i][1], dirs[i][0]));
    x.push_back(best.theta[i]);
    x.push_back(best.phi[i]);
  }
  best.amplification = amplifications(order, x);
  best.objective = score(best.amplification);
  return best;
}

runtime::LobeTable make_amplification_table(int order, const AmplificationResult& result, nlohmann::json provenance) {
  runtime::LobeTable table;
  table.order = order;
  table.lobe_sharing = true;
  std::vector<std::array<double, 3>> dirs;
  for (size_t i = 0; i < result.theta.size(); ++i) {
    runtime::TableLobe lobe;
    lobe.theta = result.theta[i];
    lobe.phi = result.phi[i];
    runtime::direction_from_angles(lobe.theta, lobe.phi, lobe.xyz.data());
    lobe.source = "continuous search for the least float error amplification (not an SH zero)";
    dirs.push_back(lobe.xyz);
    table.lobes.push_back(lobe);
  }
  std::vector<double> amplification;
  for (int l = 2; l < order; ++l) {
    runtime::TableBand band;
    band.l = l;
    for (int d = 0; d < 2 * l + 1; ++d) band.lobes.push_back(d);
    const runtime::Matrix y = runtime::band_matrix(l, dirs);
    band.condition = runtime::condition_number(y);
    const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> y_map(y.values.data(), y.rows, y.cols);
    const Eigen::MatrixXd inverse = y_map.fullPivLu().inverse();
    band.inverse = to_matrix(inverse);
    band.zeros = static_cast<int>((inverse.array() == 0).count());
    table.zeros += band.zeros;
    table.entries += static_cast<int>(inverse.size());
    amplification.push_back(runtime::band_amplification(y));
    table.bands.push_back(std::move(band));
  }
  provenance["amplification"] = amplification;
  table.provenance = provenance.dump();
  return table;
}

}  // namespace zhf::optimizer
