#include "zhf/pipeline/search.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "zhf/candidates/candidates.h"
#include "zhf/candidates/limits.h"
#include "zhf/codegen/kernels.h"
#include "zhf/optimizer/amplification.h"
#include "zhf/optimizer/continuous.h"
#include "zhf/optimizer/exhaustive.h"
#include "zhf/optimizer/local_search.h"

namespace zhf::pipeline {
namespace {

std::string format(const char* pattern, double a = 0, double b = 0, double c = 0, double d = 0, double e = 0) {
  char text[256];
  std::snprintf(text, sizeof text, pattern, a, b, c, d, e);
  return text;
}

nlohmann::json base_provenance(const SearchRequest& r) {
  nlohmann::json provenance = {{"zhf_version", ZHF_VERSION}, {"command", r.command}};
  if (r.objective == Objective::kOperations) provenance["objective"] = "operations";
  return provenance;
}

// What the lobe search ranks by: zeros (ties to the optimizer's multiply model, with which the
// checked-in tables were made and still reproduce), or the lobe rotation's multiplies that depend
// on the lobe set, as the code generator counts them.
optimizer::Scoring scoring(const SearchRequest& r) {
  optimizer::Scoring s;
  if (r.objective != Objective::kOperations) return s;
  s.ranking = optimizer::Ranking::kFewestMultiplies;
  s.lobe_set_multiplies = codegen::lobe_dependent_multiplies;
  return s;
}

// The search's figure of merit for the user: zeros, or multiplies and zeros.
std::string merit(const SearchRequest& r, const optimizer::Fitness& f) {
  return r.objective == Objective::kOperations ? format("%.0f lobe-dependent multiplies (%.0f zeros)", f.multiplies, f.zeros)
                                               : format("%.0f zeros", f.zeros);
}

void say(const SearchRequest& r, const std::string& line) {
  if (r.progress) r.progress(line);
}

SearchOutcome amplification(const SearchRequest& r) {
  if (!r.lobe_sharing || r.exhaustive || r.seed_from_continuous)
    throw std::invalid_argument("the amplification objective searches shared continuous lobes (no --no-sharing, "
                                "--exhaustive or --seed-from-continuous)");
  optimizer::AmplificationOptions options;
  options.seed = r.seed;
  options.starts = r.starts;
  options.threads = r.threads;
  options.stop = r.stop;
  const optimizer::AmplificationResult result = optimizer::amplification_search(r.order, options);
  SearchOutcome out;
  out.interrupted = result.interrupted;
  if (result.theta.empty()) {
    out.summary = "interrupted before the first pass ended";
    return out;
  }
  nlohmann::json provenance = base_provenance(r);
  provenance["seed"] = r.seed;
  provenance["objective"] = "amplification";
  provenance["starts"] = r.starts;
  provenance["evaluations"] = result.evaluations;
  out.table = optimizer::make_amplification_table(r.order, result, provenance);
  out.found = true;
  out.summary = "  float error amplification per band:";
  for (double a : result.amplification) out.summary += format(" %.3f", a);
  out.summary += format("\n  search: %.0f evaluations", double(result.evaluations));
  return out;
}

SearchOutcome exhaustive(const SearchRequest& r, const optimizer::LobeEvaluator& evaluator) {
  const optimizer::ExhaustiveResult e = optimizer::exhaustive_search(evaluator, r.time_limit, r.threads, r.stop);
  SearchOutcome out;
  out.interrupted = e.search.interrupted;
  if (!e.search.fitness.invertible) {
    // The enumeration starts among repeated and clustered lobes; a singular set is no table.
    out.summary = format("exhaustive: no invertible lobe set among the %.0f searched (%.1f s)", e.sets_evaluated, e.search.seconds);
    return out;
  }
  nlohmann::json provenance = base_provenance(r);
  provenance["exhaustive"] = e.complete ? "complete" : "partial";
  provenance["evaluations"] = e.search.evaluations;
  out.table = optimizer::make_table(evaluator, e.search.best, provenance);
  out.found = true;
  out.feasible = e.search.fitness.feasible;
  out.summary = e.complete ? format("  exhaustive: all %.0f lobe sets (up to permutations within a band) in %.1f s: ",
                                    e.sets_total, e.search.seconds) + merit(r, e.search.fitness) + " is optimal"
                           : format("  exhaustive: stopped after %.0f of %.3g lobe sets (%.2g%%) in %.1f s; best ",
                                    e.sets_evaluated, e.sets_total, 100 * e.sets_evaluated / e.sets_total, e.search.seconds) +
                                 merit(r, e.search.fitness) +
                                 (r.objective == Objective::kSparsity ? format(", bound %.0f zeros", e.upper_bound) : "");
  return out;
}

// The genetic search, then the iterated local search, under the evaluator's ranking.
SearchOutcome lobe_search(const SearchRequest& r, const optimizer::LobeEvaluator& evaluator) {
  optimizer::GeneticOptions ga;
  ga.seed = r.seed;
  ga.population = r.population;
  ga.max_generations = r.generations;
  ga.stall_generations = r.stall;
  ga.time_limit_seconds = r.time_limit;
  ga.threads = r.threads;
  ga.stop = r.stop;
  if (r.seed_from_continuous) {
    optimizer::ContinuousOptions continuous;
    continuous.seed = r.seed;
    for (const optimizer::ContinuousStart& start : optimizer::continuous_search(evaluator, continuous)) {
      ga.initial.push_back(start.snapped);
      say(r, format("continuous start: objective %.3f, snapped to %.0f zeros, worst cond %.3g", start.objective,
                    start.fitness.zeros, start.fitness.worst_condition));
    }
  }
  if (r.progress)
    ga.on_generation = [&r](const optimizer::GenerationReport& g) {
      say(r, format("ga generation %.0f: best ", g.generation) + merit(r, g.best) +
                 format(", worst cond %.2f, %.0f evaluations/s, %.1f s", g.best.worst_condition,
                        g.elapsed_seconds > 0 ? g.evaluations / g.elapsed_seconds : 0.0, g.elapsed_seconds));
    };
  const optimizer::SearchResult ga_result = optimizer::genetic_search(evaluator, ga);
  optimizer::LocalSearchOptions ils;
  ils.seed = r.seed;
  ils.stall_kicks = r.local_search_stall;
  ils.threads = r.threads;
  ils.stop = r.stop;
  ils.time_limit_seconds = r.time_limit > 0 ? std::max(candidates::kMinSearchSeconds, r.time_limit - ga_result.seconds) : 0;
  if (r.progress)
    ils.on_improvement = [&r](int kick, const optimizer::Fitness& best, long evaluations) {
      say(r, format("local search kick %.0f: best ", kick) + merit(r, best) +
                 format(", worst cond %.2f, %.0f evaluations", best.worst_condition, double(evaluations)));
    };
  const bool ran_local_search = !ga_result.interrupted && !ga_result.timed_out;
  optimizer::SearchResult ils_result;
  if (ran_local_search) ils_result = optimizer::iterated_local_search(evaluator, ga_result.best, ga_result.fitness, ils);
  const optimizer::SearchResult& final_result = ran_local_search ? ils_result : ga_result;
  SearchOutcome out;
  out.interrupted = ga_result.interrupted || ils_result.interrupted;
  const bool timed_out = ga_result.timed_out || ils_result.timed_out;
  nlohmann::json provenance = base_provenance(r);
  provenance["seed"] = r.seed;
  provenance["generations"] = ga_result.generations;
  provenance["local_search_kicks"] = ils_result.generations;
  provenance["evaluations"] = ga_result.evaluations + ils_result.evaluations;
  provenance["stopped_by"] = out.interrupted ? "interrupt" : timed_out ? "time limit" : "stall";
  out.table = optimizer::make_table(evaluator, final_result.best, provenance);
  out.found = true;
  out.feasible = final_result.fitness.feasible;
  out.summary = format("  search: %.0f generations, %.0f local-search kicks, %.0f evaluations, %.1f s", ga_result.generations,
                       ils_result.generations, double(ga_result.evaluations + ils_result.evaluations),
                       ga_result.seconds + ils_result.seconds);
  if (!out.feasible)
    out.summary += format("\n  note: no lobe set within --max-condition %.3g was found; this is the best unbounded one", r.max_condition);
  return out;
}

}  // namespace

SearchOutcome search(const SearchRequest& request) {
  if (request.order < candidates::kMinSearchOrder || request.order > candidates::kMaxSearchOrder)
    throw std::invalid_argument("order " + std::to_string(request.order) + " is outside [" +
                                std::to_string(candidates::kMinSearchOrder) + ", " + std::to_string(candidates::kMaxSearchOrder) + "]");
  if (request.objective == Objective::kAmplification) return amplification(request);
  const candidates::CandidateSet set = candidates::enumerate_candidates(request.order);
  const optimizer::LobeEvaluator evaluator(set, request.lobe_sharing, request.max_condition, scoring(request));
  return request.exhaustive ? exhaustive(request, evaluator) : lobe_search(request, evaluator);
}

}  // namespace zhf::pipeline
