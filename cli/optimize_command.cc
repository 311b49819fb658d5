#include <unistd.h>

#include <cstdio>
#include <memory>

#include "commands.h"
#include "options.h"
#include "progress.h"
#include "zhf/candidates/limits.h"
#include "zhf/codegen/kernels.h"
#include "zhf/codegen/limits.h"
#include "zhf/io/files.h"
#include "zhf/io/lobe_table_writer.h"
#include "zhf/io/signals.h"
#include "zhf/pipeline/search.h"
#include "zhf/runtime/errors.h"
#include "zhf/runtime/tolerances.h"

namespace zhf::cli {
namespace {

struct OptimizeOptions {
  std::string order, seed = "1", time_limit = "0", threads = "0", population = "500", generations = "0", stall = "50",
                     local_search_stall = "100", max_condition = "50", starts = "8";
  bool starts_given = false;
  bool no_sharing = false;
  bool exhaustive = false;
  bool seed_from_continuous = false;
  bool quiet = false, verbose = false;
  std::string objective = "sparsity";
  std::string out;
};

// The published figures for the paper's lobe sets (with sharing), recomputed by zhf.
struct PaperFigure {
  int order, zeros;
  double worst_condition;
};
constexpr PaperFigure kPaper[] = {{3, 16, 2.12},  {4, 41, 6.80},   {5, 80, 14.62},
                                  {6, 139, 307.29}, {7, 199, 137.98}, {8, 286, 4107.88}};

void print_summary(const runtime::LobeTable& table) {
  std::printf("order %d, %s, %zu lobes\n", table.order, table.lobe_sharing ? "lobe sharing" : "no sharing", table.lobes.size());
  std::printf("  band  zeros/entries  condition  multiplies of z = A^T f\n");
  int multiplies = 0;
  for (const runtime::TableBand& band : table.bands) {
    const int band_multiplies = codegen::lobe_weight_multiplies(band.inverse);
    multiplies += band_multiplies;
    std::printf("  %4d  %5d/%-7d  %9.2f  %10d\n", band.l, band.zeros, band.inverse.rows * band.inverse.cols, band.condition,
                band_multiplies);
  }
  std::printf("  total %d/%d zeros (%.1f%% sparse), worst condition %.2f, %d multiplies\n", table.zeros, table.entries,
              100.0 * table.zeros / std::max(1, table.entries), table.worst_condition(), multiplies);
  if (table.order <= codegen::kMaxEmitOrder)
    std::printf("  rotate_order%d by lobes (zhf emit --method zhf): %d multiplies, %d of them depending on the lobe set\n",
                table.order, codegen::lobe_rotation_multiplies(table), codegen::lobe_dependent_multiplies(table));
  for (const PaperFigure& p : kPaper)
    if (p.order == table.order && table.lobe_sharing)
      std::printf("  paper: %d zeros, worst condition %.2f\n", p.zeros, p.worst_condition);
}

int run_optimize(const OptimizeOptions& o, const std::string& command) {
  pipeline::SearchRequest r;
  r.order = static_cast<int>(integer_option("--order", o.order, candidates::kMinSearchOrder, candidates::kMaxSearchOrder));
  r.objective = o.objective == "amplification" ? pipeline::Objective::kAmplification
                : o.objective == "operations"  ? pipeline::Objective::kOperations
                                               : pipeline::Objective::kSparsity;
  r.seed = seed_option("--seed", o.seed);
  r.time_limit = number_option("--time-limit", o.time_limit, 0, candidates::kMaxSearchTimeLimit);
  r.threads = threads_option(o.threads);
  r.population = static_cast<int>(integer_option("--population", o.population, candidates::kMinPopulation, candidates::kMaxPopulation));
  r.generations = static_cast<int>(integer_option("--generations", o.generations, 0, candidates::kMaxGenerations));
  r.stall = static_cast<int>(integer_option("--stall", o.stall, 1, candidates::kMaxStall));
  r.local_search_stall = static_cast<int>(integer_option("--local-search-stall", o.local_search_stall, 0, candidates::kMaxStall));
  r.max_condition = number_option("--max-condition", o.max_condition, 1.0, runtime::tolerance::kSingularCondition);
  r.starts = static_cast<int>(integer_option("--starts", o.starts, 1, candidates::kMaxSearchStarts));
  r.lobe_sharing = !o.no_sharing;
  r.exhaustive = o.exhaustive;
  r.seed_from_continuous = o.seed_from_continuous;
  r.command = command;
  r.stop = &io::interrupt_requested();
  if (r.objective == pipeline::Objective::kAmplification && (o.no_sharing || o.exhaustive || o.seed_from_continuous))
    throw UsageError("--objective amplification: searches shared continuous lobes; drop --no-sharing, --exhaustive and "
                     "--seed-from-continuous");
  if (r.objective != pipeline::Objective::kAmplification && o.starts_given)
    throw UsageError("--starts: only --objective amplification has random starts");
  // Refuse an unwritable output before the search, not after it.
  if (!o.out.empty()) io::PendingFile check(o.out);
  Progress progress("optimize", o.quiet, o.verbose);
  r.progress = [&progress](const std::string& line) { progress.say(line); };
  const pipeline::SearchOutcome outcome = pipeline::search(r);
  progress.done();
  if (!outcome.found) {
    std::printf("%s; nothing written\n", outcome.summary.c_str());
    return outcome.interrupted ? io::interrupted_exit_code() : kExitFailure;
  }
  print_summary(outcome.table);
  std::printf("%s\n", outcome.summary.c_str());
  const std::string text = io::lobe_table_text(outcome.table, o.out.empty() ? "the table found" : o.out);
  if (outcome.interrupted) {
    // The best table so far goes beside the output, which stays untouched.
    const std::string path = (o.out.empty() ? "zhf-order-" + std::to_string(r.order) + ".json" : o.out) + ".interrupted.json";
    io::write_file_atomically(path, text, io::OnInterrupt::kCommit);
    std::fprintf(stderr, "zhf: interrupted; the best table so far is in %s (%s untouched)\n", path.c_str(),
                 o.out.empty() ? "no output" : o.out.c_str());
    return io::interrupted_exit_code();
  }
  if (!o.out.empty()) {
    io::write_file_atomically(o.out, text);
    std::printf("wrote %s\n", o.out.c_str());
  }
  return kExitOk;
}

}  // namespace

void add_optimize_command(CLI::App& app, Action& action, const std::string& command_line) {
  auto o = std::make_shared<OptimizeOptions>();
  CLI::App* c = app.add_subcommand("optimize", "Search for sparse lobe directions of an order");
  c->add_option("--order", o->order, "Order N (bands 0..N-1), " + std::to_string(candidates::kMinSearchOrder) + ".." + std::to_string(candidates::kMaxSearchOrder))->required();
  c->add_option("--seed", o->seed, "Random seed, 0..2^64-1 (default 1)");
  c->add_option("--time-limit", o->time_limit, "Stop after this many seconds (0: none; results then depend on speed)");
  add_threads_option(c, o->threads);
  c->add_option("--population", o->population, "GA population, " + std::to_string(candidates::kMinPopulation) + ".." + std::to_string(candidates::kMaxPopulation) + " (default 500)");
  c->add_option("--generations", o->generations, "GA generation limit (0: none)");
  c->add_option("--stall", o->stall, "GA stops after this many generations without improvement (default 50)");
  c->add_option("--local-search-stall", o->local_search_stall,
                "Local search stops after this many kicks without improvement (default 100; 0: single descent)");
  c->add_option("--max-condition", o->max_condition, "Reject lobe sets whose Y_l condition exceeds this, 1.." + runtime::format_number(runtime::tolerance::kSingularCondition) + " (default 50)");
  c->add_flag("--no-sharing", o->no_sharing, "Each band gets its own 2l+1 lobes (N^2-4 in all)");
  c->add_flag("--exhaustive", o->exhaustive,
              "Enumerate every lobe set (up to permutations within a band); with --time-limit, report the bound");
  c->add_flag("--seed-from-continuous", o->seed_from_continuous, "Seed the GA with 16 continuous (nlopt) optima snapped to candidates");
  c->add_option("--objective", o->objective,
                "sparsity (default: SH-zero candidates, most zeros within --max-condition), operations (SH-zero "
                "candidates, fewest emitted multiplies of the lobe weights z = A^T f within --max-condition) or "
                "amplification (continuous lobes with the least float error amplification: the lanes tables of "
                "runtime/lanes.h)")
      ->check(CLI::IsMember({"sparsity", "operations", "amplification"}));
  CLI::Option* starts = c->add_option("--starts", o->starts,
                                      "amplification: random start points (default 8); more finds lower error, in proportion more time");
  add_progress_flags(c, o->quiet, o->verbose);
  c->add_option("--out", o->out, "Write the lobe table (zhf-lobes-1 JSON) here");
  c->callback([o, starts, &action, command_line] {
    o->starts_given = starts->count() > 0;
    action = [o, command_line] { return run_optimize(*o, command_line); };
  });
}

}  // namespace zhf::cli
