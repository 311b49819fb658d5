#include <chrono>
#include <cstdio>
#include <memory>
#include <thread>
#include <string>
#include <vector>

#include "commands.h"
#include "options.h"
#include "zhf/frames/designs.h"
#include "zhf/frames/frame.h"
#include "zhf/io/errors.h"
#include "zhf/io/files.h"
#include "zhf/io/signals.h"
#include "zhf/runtime/limits.h"
#include "zhf/runtime/lobe_table.h"

namespace zhf::cli {
namespace {

struct DesignsOptions {
  std::string t, points = "0", starts = "64", seed = "1", threads = "0";
  bool symmetric = false;
  std::string out;
};

int run_designs(const DesignsOptions& o) {
  frames::DesignSearch s;
  s.t = static_cast<int>(integer_option("--t", o.t, 1, frames::kMaxDesignStrength));
  s.symmetric = o.symmetric;
  const int best = frames::best_known_count(s.t);
  const frames::DesignChoice choice = frames::default_design(s.t);
  s.points = static_cast<int>(integer_option("--points", o.points, 0, frames::kMaxPoints));
  if (s.points == 0) {
    s.points = choice.points;
    s.symmetric = s.symmetric || choice.symmetric;
  }
  if (s.points < 2) throw UsageError("--points: a design needs at least 2 points");
  if (s.symmetric && s.points % 2) throw UsageError("--points: a symmetric design has an even count (got " + std::to_string(s.points) + ")");
  s.starts = static_cast<int>(integer_option("--starts", o.starts, 1, 100000));
  s.seed = seed_option("--seed", o.seed);
  const int threads = static_cast<int>(integer_option("--threads", o.threads, 0, runtime::kMaxThreads));
  s.threads = threads ? threads : std::max(1u, std::thread::hardware_concurrency());
  s.interrupted = [] { return io::interrupt_requested().load(); };
  std::unique_ptr<io::PendingFile> out;
  if (!o.out.empty()) out = std::make_unique<io::PendingFile>(o.out);
  const auto t0 = std::chrono::steady_clock::now();
  const frames::Design d = frames::search_design(s);
  io::throw_if_interrupted();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (d.start < 0) {
    std::fprintf(stderr, "zhf designs: no %d-point %d-design in %d starts (best residual %.3g)\n", s.points, s.t, s.starts, d.residual);
    return kExitFailure;
  }
  std::printf("t = %d: %zu points (best known %s), residual %.2e, start %d, %.2f s\n", s.t, d.points.size(),
              best > 0 ? std::to_string(best).c_str() : "-", d.residual, d.start, seconds);
  if (out) {
    nlohmann::ordered_json j;
    j["format"] = frames::kDesignFormat;
    j["t"] = s.t;
    j["count"] = d.points.size();
    j["symmetric"] = s.symmetric;
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

struct FrameOptions {
  std::string points, table, bands;
  std::string out;
};

int run_frame(const FrameOptions& o) {
  if (o.points.empty() == o.table.empty()) throw UsageError("--points or --table: give exactly one");
  std::unique_ptr<io::PendingFile> out;
  if (!o.out.empty()) out = std::make_unique<io::PendingFile>(o.out);
  // Band ranges: --bands L0..L1 over every direction; a table without --bands: each band on its lobes.
  struct Job {
    std::vector<frames::Point> directions;
    int lmin, lmax;
  };
  std::vector<Job> jobs;
  int lmin = 0, lmax = -1;
  if (!o.bands.empty()) {
    const std::vector<int> bands = orders_option("--bands", o.bands, 0, frames::kMaxFrameBand);
    lmin = bands.front();
    lmax = bands.back();
    if (lmax - lmin + 1 != static_cast<int>(bands.size())) throw UsageError("--bands: give a range L0..L1");
  }
  if (!o.points.empty()) {
    if (o.bands.empty()) throw UsageError("--bands: required with --points");
    jobs.push_back({frames::read_points(o.points), lmin, lmax});
  } else {
    const runtime::LobeTable table = runtime::read_lobe_table(o.table);
    std::vector<frames::Point> all;
    for (const runtime::TableLobe& lobe : table.lobes) all.push_back({lobe.xyz[0], lobe.xyz[1], lobe.xyz[2]});
    if (!o.bands.empty()) {
      jobs.push_back({all, lmin, lmax});
    } else {
      for (const runtime::TableBand& band : table.bands) {
        std::vector<frames::Point> lobes;
        for (int d : band.lobes) lobes.push_back(all[d]);
        jobs.push_back({lobes, band.l, band.l});
      }
    }
  }
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  std::printf("%-7s %10s %9s %14s %14s %10s %11s  %s\n", "bands", "directions", "dimension", "A", "B", "sqrt(B/A)", "redundancy",
              "kind");
  for (const Job& job : jobs) {
    const frames::FrameBounds b = frames::frame_bounds(job.directions, job.lmin, job.lmax);
    const std::string kind = !b.frame() ? "not a frame" : b.parseval() ? "Parseval tight" : b.tight() ? "tight" : "frame";
    const std::string bands = std::to_string(b.lmin) + ".." + std::to_string(b.lmax);
    std::printf("%-7s %10d %9d %14.8g %14.8g %10.4g %11.4g  %s\n", bands.c_str(), b.directions, b.dimension, b.lower, b.upper,
                b.condition(), b.redundancy(), kind.c_str());
    rows.push_back({{"lmin", b.lmin},
                    {"lmax", b.lmax},
                    {"directions", b.directions},
                    {"dimension", b.dimension},
                    {"lower_bound", b.lower},
                    {"upper_bound", b.upper},
                    {"condition", b.frame() ? nlohmann::ordered_json(b.condition()) : nlohmann::ordered_json(nullptr)},
                    {"redundancy", b.redundancy()},
                    {"tight", b.tight()},
                    {"parseval", b.parseval()}});
    io::throw_if_interrupted();
  }
  if (out) {
    out->write(io::json_text(nlohmann::ordered_json{{"format", "zhf-frame-1"}, {"frames", rows}}));
    out->commit();
  }
  return kExitOk;
}

}  // namespace

void add_frames_commands(CLI::App& app, Action& action) {
  auto d = std::make_shared<DesignsOptions>();
  CLI::App* c = app.add_subcommand("designs", "Find a spherical t-design: equal-weight points exact for every SH of degree <= t");
  c->add_option("--t", d->t, "Strength t, 1..50")->required();
  c->add_option("--points", d->points,
                "Point count (default: the smallest known for t <= 10, antipodal sets of the smallest known count for odd t "
                "(Womersley's 192 and 234 at 19 and 21), the efficient count ceil((t+1)^2/2)+1 for even t >= 12)");
  c->add_flag("--symmetric", d->symmetric, "Antipodal pairs: x and -x (odd bands vanish; half the unknowns)");
  c->add_option("--starts", d->starts, "Starts to try, 1..100000 (default 64); the first that converges wins");
  c->add_option("--seed", d->seed, "Random seed, 0..2^64-1 (default 1)");
  c->add_option("--threads", d->threads, "Threads, 0..256 (0: all cores); never changes the result");
  c->add_option("--json", d->out, "Write the design here (zhf-design-1)");
  c->callback([d, &action] { action = [d] { return run_designs(*d); }; });

  auto f = std::make_shared<FrameOptions>();
  CLI::App* fc = app.add_subcommand("frame", "Frame bounds of the zonal lobes at a set of directions, for a band range");
  fc->add_option("--points", f->points, "Directions: a JSON array of [x, y, z] or a design file");
  fc->add_option("--table", f->table, "A lobe table's lobes (without --bands: each band on its own lobes)");
  fc->add_option("--bands", f->bands, "Bands L0..L1 (0..63)");
  fc->add_option("--json", f->out, "Write the bounds here (zhf-frame-1)");
  fc->callback([f, &action] { action = [f] { return run_frame(*f); }; });
}

}  // namespace zhf::cli
