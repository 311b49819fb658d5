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
#include "zhf/frames/needlets.h"
#include "zhf/pipeline/project.h"
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

struct NeedletOptions {
  std::string dilation = "2", lmax, sizes = "64,256,1024,4096,16384";
  bool gauss = false;
  std::string out;
};

double dilation_option(const std::string& text) {
  return number_option("--B", text, frames::kMinDilation, frames::kMaxDilation);
}

int run_needlet_window(const NeedletOptions& o) {
  const double dilation = dilation_option(o.dilation);
  const int lmax = static_cast<int>(integer_option("--lmax", o.lmax, 0, frames::kMaxNeedletBand));
  std::unique_ptr<io::PendingFile> out;
  if (!o.out.empty()) out = std::make_unique<io::PendingFile>(o.out);
  nlohmann::ordered_json b = nlohmann::ordered_json::array();
  const std::vector<frames::WindowValue> windows = frames::needlet_windows(dilation, lmax);
  for (std::size_t i = 0; i < windows.size(); ++i) {
    const frames::WindowValue& w = windows[i];
    b.push_back({w.j, w.l, w.value});
    if (i == 0 || windows[i - 1].j != w.j) std::printf("level %d: bands %d..", w.j, w.l);
    if (i + 1 == windows.size() || windows[i + 1].j != w.j) std::printf("%d\n", w.l);
  }
  std::printf("%zu windows\n", b.size());
  if (out) {
    out->write(io::json_text(nlohmann::ordered_json{{"format", "zhf-needlet-window-1"}, {"B", dilation}, {"lmax", lmax}, {"b", b}}));
    out->commit();
  }
  return kExitOk;
}

// The frame's levels, the kernel tables' error per size, and the tabulated rotation's error per
// size against the exact path; times on stdout only, so the JSON is the same on every run.
int run_needlet_tables(const NeedletOptions& o) {
  const double dilation = dilation_option(o.dilation);
  const int lmax = static_cast<int>(integer_option("--lmax", o.lmax, 1, frames::kMaxNeedletFrameBand));
  const std::vector<int> sizes = orders_option("--sizes", o.sizes, frames::kMinTableSize, frames::kMaxTableSize);
  if (sizes.size() > 16) throw UsageError("--sizes: at most 16 sizes (got " + std::to_string(sizes.size()) + ")");
  std::unique_ptr<io::PendingFile> out;
  if (!o.out.empty()) out = std::make_unique<io::PendingFile>(o.out);
  const std::string designs = pipeline::project().generated() + "/designs";
  const frames::NeedletFrame frame =
      o.gauss ? frames::NeedletFrame(dilation, lmax)
              : frames::NeedletFrame(dilation, lmax, [&](int degree) { return frames::design_cubature(designs, degree); });
  nlohmann::ordered_json levels = nlohmann::ordered_json::array();
  std::printf("%6s %9s %7s  %s\n", "level", "bands", "points", "cubature");
  for (const frames::NeedletLevel& level : frame.levels()) {
    const std::string bands = std::to_string(level.lmin) + ".." + std::to_string(level.lmax);
    std::printf("%6d %9s %7zu  %s\n", level.j, bands.c_str(), level.cubature.points.size(), level.cubature.name.c_str());
    levels.push_back({{"j", level.j}, {"lmin", level.lmin}, {"lmax", level.lmax}, {"points", level.cubature.points.size()},
                      {"cubature", level.cubature.name}});
  }
  const auto how_name = [](frames::Interpolation how) { return how == frames::Interpolation::kLinear ? "linear" : "quadratic"; };
  const frames::Interpolation hows[] = {frames::Interpolation::kLinear, frames::Interpolation::kQuadratic};

  // Kernel tables: the worst level's error relative to its peak.
  nlohmann::ordered_json kernel_rows = nlohmann::ordered_json::array();
  std::printf("\nkernel table (max error / peak, worst level)\n%8s %12s %12s\n", "size", "linear", "quadratic");
  for (int size : sizes) {
    nlohmann::ordered_json row{{"size", size}};
    std::printf("%8d", size);
    for (frames::Interpolation how : hows) {
      double worst = 0;
      for (int a = 1; a < static_cast<int>(frame.levels().size()); ++a) {
        const auto kernel = [&](double t) { return frame.kernel(a, t); };
        worst = std::max(worst, frames::table_error(frames::UniformTable(kernel, size), kernel, how));
      }
      row[how_name(how)] = worst;
      std::printf(" %12.3e", worst);
      io::throw_if_interrupted();
    }
    std::printf("\n");
    kernel_rows.push_back(row);
  }

  // Rotation of a fixed unit-norm signal by a fixed turn: max coefficient error against the exact path.
  std::vector<double> f(runtime::coefficient_count(lmax + 1));
  for (std::size_t i = 0; i < f.size(); ++i) f[i] = std::sin(1.0 + 0.7 * double(i)) / std::sqrt(double(f.size()) / 2);
  const std::vector<double> beta = frame.analyze(f);
  const runtime::Matrix3 r = runtime::rotation_from_zyz(0.3, 1.1, -0.7);
  auto t0 = std::chrono::steady_clock::now();
  const std::vector<double> exact = frame.rotate_exact(beta, r);
  const double exact_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  nlohmann::ordered_json rotation_rows = nlohmann::ordered_json::array();
  std::printf("\nrotation of %d coefficients (max error against the exact path; exact path %.3g ms)\n%8s %12s %12s %12s %12s\n",
              frame.size(), exact_seconds * 1e3, "size", "linear", "ms", "quadratic", "ms");
  for (int size : sizes) {
    nlohmann::ordered_json row{{"size", size}};
    std::printf("%8d", size);
    for (frames::Interpolation how : hows) {
      const frames::TabulatedNeedletRotation rotation(frame, size, how);
      t0 = std::chrono::steady_clock::now();
      const std::vector<double> turned = rotation.rotate(beta, r);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      double worst = 0;
      for (std::size_t i = 0; i < turned.size(); ++i) worst = std::max(worst, std::abs(turned[i] - exact[i]));
      row[how_name(how)] = worst;
      std::printf(" %12.3e %12.3g", worst, seconds * 1e3);
      io::throw_if_interrupted();
    }
    std::printf("\n");
    rotation_rows.push_back(row);
  }
  if (out) {
    out->write(io::json_text(nlohmann::ordered_json{{"format", "zhf-needlet-tables-1"},
                                                    {"B", dilation},
                                                    {"lmax", lmax},
                                                    {"coefficients", frame.size()},
                                                    {"levels", levels},
                                                    {"kernel_tables", kernel_rows},
                                                    {"rotation", rotation_rows}}));
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

  CLI::App* nc = app.add_subcommand("needlets", "Spherical needlets: windows, kernel tables and tabulated rotation");
  nc->require_subcommand(1);
  auto w = std::make_shared<NeedletOptions>();
  CLI::App* wc = nc->add_subcommand("window", "The Littlewood-Paley windows b(l / B^j), every non-zero one for bands 0..lmax");
  wc->add_option("--B", w->dilation, "Dilation B, in [1.05, 64] (default 2)");
  wc->add_option("--lmax", w->lmax, "Highest band, 0..4096")->required();
  wc->add_option("--json", w->out, "Write the windows here: {\"B\", \"lmax\", \"b\": [[j, l, value], ...]}");
  wc->callback([w, &action] { action = [w] { return run_needlet_window(*w); }; });
  auto t = std::make_shared<NeedletOptions>();
  CLI::App* tc = nc->add_subcommand("tables", "The needlet frame of bands 0..lmax: levels, kernel look-up error and tabulated rotation error per table size");
  tc->add_option("--B", t->dilation, "Dilation B, in [1.05, 64] (default 2)");
  tc->add_option("--lmax", t->lmax, "Band limit, 1..64")->required();
  tc->add_option("--sizes", t->sizes, "Table sizes, e.g. 64,256,1024 (3..1048576; default 64,256,1024,4096,16384)");
  tc->add_flag("--gauss", t->gauss, "Gauss product cubatures at every level instead of the shipped designs");
  tc->add_option("--json", t->out, "Write the tables here (zhf-needlet-tables-1)");
  tc->callback([t, &action] { action = [t] { return run_needlet_tables(*t); }; });
}

}  // namespace zhf::cli
