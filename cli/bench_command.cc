#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>

#include "commands.h"
#include "zhf/bench/suite.h"
#include "zhf/io/files.h"

namespace zhf::cli {
namespace {

struct BenchOptions {
  bool quick = false;
  std::string orders;
  std::string json;
  std::string plot;
};

std::vector<int> parse_bench_orders(const std::string& text) {
  std::vector<int> orders;
  std::stringstream s(text);
  std::string item;
  while (std::getline(s, item, ',')) {
    try {
      size_t used = 0;
      const int n = std::stoi(item, &used);
      if (used != item.size()) throw std::invalid_argument(item);
      if (n < 2 || n > 16) throw UsageError("--orders: " + item + " is outside [2, 16]");
      orders.push_back(n);
    } catch (const std::logic_error&) {
      throw UsageError("--orders: expected a list like 3,5,8, found \"" + text + "\"");
    }
  }
  if (orders.empty()) throw UsageError("--orders: no orders in \"" + text + "\"");
  return orders;
}

int run_bench(const BenchOptions& o) {
  bench::SuiteOptions options;
  options.quick = o.quick;
  if (!o.orders.empty()) options.orders = parse_bench_orders(o.orders);
  options.source_dir = std::filesystem::path(project_path("generated")).parent_path().string();
  if (options.source_dir.empty()) options.source_dir = ".";
  options.progress = [](const std::string& line) { std::fprintf(stderr, "  %s\n", line.c_str()); };
  std::fprintf(stderr, "zhf bench%s: measuring (one line per method, order and scenario)\n", o.quick ? " --quick" : "");
  const bench::SuiteReport report = bench::run_suite(options);
  std::printf("CPU: %s\ncompiler: %s\nflags: %s\ndate: %s\n\n%s", report.cpu.c_str(), report.compiler.c_str(),
              report.flags.c_str(), report.date.c_str(), report.table().c_str());
  std::printf("\nscaling (single vector, ns ~ N^k over orders >= 3):");
  for (const char* method : {"zhf", "zhf_runtime", "zxzxz", "ivanic_ruedenberg", "healpix"}) {
    const double k = bench::scaling_exponent(report, method, "single", method == std::string("healpix") ? "incl. real<->complex" : "");
    if (k == k) std::printf(" %s %.2f;", method, k);
  }
  std::printf("\n");
  if (!o.json.empty()) {
    io::write_file_atomically(o.json, io::json_text(report.to_json()));
    std::printf("wrote %s\n", o.json.c_str());
  }
  if (!o.plot.empty()) std::printf("%s\n", bench::write_plots(report, o.plot).c_str());
  return kExitOk;
}

}  // namespace

void add_bench_command(CLI::App& app, Action& action) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* c = app.add_subcommand("bench", "Time and error of every rotation method, per order and scenario");
  c->add_flag("--quick", o->quick, "Small counts and few repeats (CI: checks every method runs and is accurate)");
  c->add_option("--orders", o->orders, "Orders, e.g. 3,5,8 (default 2..8 plus 10, 12, 16)");
  c->add_option("--json", o->json, "Write every measurement as JSON here");
  c->add_option("--plot", o->plot, "Write the Pareto plot here (SVG; also FILE_scaling.svg, .csv and .gp)");
  c->callback([o, &action] { action = [o] { return run_bench(*o); }; });
}

}  // namespace zhf::cli
