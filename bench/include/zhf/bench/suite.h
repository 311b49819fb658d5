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

// The variant of the float kernels with the lobe stage in float whatever the error model says: a
// knob that trades accuracy (the float error model instead of 1e-6), so never a row's winner.
inline constexpr const char* kAllFloatVariant = "all float";

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
// A report zhf bench --out wrote (zhf-bench-1, at most runtime::kMaxTableBytes), to redraw its
// plots without measuring again. Throws InputError naming the file and the field.
SuiteReport read_report(const std::string& path);

}  // namespace zhf::bench
