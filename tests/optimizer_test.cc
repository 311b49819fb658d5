#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include <Eigen/LU>
#include <gtest/gtest.h>

#include "zhf/io/errors.h"
#include "zhf/io/files.h"
#include "zhf/optimizer/conditioned.h"
#include "zhf/optimizer/exhaustive.h"
#include "zhf/optimizer/genetic.h"
#include "zhf/optimizer/lobe_table.h"
#include "zhf/optimizer/local_search.h"
#include "zhf/sh/slow_reference.h"

namespace zhf::optimizer {
namespace {

// Counted zeros, recomputed in long double, sit at rounding level, not at "small".
constexpr double kZeroInLongDouble = 1e-13;
// Condition numbers printed in the reference are rounded to 2 decimals; 1% covers that.
constexpr double kPaperConditionRelative = 0.01;

const candidates::CandidateSet& candidate_set(int order) {
  static std::map<int, candidates::CandidateSet> sets;
  auto it = sets.find(order);
  if (it == sets.end()) it = sets.emplace(order, candidates::enumerate_candidates(order)).first;
  return it->second;
}

Genome genome_from_reference(const nlohmann::json& entry, const candidates::CandidateSet& set) {
  Genome genome;
  for (const auto& lobe : entry.at("lobes")) {
    const double theta = lobe.at("theta"), phi = lobe.at("phi");
    const double xyz[3] = {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
    genome.push_back(candidates::find_direction(set, xyz, 1e-9));
  }
  return genome;
}

// Rebuilds Y_l in long double from the lobes' theta and phi (slow closed form) and checks
// that every entry counted as zero is at rounding level. The directions themselves are
// doubles, so a band of condition k still carries ~k * 1e-16 * max|A| of input rounding:
// only bands within the default condition bound are held to kZeroInLongDouble.
void expect_zeros_exact_in_long_double(const LobeEvaluator& evaluator, const Genome& genome,
                                       const std::vector<BandAnalysis>& bands, const std::string& what) {
  using MatrixL = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
  for (const BandAnalysis& band : bands) {
    if (band.condition > kDefaultMaxCondition) continue;
    const int size = 2 * band.l + 1;
    MatrixL y(size, size);
    for (int d = 0; d < size; ++d) {
      const candidates::Direction& lobe = evaluator.candidates().directions[genome[band.lobes[d]]];
      for (int m = -band.l; m <= band.l; ++m) y(d, m + band.l) = sh::slow::real_sh(band.l, m, lobe.theta, lobe.phi);
    }
    const MatrixL inverse = y.fullPivLu().inverse();
    for (int i = 0; i < size; ++i)
      for (int j = 0; j < size; ++j)
        if (band.inverse(i, j) == 0) {
          EXPECT_LT(std::abs(double(inverse(i, j))), kZeroInLongDouble)
              << what << " band " << band.l << " entry (m=" << i - band.l << ", lobe " << j << ")";
        }
  }
}

TEST(Objective, LobeIndexingWithAndWithoutSharing) {
  EXPECT_EQ(lobe_count(8, true), 15);
  EXPECT_EQ(lobe_count(8, false), 60);  // 5+7+9+11+13+15
  EXPECT_EQ(lobe_index(4, 8, true), 8);
  EXPECT_EQ(lobe_index(2, 0, false), 0);
  EXPECT_EQ(lobe_index(3, 0, false), 5);
  EXPECT_EQ(lobe_index(4, 0, false), 12);
}

TEST(Objective, ZerosAndMultiplyCostOnAHandMadeMatrix) {
  Eigen::MatrixXd a(3, 3);
  a << 1.0, 0.0, 3e-12,  //
      -1.0, 2.0, 0.5,    //
      1e-11, -2.0, 0.5;
  // max |a| = 2, so entries at or below 2e-10 are zero: 0.0, 3e-12, 1e-11.
  EXPECT_EQ(zero_small_entries(a), 3);
  EXPECT_EQ(a(0, 2), 0.0);
  // Column 0: |1|, |-1| share one multiply; column 1: |2|, |-2| one; column 2: 0.5, 0.5 one.
  EXPECT_EQ(multiply_cost(a), 3);
}

TEST(Objective, RepeatedLobeIsSingular) {
  const LobeEvaluator evaluator(candidate_set(3), true, kDefaultMaxCondition);
  const Fitness f = evaluator.evaluate({3, 3, 7, 9, 11});
  EXPECT_FALSE(f.invertible);
  EXPECT_FALSE(f.feasible);
}

// Orders above 16 evaluate candidates' SH on demand instead of tabulating them: same fitness.
TEST(Objective, OnDemandEvaluationMatchesTheTable) {
  const candidates::CandidateSet& set = candidate_set(6);
  const LobeEvaluator tabulated(set, true, kDefaultMaxCondition);
  const LobeEvaluator on_demand(set, true, kDefaultMaxCondition, /*max_tabulated_values=*/0);
  std::mt19937_64 rng(6);
  std::uniform_int_distribution<int> pick(0, static_cast<int>(set.directions.size()) - 1);
  for (int trial = 0; trial < 50; ++trial) {
    Genome genome(tabulated.genes());
    for (int& g : genome) g = pick(rng);
    const Fitness a = tabulated.evaluate(genome), b = on_demand.evaluate(genome);
    EXPECT_EQ(a.zeros, b.zeros) << "trial " << trial;
    EXPECT_EQ(a.invertible, b.invertible) << "trial " << trial;
    EXPECT_EQ(a.worst_condition, b.worst_condition) << "trial " << trial;
  }
}

TEST(Objective, PaperLobeSetsGiveThePublishedFigures) {
  const nlohmann::json reference = io::read_json_file(std::string(ZHF_SHARED_DIR) + "/reference/paper_lobes.json");
  for (const auto& entry : reference.at("orders")) {
    const int order = entry.at("N");
    const LobeEvaluator evaluator(candidate_set(order), true, 1e9);
    const Genome genome = genome_from_reference(entry, candidate_set(order));
    const std::vector<BandAnalysis> bands = evaluator.analyze(genome);
    EXPECT_EQ(evaluator.fitness_of(bands).zeros, entry.at("zeros").get<int>()) << "order " << order;
    EXPECT_EQ(evaluator.evaluate(genome).zeros, entry.at("zeros").get<int>()) << "order " << order << " fast path";
    for (size_t b = 0; b < bands.size(); ++b) {
      const auto& expected = entry.at("bands")[b];
      EXPECT_EQ(bands[b].zeros, expected.at("zeros").get<int>()) << "order " << order << " band " << bands[b].l;
      const double condition = expected.at("condition");
      EXPECT_NEAR(bands[b].condition, condition, kPaperConditionRelative * condition)
          << "order " << order << " band " << bands[b].l;
    }
    expect_zeros_exact_in_long_double(evaluator, genome, bands, "paper order " + std::to_string(order));
  }
}

TEST(GeneticSearch, SameResultWithOneAndTwoThreads) {
  const LobeEvaluator evaluator(candidate_set(5), true, kDefaultMaxCondition);
  GeneticOptions options;
  options.seed = 42;
  options.population = 120;
  options.stall_generations = 15;
  options.threads = 1;
  const SearchResult one = genetic_search(evaluator, options);
  options.threads = 2;
  const SearchResult two = genetic_search(evaluator, options);
  EXPECT_EQ(one.best, two.best);
  EXPECT_EQ(one.generations, two.generations);
  EXPECT_EQ(one.evaluations, two.evaluations);

  LocalSearchOptions polish;
  polish.seed = 42;
  polish.stall_kicks = 5;
  polish.threads = 1;
  const SearchResult a = iterated_local_search(evaluator, one.best, one.fitness, polish);
  polish.threads = 2;
  const SearchResult b = iterated_local_search(evaluator, one.best, one.fitness, polish);
  EXPECT_EQ(a.best, b.best);
  EXPECT_EQ(a.evaluations, b.evaluations);
}

TEST(GeneticSearch, BeatsRandomSamplingWithTheSameEvaluations) {
  const LobeEvaluator evaluator(candidate_set(6), true, kDefaultMaxCondition);
  GeneticOptions options;
  options.seed = 3;
  const SearchResult ga = genetic_search(evaluator, options);
  const SearchResult random = random_search(evaluator, ga.evaluations, 3);
  EXPECT_EQ(random.evaluations, ga.evaluations);
  EXPECT_TRUE(better(ga.fitness, random.fitness))
      << "GA " << ga.fitness.zeros << " zeros vs random " << random.fitness.zeros << " in " << ga.evaluations
      << " evaluations";
  EXPECT_GT(ga.fitness.zeros, random.fitness.zeros + 20);
}

TEST(GeneticSearch, GenesStayInTheirCandidateSets) {
  const candidates::CandidateSet& set = candidate_set(5);
  const LobeEvaluator evaluator(set, true, kDefaultMaxCondition);
  std::mt19937_64 rng(9);
  std::vector<std::vector<int>> allowed(evaluator.genes());
  for (auto& list : allowed) {
    std::set<int> chosen;
    while (chosen.size() < 40) chosen.insert(static_cast<int>(rng() % set.directions.size()));
    list.assign(chosen.begin(), chosen.end());
  }
  GeneticOptions options;
  options.population = 100;
  options.stall_generations = 10;
  options.gene_candidates = allowed;
  LocalSearchOptions polish;
  polish.stall_kicks = 3;
  polish.gene_candidates = allowed;
  GenerationReport last;
  options.on_generation = [&](const GenerationReport& r) { last = r; };
  const SearchResult ga = genetic_search(evaluator, options);
  const SearchResult ils = iterated_local_search(evaluator, ga.best, ga.fitness, polish);
  for (const Genome* genome : {&ga.best, &ils.best})
    for (int g = 0; g < evaluator.genes(); ++g) {
      const auto& list = allowed[g];
      EXPECT_TRUE(std::binary_search(list.begin(), list.end(), (*genome)[g])) << "gene " << g;
    }
}

TEST(Exhaustive, ProvesTheOrder3Optimum) {
  const LobeEvaluator evaluator(candidate_set(3), true, kDefaultMaxCondition);
  const ExhaustiveResult r = exhaustive_search(evaluator, 0, 0);
  EXPECT_TRUE(r.complete);
  EXPECT_EQ(r.sets_total, 65780);  // C(26, 5)
  EXPECT_EQ(r.sets_evaluated, 65780);
  EXPECT_EQ(r.search.fitness.zeros, 16);
  EXPECT_EQ(r.upper_bound, 16);
}

LobeTable small_table() {
  const LobeEvaluator evaluator(candidate_set(4), true, kDefaultMaxCondition);
  GeneticOptions options;
  options.population = 60;
  options.stall_generations = 10;
  const SearchResult r = genetic_search(evaluator, options);
  return make_table(evaluator, r.best, {{"command", "test"}});
}

TEST(LobeTableFile, RoundTripsByteForByte) {
  const LobeTable table = small_table();
  const std::string text = io::json_text(to_json(table));
  const LobeTable read = table_from_json(nlohmann::json::parse(text), "t.json");
  EXPECT_EQ(io::json_text(to_json(read)), text);
  EXPECT_EQ(read.zeros, table.zeros);
  for (size_t b = 0; b < table.bands.size(); ++b) EXPECT_EQ(read.bands[b].inverse, table.bands[b].inverse);
}

void expect_rejected(nlohmann::json json, const std::string& field) {
  try {
    table_from_json(json, "t.json");
    ADD_FAILURE() << "accepted a table with a bad " << field;
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("t.json: " + field), std::string::npos) << e.what();
  }
}

TEST(LobeTableFile, RejectsBadTablesNamingTheField) {
  const nlohmann::json good = nlohmann::json::parse(io::json_text(to_json(small_table())));
  ASSERT_NO_THROW(table_from_json(good, "t.json"));
  auto with = [&](auto&& change) {
    nlohmann::json j = good;
    change(j);
    return j;
  };
  expect_rejected(with([](nlohmann::json& j) { j["format"] = "zhf-lobes-0"; }), "format");
  expect_rejected(with([](nlohmann::json& j) { j.erase("order"); }), "order");
  expect_rejected(with([](nlohmann::json& j) { j["order"] = "four"; }), "order");
  expect_rejected(with([](nlohmann::json& j) { j["lobes"].erase(6); }), "lobes");
  expect_rejected(with([](nlohmann::json& j) { j["lobes"][1]["theta"] = j["lobes"][1]["theta"].get<double>() + 1e-6; }),
                  "lobes[1].xyz");
  expect_rejected(with([](nlohmann::json& j) { j["lobes"][2]["xyz"] = {0, 0}; }), "lobes[2].xyz");
  expect_rejected(with([](nlohmann::json& j) { j["bands"][1]["inverse"][3][2] = 0.125; }), "bands[1]");
  expect_rejected(with([](nlohmann::json& j) { j["bands"][0]["inverse"].erase(0); }), "bands[0].inverse");
  expect_rejected(with([](nlohmann::json& j) { j["bands"][0]["zeros"] = 1; }), "bands[0].zeros");
  expect_rejected(with([](nlohmann::json& j) { j["bands"][1]["condition"] = 1e3; }), "bands[1].condition");
  expect_rejected(with([](nlohmann::json& j) { j["zeros"] = 1; }), "zeros");
  // Tampered directions: move a lobe consistently (theta, phi and xyz); the inverse no longer fits.
  expect_rejected(with([](nlohmann::json& j) {
                    j["lobes"][0] = {{"theta", 0.3}, {"phi", 0.2}, {"xyz", {std::sin(0.3) * std::cos(0.2), std::sin(0.3) * std::sin(0.2), std::cos(0.3)}}, {"source", "x"}};
                  }),
                  "bands[0].inverse");
}

TEST(LobeTableFile, RejectsNearSingularSetsWithTheCondition) {
  // Two lobes 1e-7 apart: Y_2 is near-singular (condition ~1e7).
  nlohmann::json j = nlohmann::json::parse(io::json_text(to_json(small_table())));
  const double theta = j["lobes"][0]["theta"].get<double>() + 1e-7, phi = j["lobes"][0]["phi"];
  j["lobes"][1] = {{"theta", theta}, {"phi", phi}, {"xyz", {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)}}, {"source", "x"}};
  try {
    table_from_json(j, "t.json");
    ADD_FAILURE() << "accepted a near-singular table";
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("near-singular (condition"), std::string::npos) << e.what();
  }
}

// The amplification search: a continuous set that beats the sparse table's worst a_l, the same
// set for the same seed whatever the thread count, and a table that reads back.
TEST(Conditioned, FindsALowerAmplificationThanTheSparseTableReproducibly) {
  constexpr int kOrder = 4;
  ConditionedOptions options;
  options.starts = 3;
  options.passes = 1;
  options.max_evaluations_per_pass = 3000;
  options.threads = 1;
  const ConditionedResult a = conditioned_search(kOrder, options);
  options.threads = 2;  // the starts run on two threads: the same set
  const ConditionedResult b = conditioned_search(kOrder, options);
  ASSERT_EQ(a.theta.size(), 2u * kOrder - 1);
  EXPECT_EQ(a.theta, b.theta);
  EXPECT_EQ(a.phi, b.phi);
  EXPECT_EQ(a.evaluations, b.evaluations);

  const LobeTable sparse = read_table(std::string(ZHF_SOURCE_DIR) + "/generated/lobes/order_4.json");
  double sparse_worst = 0, worst = 0;
  for (const TableBand& band : sparse.bands)
    sparse_worst = std::max(sparse_worst, band_amplification(sparse.band_matrix(band.l)));
  for (double v : a.amplification) worst = std::max(worst, v);
  EXPECT_LT(worst, sparse_worst);
  EXPECT_GE(worst, 1.0);  // a_l = 1 only for an orthogonal Y_l

  const LobeTable table = make_conditioned_table(kOrder, a, {{"seed", 1}});
  const LobeTable back = table_from_json(nlohmann::json::parse(to_json(table).dump()), "t");
  ASSERT_EQ(back.bands.size(), 2u);
  for (size_t b = 0; b < back.bands.size(); ++b)
    EXPECT_NEAR(band_amplification(back.band_matrix(back.bands[b].l)), a.amplification[b], 1e-9) << "band " << b + 2;
}

}  // namespace
}  // namespace zhf::optimizer
