#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "commands.h"
#include "interrupt.h"
#include "zhf/io/files.h"
#include "zhf/optimizer/conditioned.h"
#include "zhf/optimizer/continuous.h"
#include "zhf/optimizer/exhaustive.h"
#include "zhf/optimizer/genetic.h"
#include "zhf/optimizer/lobe_table.h"
#include "zhf/optimizer/local_search.h"

namespace zhf::cli {
namespace {

inline constexpr int kMaxOptimizeOrder = 32;

struct OptimizeOptions {
  int order = 0;
  std::uint64_t seed = 1;
  double time_limit = 0;
  int threads = 0;
  int population = 500;
  int generations = 0;
  int stall = 50;
  int local_search_stall = 100;
  double max_condition = optimizer::kDefaultMaxCondition;
  bool no_sharing = false;
  bool exhaustive = false;
  bool seed_from_continuous = false;
  bool quiet = false;
  std::string objective = "sparsity";
  int starts = optimizer::ConditionedOptions{}.starts;
  bool starts_given = false;
  std::string out;
};

// The published figures for the paper's lobe sets (with sharing), recomputed by zhf.
struct PaperFigure {
  int order, zeros;
  double worst_condition;
};
constexpr PaperFigure kPaper[] = {{3, 16, 2.12},  {4, 41, 6.80},   {5, 80, 14.62},
                                  {6, 139, 307.29}, {7, 199, 137.98}, {8, 286, 4107.88}};

void print_summary(const optimizer::LobeTable& table) {
  std::printf("order %d, %s, %zu lobes\n", table.order, table.lobe_sharing ? "lobe sharing" : "no sharing",
              table.lobes.size());
  std::printf("  band  zeros/entries  condition\n");
  for (const optimizer::TableBand& band : table.bands)
    std::printf("  %4d  %5d/%-7d  %9.2f\n", band.l, band.zeros, int(band.inverse.size()), band.condition);
  std::printf("  total %d/%d zeros (%.1f%% sparse), worst condition %.2f\n", table.zeros, table.entries,
              100.0 * table.zeros / table.entries, table.worst_condition());
  for (const PaperFigure& p : kPaper)
    if (p.order == table.order && table.lobe_sharing)
      std::printf("  paper: %d zeros, worst condition %.2f\n", p.zeros, p.worst_condition);
}

void write_table(const optimizer::LobeTable& table, const OptimizeOptions& o) {
  if (o.out.empty()) return;
  io::write_file_atomically(o.out, io::json_text(optimizer::to_json(table)));
  std::printf("wrote %s\n", o.out.c_str());
}

std::string interrupted_path(const OptimizeOptions& o) {
  return (o.out.empty() ? "zhf-order-" + std::to_string(o.order) + ".json" : o.out) + ".interrupted.json";
}

// Interrupted: the best table so far goes beside the output, which stays untouched.
int save_interrupted(const optimizer::LobeTable& table, const OptimizeOptions& o) {
  const std::string path = interrupted_path(o);
  io::write_file_atomically(path, io::json_text(optimizer::to_json(table)));
  std::fprintf(stderr, "zhf: interrupted; the best table so far is in %s (%s untouched)\n", path.c_str(),
               o.out.empty() ? "no output" : o.out.c_str());
  return kExitInterrupted;
}

int run_exhaustive(const optimizer::LobeEvaluator& evaluator, const OptimizeOptions& o, const std::string& command) {
  const optimizer::ExhaustiveResult r =
      optimizer::exhaustive_search(evaluator, o.time_limit, o.threads, &interrupt_requested());
  if (!r.search.fitness.invertible) {
    // The enumeration starts among repeated and clustered lobes; a singular set is no table.
    std::printf("exhaustive: no invertible lobe set among the %.0f searched (%.1f s); nothing written\n",
                r.sets_evaluated, r.search.seconds);
    return r.search.interrupted ? kExitInterrupted : kExitFailure;
  }
  const nlohmann::json provenance = {{"zhf_version", ZHF_VERSION},
                                     {"command", command},
                                     {"exhaustive", r.complete ? "complete" : "partial"},
                                     {"evaluations", r.search.evaluations}};
  const optimizer::LobeTable table = optimizer::make_table(evaluator, r.search.best, provenance);
  print_summary(table);
  if (r.complete) {
    std::printf("  exhaustive: all %.0f lobe sets (up to permutations within a band) in %.1f s: %d zeros is optimal\n",
                r.sets_total, r.search.seconds, r.search.fitness.zeros);
  } else {
    std::printf("  exhaustive: stopped after %.0f of %.3g lobe sets (%.2g%%) in %.1f s; best %d zeros, bound %d\n",
                r.sets_evaluated, r.sets_total, 100 * r.sets_evaluated / r.sets_total, r.search.seconds,
                r.search.fitness.zeros, r.upper_bound);
  }
  if (r.search.interrupted) return save_interrupted(table, o);
  write_table(table, o);
  return kExitOk;
}

// --objective amplification: continuous directions for the float lanes rotation.
int run_conditioned(const OptimizeOptions& o, const std::string& command) {
  if (o.no_sharing || o.exhaustive || o.seed_from_continuous)
    throw UsageError("--objective amplification: searches shared continuous lobes; drop --no-sharing, --exhaustive "
                     "and --seed-from-continuous");
  optimizer::ConditionedOptions options;
  options.seed = o.seed;
  options.starts = o.starts;
  options.threads = o.threads;
  options.stop = &interrupt_requested();
  const optimizer::ConditionedResult result = optimizer::conditioned_search(o.order, options);
  if (result.theta.empty()) {
    std::fprintf(stderr, "zhf: interrupted before the first pass ended; nothing written\n");
    return kExitInterrupted;
  }
  const nlohmann::json provenance = {{"zhf_version", ZHF_VERSION},
                                     {"command", command},
                                     {"seed", o.seed},
                                     {"objective", "amplification"},
                                     {"starts", o.starts},
                                     {"evaluations", result.evaluations}};
  const optimizer::LobeTable table = optimizer::make_conditioned_table(o.order, result, provenance);
  print_summary(table);
  std::printf("  float error amplification per band:");
  for (double a : result.amplification) std::printf(" %.3f", a);
  std::printf("\n  search: %ld evaluations\n", result.evaluations);
  if (result.interrupted) return save_interrupted(table, o);
  write_table(table, o);
  return kExitOk;
}

int run_optimize(const OptimizeOptions& o, const std::string& command) {
  if (o.order < candidates::kMinOrder || o.order > kMaxOptimizeOrder)
    throw UsageError("--order: " + std::to_string(o.order) + " is outside [3, " + std::to_string(kMaxOptimizeOrder) + "]");
  const InterruptGuard interrupts;
  if (o.objective == "amplification") return run_conditioned(o, command);
  if (o.starts_given) throw UsageError("--starts: only --objective amplification has random starts");
  const candidates::CandidateSet set = candidates::enumerate_candidates(o.order);
  const optimizer::LobeEvaluator evaluator(set, !o.no_sharing, o.max_condition);
  const bool tty = isatty(STDERR_FILENO);
  if (o.exhaustive) return run_exhaustive(evaluator, o, command);

  optimizer::GeneticOptions ga;
  ga.seed = o.seed;
  ga.population = o.population;
  ga.max_generations = o.generations;
  ga.stall_generations = o.stall;
  ga.time_limit_seconds = o.time_limit;
  ga.threads = o.threads;
  ga.stop = &interrupt_requested();
  if (o.seed_from_continuous) {
    optimizer::ContinuousOptions continuous;
    continuous.seed = o.seed;
    for (const optimizer::ContinuousStart& start : optimizer::continuous_search(evaluator, continuous)) {
      ga.initial.push_back(start.snapped);
      if (!o.quiet)
        std::fprintf(stderr, "continuous start: objective %.3f, snapped to %d zeros, worst cond %.3g\n",
                     start.objective, start.fitness.zeros, start.fitness.worst_condition);
    }
  }
  if (!o.quiet) {
    ga.on_generation = [tty](const optimizer::GenerationReport& r) {
      std::fprintf(stderr, "%sga generation %d: best zeros %d, worst cond %.2f, %.0f evaluations/s, %.1f s%s",
                   tty ? "\r" : "", r.generation, r.best.zeros, r.best.worst_condition,
                   r.elapsed_seconds > 0 ? r.evaluations / r.elapsed_seconds : 0.0, r.elapsed_seconds,
                   tty ? "   " : "\n");
    };
  }
  const optimizer::SearchResult ga_result = optimizer::genetic_search(evaluator, ga);
  if (!o.quiet && tty) std::fprintf(stderr, "\n");

  optimizer::LocalSearchOptions ils;
  ils.seed = o.seed;
  ils.stall_kicks = o.local_search_stall;
  ils.threads = o.threads;
  ils.stop = &interrupt_requested();
  ils.time_limit_seconds = o.time_limit > 0 ? std::max(1e-3, o.time_limit - ga_result.seconds) : 0;
  if (!o.quiet) {
    ils.on_improvement = [](int kick, const optimizer::Fitness& best, long evaluations) {
      std::fprintf(stderr, "local search kick %d: best zeros %d, worst cond %.2f, %ld evaluations\n", kick, best.zeros,
                   best.worst_condition, evaluations);
    };
  }
  const bool ran_local_search = !ga_result.interrupted && !ga_result.timed_out;
  optimizer::SearchResult ils_result;
  if (ran_local_search) ils_result = optimizer::iterated_local_search(evaluator, ga_result.best, ga_result.fitness, ils);
  const optimizer::SearchResult& final_result = ran_local_search ? ils_result : ga_result;

  const bool interrupted = ga_result.interrupted || ils_result.interrupted;
  const bool timed_out = ga_result.timed_out || ils_result.timed_out;
  const nlohmann::json provenance = {
      {"zhf_version", ZHF_VERSION},
      {"command", command},
      {"seed", o.seed},
      {"generations", ga_result.generations},
      {"local_search_kicks", ils_result.generations},
      {"evaluations", ga_result.evaluations + ils_result.evaluations},
      {"stopped_by", interrupted ? "interrupt" : timed_out ? "time limit" : "stall"},
  };
  const optimizer::LobeTable table = optimizer::make_table(evaluator, final_result.best, provenance);
  print_summary(table);
  std::printf("  search: %d generations, %d local-search kicks, %ld evaluations, %.1f s\n", ga_result.generations,
              ils_result.generations, ga_result.evaluations + ils_result.evaluations,
              ga_result.seconds + ils_result.seconds);
  if (!final_result.fitness.feasible)
    std::printf("  note: no lobe set within --max-condition %.3g was found; this is the best unbounded one\n",
                o.max_condition);
  if (interrupted) return save_interrupted(table, o);
  write_table(table, o);
  return kExitOk;
}

}  // namespace

void add_optimize_command(CLI::App& app, Action& action, const std::string& command_line) {
  auto o = std::make_shared<OptimizeOptions>();
  CLI::App* c = app.add_subcommand("optimize", "Search for sparse lobe directions of an order");
  c->add_option("--order", o->order, "Order N (bands 0..N-1), 3..32")->required();
  c->add_option("--seed", o->seed, "Random seed (default 1)");
  c->add_option("--time-limit", o->time_limit, "Stop after this many seconds (0: none; results then depend on speed)")
      ->check(CLI::NonNegativeNumber);
  c->add_option("--threads", o->threads, "Evaluation threads (0: all cores); never changes the result")
      ->check(CLI::NonNegativeNumber);
  c->add_option("--population", o->population, "GA population (default 500)")->check(CLI::Range(4, 1000000));
  c->add_option("--generations", o->generations, "GA generation limit (0: none)")->check(CLI::NonNegativeNumber);
  c->add_option("--stall", o->stall, "GA stops after this many generations without improvement (default 50)")
      ->check(CLI::Range(1, 1000000));
  c->add_option("--local-search-stall", o->local_search_stall,
                "Local search stops after this many kicks without improvement (default 100; 0: single descent)")
      ->check(CLI::NonNegativeNumber);
  c->add_option("--max-condition", o->max_condition, "Reject lobe sets whose Y_l condition exceeds this (default 50)")
      ->check(CLI::Range(1.0, optimizer::kSingularCondition));
  c->add_flag("--no-sharing", o->no_sharing, "Each band gets its own 2l+1 lobes (N^2-4 in all)");
  c->add_flag("--exhaustive", o->exhaustive,
              "Enumerate every lobe set (up to permutations within a band); with --time-limit, report the bound");
  c->add_flag("--seed-from-continuous", o->seed_from_continuous,
              "Seed the GA with 16 continuous (nlopt) optima snapped to candidates");
  c->add_option("--objective", o->objective,
                 "sparsity (default: SH-zero candidates, most zeros within --max-condition) or amplification "
                 "(continuous lobes with the least float error amplification, for runtime/lanes.h)")
      ->check(CLI::IsMember({"sparsity", "amplification"}));
  CLI::Option* starts = c->add_option("--starts", o->starts,
                                      "amplification: random start points (default 8); more finds lower error, "
                                      "in proportion more time")
                            ->check(CLI::Range(1, 1000000));
  c->add_flag("--quiet", o->quiet, "No progress on stderr");
  c->add_option("--out", o->out, "Write the lobe table (zhf-lobes-1 JSON) here");
  c->callback([o, starts, &action, command_line] {
    o->starts_given = starts->count() > 0;
    action = [o, command_line] { return run_optimize(*o, command_line); };
  });
}

}  // namespace zhf::cli
