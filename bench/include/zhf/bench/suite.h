// zhf bench: every rotation method of the project side by side in one run, per order and
// scenario, with time per rotated vector, error against the double reference and operation
// counts; a table, JSON and gnuplot plots (the speed/accuracy trade).
#pragma once

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace zhf::bench {

struct SuiteOptions {
  bool quick = false;               // CI: small counts, few repeats; same methods and orders
  std::vector<int> orders;          // empty: 2..8, plus 10, 12, 16 for the general methods
  std::string source_dir;           // holds generated/ and bench/tables/
  std::function<void(const std::string&)> progress;  // one line per measurement
};

struct Row {
  std::string method;     // e.g. zhf, zhf_signal_tailored, zhf_runtime, ivanic_ruedenberg, zxzxz, dense_apply, healpix
  std::string scenario;   // single, rgb, batch, shared
  std::string precision;  // float, double
  std::string variant;    // the knob, e.g. "threads 2", "pruned 1e-3", "table cond<=50", "no sharing"
  int order = 0;
  double ns_median = 0, ns_min = 0, ns_max = 0;  // per rotated vector (all channels), over repeats
  double max_error = 0, rms_error = 0;           // vs the double reference, unit-norm inputs
  double worst_unit_error = NAN;                 // single vector: the worst unit input (NaN: not measured)
  long multiplies = -1, adds = -1;               // straight-line methods only
};

struct SuiteReport {
  std::vector<Row> rows;
  std::string cpu, compiler, flags, date;
  std::vector<std::string> notes;  // methods not run and why
  nlohmann::ordered_json to_json() const;
  std::string table() const;
};

SuiteReport run_suite(const SuiteOptions& options);

// Least-squares slope of log(ns) against log(N) for one method and scenario (orders >= 3).
double scaling_exponent(const SuiteReport& report, const std::string& method, const std::string& scenario,
                        const std::string& variant = "");

// Refuses (OutputError) a --plot path write_plots could not use: control characters in it, or a
// file beside it (FILE.csv, FILE.gp, FILE_scaling.svg) that zhf bench did not write. Call it
// before measuring.
void check_plot_targets(const std::string& svg_path);

// Writes path (Pareto: max error against time, one series per method, log-log) and
// path-with-"_scaling" (time against N), with their .csv and .gp beside them; runs gnuplot
// when installed. Returns what it wrote, or why it could not draw.
std::string write_plots(const SuiteReport& report, const std::string& svg_path);

}  // namespace zhf::bench
