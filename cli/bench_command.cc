#include <cstdio>
#include <memory>

#include "commands.h"
#include "options.h"
#include "progress.h"
#include "zhf/bench/limits.h"
#include "zhf/bench/plots.h"
#include "zhf/io/files.h"
#include "zhf/io/signals.h"
#include "zhf/pipeline/data_root.h"

namespace zhf::cli {
namespace {

struct BenchOptions {
  bool quick = false;
  bool quiet = false, verbose = false;
  std::string orders;
  std::string json;
  std::string plot;
  std::string from;
};

// --from: the plots of a report written before, drawn again (nothing measured).
int redraw(const BenchOptions& o) {
  if (o.plot.empty()) throw UsageError("--from: give --plot too (it redraws the plots of a saved report)");
  if (o.quick || !o.orders.empty() || !o.json.empty()) throw UsageError("--from: measures nothing; drop --quick, --orders and --out");
  io::PendingFile check(o.plot);
  bench::check_plot_targets(o.plot);
  const bench::SuiteReport report = bench::read_report(o.from);
  io::PendingFiles outputs;
  const std::string plots = bench::stage_plots(report, o.plot, outputs);
  outputs.commit();
  std::printf("%s\n", plots.c_str());
  return kExitOk;
}

int run_bench(const BenchOptions& o) {
  if (!o.from.empty()) return redraw(o);
  bench::SuiteOptions options;
  options.quick = o.quick;
  if (!o.orders.empty()) options.orders = orders_option("--orders", o.orders, 2, bench::kMaxBenchOrder);
  options.source_dir = pipeline::data_root().root;
  // Refuse an unwritable output before minutes of measuring, not after.
  if (!o.json.empty()) io::PendingFile check(o.json);
  if (!o.plot.empty()) {
    io::PendingFile check(o.plot);
    bench::check_plot_targets(o.plot);
  }
  Progress progress("bench", o.quiet, o.verbose);
  options.progress = [&progress](const std::string& line) { progress.say("measuring " + line); };
  const bench::SuiteReport report = bench::run_suite(options);
  progress.done();
  std::printf("CPU: %s\ncompiler: %s\nflags: %s\ndate: %s\n\n%s", report.cpu.c_str(), report.compiler.c_str(),
              report.flags.c_str(), report.date.c_str(), report.table().c_str());
  std::printf("\nscaling (single vector, ns ~ N^k over orders >= 3):");
  for (const char* method : {"zhf", "zhf_runtime", "zxzxz", "ivanic_ruedenberg", "healpix"}) {
    const double k = bench::scaling_exponent(report, method, "single", method == std::string("healpix") ? "incl. real<->complex" : "");
    if (k == k) std::printf(" %s %.2f;", method, k);
  }
  std::printf("\n");
  // The report and its plots are one result: if gnuplot fails, or a signal comes, nothing is written.
  io::PendingFiles outputs;
  const std::string plots = o.plot.empty() ? "" : bench::stage_plots(report, o.plot, outputs);
  if (!o.json.empty()) outputs.add(o.json).write(io::json_text(report.to_json()));
  outputs.commit();
  if (!o.json.empty()) std::printf("wrote %s\n", o.json.c_str());
  if (!plots.empty()) std::printf("%s\n", plots.c_str());
  return kExitOk;
}

}  // namespace

void add_bench_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* c = app.add_subcommand("bench", "Time and error of every rotation method, per order and scenario");
  c->add_flag("--quick", o->quick, "Small counts and few repeats (CI: checks every method runs and is accurate)");
  add_progress_flags(c, o->quiet, o->verbose);
  c->add_option("--orders", o->orders, "Orders, e.g. 3,5,8 or 2..8, each 2.." + std::to_string(bench::kMaxBenchOrder) +
                                          " (default 2..8 plus 10, 12, 16)");
  keep_old_spelling(c, c->add_option("--out", o->json, "Write every measurement as JSON here"), "--json", o->json);
  c->add_option("--plot", o->plot,
                "Write the Pareto fronts here (SVG), and beside it FILE_scenarios.svg, FILE_scaling.svg, FILE.csv and FILE.gp "
                "(replaced only when zhf bench wrote them; needs gnuplot)");
  c->add_option("--from", o->from, "Redraw the --plot files from a report an earlier --out wrote (measures nothing)");
  c->callback([o, &action] { action = [o] { return run_bench(*o); }; });
}

}  // namespace zhf::cli
