#include "zhf/optimizer/objective.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SVD>

#include "zhf/runtime/sh_eval.h"
#include "zhf/tolerances/tolerances.h"

namespace zhf::optimizer {

bool better(const Fitness& a, const Fitness& b, Ranking ranking) {
  if (a.feasible != b.feasible) return a.feasible;
  if (a.invertible != b.invertible) return a.invertible;
  // Outside the bound, head for it: the better-conditioned set wins.
  if (!a.feasible && a.worst_condition != b.worst_condition) return a.worst_condition < b.worst_condition;
  if (ranking == Ranking::kFewestMultiplies && a.multiplies != b.multiplies) return a.multiplies < b.multiplies;
  if (a.zeros != b.zeros) return a.zeros > b.zeros;
  if (a.worst_condition != b.worst_condition) return a.worst_condition < b.worst_condition;
  return a.multiplies < b.multiplies;
}

int zero_small_entries(Eigen::MatrixXd& inverse) {
  const double threshold = zhf::tolerance::kZeroRelative * inverse.cwiseAbs().maxCoeff();
  int zeros = 0;
  for (int i = 0; i < inverse.rows(); ++i)
    for (int j = 0; j < inverse.cols(); ++j)
      if (std::abs(inverse(i, j)) <= threshold) {
        inverse(i, j) = 0;
        ++zeros;
      }
  return zeros;
}

int multiply_cost(const Eigen::MatrixXd& inverse) {
  int cost = 0;
  std::vector<double> magnitudes;
  for (int j = 0; j < inverse.cols(); ++j) {
    magnitudes.clear();
    for (int i = 0; i < inverse.rows(); ++i)
      if (inverse(i, j) != 0) magnitudes.push_back(std::abs(inverse(i, j)));
    std::sort(magnitudes.begin(), magnitudes.end());
    for (size_t k = 0; k < magnitudes.size(); ++k)
      if (k == 0 || magnitudes[k] - magnitudes[k - 1] > zhf::tolerance::kSameMagnitude * magnitudes[k]) ++cost;
  }
  return cost;
}

namespace {

// The table of a lobe set as analysed (bands' A_l, zeros and conditions), without the lobes'
// sources and the provenance.
runtime::LobeTable table_of(const LobeEvaluator& evaluator, const Genome& genes, const std::vector<BandAnalysis>& bands) {
  runtime::LobeTable table;
  table.order = evaluator.order();
  table.lobe_sharing = evaluator.lobe_sharing();
  for (int c : genes) {
    const candidates::Direction& d = evaluator.candidates().directions.at(c);
    runtime::TableLobe lobe;
    lobe.theta = d.theta;
    lobe.phi = d.phi;
    std::copy(d.xyz, d.xyz + 3, lobe.xyz.begin());
    table.lobes.push_back(lobe);
  }
  for (const BandAnalysis& analysis : bands) {
    runtime::TableBand band;
    band.l = analysis.l;
    for (int d = 0; d < 2 * band.l + 1; ++d) band.lobes.push_back(runtime::lobe_index(band.l, d, table.lobe_sharing));
    band.inverse = to_matrix(analysis.inverse);
    band.zeros = analysis.zeros;
    band.condition = analysis.condition;
    table.zeros += band.zeros;
    table.entries += static_cast<int>(analysis.inverse.size());
    table.bands.push_back(std::move(band));
  }
  return table;
}

}  // namespace

LobeEvaluator::LobeEvaluator(const candidates::CandidateSet& set, bool lobe_sharing, double max_condition, Scoring scoring,
                             size_t max_tabulated_values)
    : candidates_(set), order_(set.order), lobe_sharing_(lobe_sharing), max_condition_(max_condition),
      scoring_(std::move(scoring)) {
  const int count = runtime::coefficient_count(order_);
  // The default bound tabulates every order up to 16; order 32 has 6.4 million candidates (52 GB
  // of values) and evaluates on demand.
  if (set.directions.size() * count > max_tabulated_values) return;
  sh_.resize(set.directions.size() * count);
  for (size_t c = 0; c < set.directions.size(); ++c) runtime::eval_sh(order_, set.directions[c].xyz, &sh_[c * count]);
}

Eigen::MatrixXd LobeEvaluator::band_matrix(const Genome& genes, int l) const {
  const int size = 2 * l + 1;
  const int count = runtime::coefficient_count(order_);
  Eigen::MatrixXd y(size, size);
  std::vector<double> values(sh_.empty() ? runtime::coefficient_count(l + 1) : 0);
  for (int d = 0; d < size; ++d) {
    const int candidate = genes[runtime::lobe_index(l, d, lobe_sharing_)];
    const double* row = nullptr;
    if (sh_.empty()) {
      runtime::eval_sh(l + 1, candidates_.directions[candidate].xyz, values.data());
      row = &values[l * l];
    } else {
      row = &sh_[size_t(candidate) * count + l * l];
    }
    for (int k = 0; k < size; ++k) y(d, k) = row[k];
  }
  return y;
}

int LobeEvaluator::multiplies(const Genome& genes, const std::vector<BandAnalysis>& bands) const {
  if (!scoring_.lobe_set_multiplies) {
    int sum = 0;
    for (const BandAnalysis& band : bands) sum += multiply_cost(band.inverse);
    return sum;
  }
  return scoring_.lobe_set_multiplies(table_of(*this, genes, bands));
}

Fitness LobeEvaluator::evaluate(const Genome& genes) const {
  Fitness fitness;
  fitness.invertible = true;
  std::vector<BandAnalysis> bands;
  for (int l = 2; l < order_; ++l) {
    BandAnalysis& band = bands.emplace_back();
    band.l = l;
    const Eigen::MatrixXd y = band_matrix(genes, l);
    const Eigen::MatrixXd gram = y.transpose() * y;
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(gram, Eigen::EigenvaluesOnly);
    const double lo = eigen.eigenvalues()(0), hi = eigen.eigenvalues()(gram.rows() - 1);
    const double condition = lo > 0 ? std::sqrt(hi / lo) : INFINITY;
    if (!(condition <= zhf::tolerance::kSingularCondition)) {
      fitness.invertible = false;
      fitness.feasible = false;
      fitness.worst_condition = INFINITY;
      return fitness;
    }
    fitness.worst_condition = std::max(fitness.worst_condition, condition);
    band.condition = condition;
    band.inverse = y.partialPivLu().inverse();
    band.zeros = zero_small_entries(band.inverse);
    fitness.zeros += band.zeros;
    // Band by band, as the checked-in tables' searches ranked sets that turn out singular.
    if (!scoring_.lobe_set_multiplies) fitness.multiplies += multiply_cost(band.inverse);
  }
  if (scoring_.lobe_set_multiplies) fitness.multiplies = multiplies(genes, bands);
  fitness.feasible = fitness.worst_condition <= max_condition_;
  return fitness;
}

std::vector<BandAnalysis> LobeEvaluator::analyze(const Genome& genes) const {
  std::vector<BandAnalysis> bands;
  for (int l = 2; l < order_; ++l) {
    BandAnalysis band;
    band.l = l;
    for (int d = 0; d < 2 * l + 1; ++d) band.lobes.push_back(runtime::lobe_index(l, d, lobe_sharing_));
    band.y = band_matrix(genes, l);
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(band.y);
    const auto& s = svd.singularValues();
    band.condition = s(s.size() - 1) > 0 ? s(0) / s(s.size() - 1) : INFINITY;
    band.inverse = band.y.fullPivLu().inverse();
    band.zeros = zero_small_entries(band.inverse);
    bands.push_back(std::move(band));
  }
  return bands;
}

Fitness LobeEvaluator::fitness_of(const Genome& genes, const std::vector<BandAnalysis>& bands) const {
  Fitness fitness;
  fitness.invertible = true;
  for (const BandAnalysis& band : bands) {
    if (!(band.condition <= zhf::tolerance::kSingularCondition)) fitness.invertible = false;
    fitness.zeros += band.zeros;
    fitness.worst_condition = std::max(fitness.worst_condition, band.condition);
  }
  fitness.multiplies = multiplies(genes, bands);
  fitness.feasible = fitness.invertible && fitness.worst_condition <= max_condition_;
  return fitness;
}

runtime::Matrix to_matrix(const Eigen::MatrixXd& m) {
  runtime::Matrix out(static_cast<int>(m.rows()), static_cast<int>(m.cols()));
  for (int i = 0; i < out.rows; ++i)
    for (int j = 0; j < out.cols; ++j) out(i, j) = m(i, j);
  return out;
}

runtime::LobeTable make_table(const LobeEvaluator& evaluator, const Genome& genes, const nlohmann::json& provenance) {
  runtime::LobeTable table = table_of(evaluator, genes, evaluator.analyze(genes));
  for (size_t i = 0; i < genes.size(); ++i) {
    const std::vector<std::string>& sources = evaluator.candidates().directions.at(genes[i]).sources;
    for (size_t k = 0; k < sources.size(); ++k) table.lobes[i].source += (k ? "; " : "") + sources[k];
  }
  table.provenance = provenance.dump();
  return table;
}

}  // namespace zhf::optimizer
