// zhf designs: a spherical t-design by the design search (frames/designs.h), written as a design
// file.
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>

#include "commands.h"
#include "options.h"
#include "progress.h"
#include "zhf/frames/designs.h"
#include "zhf/frames/limits.h"
#include "zhf/io/files.h"
#include "zhf/io/signals.h"
#include "zhf/runtime/parallel.h"

namespace zhf::cli {
namespace {

struct DesignsOptions {
  std::string t, count = "0", starts = "64", seed = "1", threads = "0";
  bool symmetric = false, tetrahedral = false, threefold = false, quiet = false;
  std::string out;
};

// The smallest counts published for t: Hardin and Sloane's library to t = 21, and Womersley's
// antipodal designs where they are smaller (t = 19 and 21).
std::string known_counts(int t) {
  const int hardin_sloane = frames::best_known_count(t);
  if (hardin_sloane < 0) return "efficient count " + std::to_string(frames::efficient_count(t));
  std::string text = "Hardin-Sloane " + std::to_string(hardin_sloane);
  if (t == 19 || t == 21) text += ", Womersley " + std::to_string(frames::symmetric_count(t));
  return text;
}

int run_designs(const DesignsOptions& o) {
  frames::DesignSearch s;
  s.t = static_cast<int>(integer_option("--t", o.t, 1, frames::kMaxDesignStrength));
  if (o.tetrahedral && (o.symmetric || o.threefold)) throw UsageError("--tetrahedral: not with --symmetric or --threefold");
  const int best = frames::best_known_count(s.t);
  const frames::DesignChoice choice = frames::default_design(s.t);
  s.points = static_cast<int>(integer_option("--count", o.count, 0, frames::kMaxDesignPoints));
  s.symmetry = o.symmetric && o.threefold ? frames::Symmetry::kAntipodalThreefold
               : o.symmetric ? frames::Symmetry::kAntipodal
               : o.tetrahedral ? frames::Symmetry::kTetrahedral
               : o.threefold   ? frames::Symmetry::kThreefold
                               : s.points ? frames::Symmetry::kFree : choice.symmetry;
  // Each symmetry its own count: the default's where the default has that symmetry.
  if (s.points == 0) s.points = frames::symmetry_count(s.symmetry, s.t);
  if (s.points < 2) throw UsageError("--count: a design needs at least 2 points");
  const int orbit = frames::orbit_size(s.symmetry);
  if (s.points % orbit)
    throw UsageError("--count: " + std::string(s.symmetry == frames::Symmetry::kAntipodal ? "a symmetric design has an even count" : "a design of whole orbits has a multiple of " + std::to_string(orbit) + " points") +
                     " (got " + std::to_string(s.points) + ")");
  s.starts = static_cast<int>(integer_option("--starts", o.starts, 1, frames::kMaxDesignStarts));
  s.seed = seed_option("--seed", o.seed);
  s.threads = runtime::worker_count(threads_option(o.threads));
  s.interrupted = [] { return io::interrupt_requested().load(); };
  Progress progress("designs", o.quiet);
  s.progress = [&](int started) { progress.update(started, s.starts, "starts tried for a " + std::to_string(s.points) + "-point " + std::to_string(s.t) + "-design"); };
  std::unique_ptr<io::PendingFile> out;
  if (!o.out.empty()) out = std::make_unique<io::PendingFile>(o.out);
  const auto t0 = std::chrono::steady_clock::now();
  const frames::Design d = frames::search_design(s);
  progress.done();
  io::throw_if_interrupted();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (d.start < 0) {
    std::fprintf(stderr, "zhf designs: no %d-point %d-design in %d starts (best residual %.3g)\n", s.points, s.t, s.starts, d.residual);
    return kExitFailure;
  }
  std::printf("t = %d: %zu points (%s), residual %.2e, start %d, %.2f s\n", s.t, d.points.size(), known_counts(s.t).c_str(),
              d.residual, d.start, seconds);
  if (out) {
    nlohmann::ordered_json j;
    j["format"] = frames::kDesignFormat;
    j["t"] = s.t;
    j["count"] = d.points.size();
    j["symmetric"] = s.symmetry == frames::Symmetry::kAntipodal || s.symmetry == frames::Symmetry::kAntipodalThreefold;
    j["tetrahedral"] = s.symmetry == frames::Symmetry::kTetrahedral;
    j["threefold"] = s.symmetry == frames::Symmetry::kThreefold || s.symmetry == frames::Symmetry::kAntipodalThreefold;
    j["residual"] = d.residual;
    j["best_known_count"] = best > 0 ? nlohmann::ordered_json(best) : nlohmann::ordered_json(nullptr);
    j["search"] = {{"seed", s.seed}, {"start", d.start}};
    nlohmann::ordered_json points = nlohmann::ordered_json::array();
    for (const frames::Point& p : d.points) points.push_back({p[0], p[1], p[2]});
    j["points"] = points;
    out->write(io::json_text(j));
    out->commit();
  }
  return kExitOk;
}


}  // namespace

void add_designs_command(CLI::App& app, Action& action) {
  auto d = std::make_shared<DesignsOptions>();
  CLI::App* c = app.add_subcommand("designs", "Find a spherical t-design: equal-weight points exact for every SH of degree <= t");
  c->add_option("--t", d->t, "Strength t (exact for every SH of degree <= t), 1.." + std::to_string(frames::kMaxDesignStrength))->required();
  CLI::Option* count = c->add_option("--count", d->count,
                "Point count (default: the smallest known for t <= 10, antipodal sets of the smallest known count for odd t "
                "(Womersley's 192 and 234 at 19 and 21) to 21, whole orbits for even t >= 12 (tetrahedral or threefold; the smallest known up to 20) "
                "and for odd t >= 23 (antipodal threefold; antipodal sets at t = 25, 37, 49, ..., where those need 2 points fewer))");
  c->add_flag("--symmetric", d->symmetric, "Antipodal pairs: x and -x (odd bands vanish; half the unknowns); with --threefold, orbits of 6");
  c->add_flag("--tetrahedral", d->tetrahedral, "Whole orbits of the chiral tetrahedral group (12 rotations; count a multiple of 12): only its invariant harmonics remain");
  c->add_flag("--threefold", d->threefold, "Whole orbits of the turns about z by 120 degrees (count a multiple of 3): only the harmonics with 3 | m remain");
  keep_old_spelling(c, count, "--points", d->count);
  c->add_option("--starts", d->starts, "Starts to try, 1.." + std::to_string(frames::kMaxDesignStarts) + " (default 64); the first that converges wins");
  c->add_option("--seed", d->seed, "Random seed, 0..2^64-1 (default 1)");
  add_threads_option(c, d->threads);
  c->add_flag("--quiet", d->quiet, "No progress line");
  keep_old_spelling(c, c->add_option("--out", d->out, "Write the design here (zhf-design-1)"), "--json", d->out);
  c->callback([d, &action] { action = [d] { return run_designs(*d); }; });
}

}  // namespace zhf::cli
