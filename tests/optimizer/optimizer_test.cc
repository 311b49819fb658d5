#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include <Eigen/LU>
#include <gtest/gtest.h>

#include "test_support.h"
#include "test_tolerances.h"
#include "zhf/optimizer/amplification.h"
#include "zhf/optimizer/exhaustive.h"
#include "zhf/optimizer/genetic.h"
#include "zhf/optimizer/local_search.h"
#include "zhf/runtime/table_io.h"
#include "zhf/tolerances/tolerances.h"
#include "zhf/sh/random.h"
#include "zhf/sh/slow_reference.h"

namespace zhf::optimizer {
namespace {

using runtime::lobe_count;
using runtime::lobe_index;
using test::kPaperConditionRelative;
using test::kPaperLobeMatch;
using zhf::tolerance::kZeroInLongDouble;

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
    genome.push_back(candidates::find_direction(set, xyz, kPaperLobeMatch));
  }
  return genome;
}

// The paper's entry for an order (tests/data/paper_lobes.json).
nlohmann::json paper_entry(int order) {
  const nlohmann::json reference = test::read_json(test::data_path("paper_lobes.json"));
  for (const auto& entry : reference.at("orders"))
    if (entry.at("N").get<int>() == order) return entry;
  throw std::runtime_error("no paper entry for order " + std::to_string(order));
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
  const LobeEvaluator on_demand(set, true, kDefaultMaxCondition, {}, /*max_tabulated_values=*/0);
  std::mt19937_64 rng(6);
  auto pick = [&](std::mt19937_64& g) { return sh::uniform_index(g, static_cast<int>(set.directions.size())); };
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
  const nlohmann::json reference = test::read_json(test::data_path("paper_lobes.json"));
  for (const auto& entry : reference.at("orders")) {
    const int order = entry.at("N");
    const LobeEvaluator evaluator(candidate_set(order), true, 1e9);
    const Genome genome = genome_from_reference(entry, candidate_set(order));
    const std::vector<BandAnalysis> bands = evaluator.analyze(genome);
    EXPECT_EQ(evaluator.fitness_of(genome, bands).zeros, entry.at("zeros").get<int>()) << "order " << order;
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

// The operations ranking puts fewer multiplies ahead of more zeros; the sparsity ranking the other
// way round; both put the condition bound first.
TEST(Objective, RankingsOrderZerosAndMultiplies) {
  Fitness sparse, cheap;
  sparse.invertible = cheap.invertible = true;
  sparse.feasible = cheap.feasible = true;
  sparse.worst_condition = cheap.worst_condition = 3;
  sparse.zeros = 40, sparse.multiplies = 30;
  cheap.zeros = 38, cheap.multiplies = 27;
  EXPECT_TRUE(better(sparse, cheap, Ranking::kMostZeros));
  EXPECT_FALSE(better(cheap, sparse, Ranking::kMostZeros));
  EXPECT_TRUE(better(cheap, sparse, Ranking::kFewestMultiplies));
  EXPECT_FALSE(better(sparse, cheap, Ranking::kFewestMultiplies));
  Fitness outside = cheap;
  outside.feasible = false;
  outside.multiplies = 1;
  EXPECT_TRUE(better(sparse, outside, Ranking::kFewestMultiplies));
  // A supplied count replaces the model in the fitness, on both paths, and is given the set's
  // table (no order-4 set has 1000 entries, so the model cannot give this figure).
  Scoring scoring;
  scoring.ranking = Ranking::kFewestMultiplies;
  scoring.lobe_set_multiplies = [](const runtime::LobeTable& t) {
    return t.order == 4 && t.lobes.size() == 7 && t.bands.size() == 2 && t.bands[1].inverse.rows == 7 ? 1000 : -1;
  };
  const LobeEvaluator counted(candidate_set(4), true, kDefaultMaxCondition, scoring);
  const Genome genome = genome_from_reference(paper_entry(4), candidate_set(4));
  EXPECT_EQ(counted.ranking(), Ranking::kFewestMultiplies);
  EXPECT_EQ(counted.fitness_of(genome, counted.analyze(genome)).multiplies, 1000);
  EXPECT_EQ(counted.evaluate(genome).multiplies, 1000);
}

// The genetic and local searches give the same lobe set for the same seed whatever the thread
// count, under a ranking.
void check_threads_do_not_change_the_search(Ranking ranking) {
  Scoring scoring;
  scoring.ranking = ranking;
  const LobeEvaluator evaluator(candidate_set(5), true, kDefaultMaxCondition, scoring);
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

TEST(GeneticSearch, SameResultWithOneAndTwoThreads) {
  for (Ranking ranking : {Ranking::kMostZeros, Ranking::kFewestMultiplies}) {
    SCOPED_TRACE(ranking == Ranking::kMostZeros ? "sparsity" : "operations");
    check_threads_do_not_change_the_search(ranking);
  }
}

// Ranked by multiplies, the same search at order 4 ends with fewer multiplies than ranked by
// zeros: the ranking reaches the search (deterministic: the same sets on every run).
TEST(GeneticSearch, OperationsRankingLowersTheMultiplies) {
  Scoring operations;
  operations.ranking = Ranking::kFewestMultiplies;
  const LobeEvaluator by_zeros(candidate_set(4), true, kDefaultMaxCondition);
  const LobeEvaluator by_multiplies(candidate_set(4), true, kDefaultMaxCondition, operations);
  GeneticOptions options;
  options.seed = 3;
  options.population = 200;
  options.stall_generations = 20;
  const SearchResult sparse = genetic_search(by_zeros, options);
  const SearchResult cheap = genetic_search(by_multiplies, options);
  ASSERT_TRUE(sparse.fitness.feasible && cheap.fitness.feasible);
  EXPECT_LT(cheap.fitness.multiplies, sparse.fitness.multiplies);
}

TEST(GeneticSearch, BeatsRandomSamplingWithTheSameEvaluations) {
  const LobeEvaluator evaluator(candidate_set(6), true, kDefaultMaxCondition);
  GeneticOptions options;
  options.seed = 3;
  const SearchResult ga = genetic_search(evaluator, options);
  const SearchResult random = random_search(evaluator, ga.evaluations, 3);
  EXPECT_EQ(random.evaluations, ga.evaluations);
  EXPECT_TRUE(evaluator.better(ga.fitness, random.fitness))
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

// make_table writes what the one validator accepts, and the table reads back the same.
TEST(Tables, MadeFromASearchValidateAndRoundTrip) {
  const LobeEvaluator evaluator(candidate_set(4), true, kDefaultMaxCondition);
  GeneticOptions options;
  options.population = 60;
  options.stall_generations = 10;
  const SearchResult r = genetic_search(evaluator, options);
  const nlohmann::json provenance = {{"command", "test"}};
  const runtime::LobeTable table = make_table(evaluator, r.best, provenance);
  EXPECT_NO_THROW(runtime::validate_lobe_table(table, "made"));
  EXPECT_EQ(table.zeros, r.fitness.zeros);
  EXPECT_EQ(runtime::provenance_command(table), "test");
}

// The amplification search: a continuous set that beats the sparse table's worst a_l, the same
// set for the same seed whatever the thread count, and a table that validates.
TEST(Amplification, FindsALowerAmplificationThanTheSparseTableReproducibly) {
  constexpr int kOrder = 4;
  AmplificationOptions options;
  options.starts = 3;
  options.passes = 1;
  options.max_evaluations_per_pass = 3000;
  options.threads = 1;
  const AmplificationResult a = amplification_search(kOrder, options);
  options.threads = 2;  // the starts run on two threads: the same set
  const AmplificationResult b = amplification_search(kOrder, options);
  ASSERT_EQ(a.theta.size(), 2u * kOrder - 1);
  EXPECT_EQ(a.theta, b.theta);
  EXPECT_EQ(a.phi, b.phi);
  EXPECT_EQ(a.evaluations, b.evaluations);

  const runtime::LobeTable sparse = runtime::read_lobe_table(test::source_path("generated/lobes/order_4.json"));
  double sparse_worst = 0, worst = 0;
  for (const runtime::TableBand& band : sparse.bands)
    sparse_worst = std::max(sparse_worst, runtime::band_amplification(runtime::band_matrix(sparse, band.l)));
  for (double v : a.amplification) worst = std::max(worst, v);
  EXPECT_LT(worst, sparse_worst);
  EXPECT_GE(worst, 1.0);  // a_l = 1 only for an orthogonal Y_l

  const runtime::LobeTable table = make_amplification_table(kOrder, a, nlohmann::json::object());
  EXPECT_NO_THROW(runtime::validate_lobe_table(table, "made"));
  ASSERT_EQ(table.bands.size(), 2u);
  for (size_t b = 0; b < table.bands.size(); ++b)
    EXPECT_EQ(runtime::band_amplification(runtime::band_matrix(table, table.bands[b].l)), a.amplification[b]) << "band " << b + 2;
}

}  // namespace
}  // namespace zhf::optimizer
