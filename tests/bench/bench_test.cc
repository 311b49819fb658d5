// zhf bench --quick, as CI runs it: every method ran at every order it covers, and every
// error, random inputs and the worst unit input, is within the method's named tolerance. No
// timing is asserted.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include <gtest/gtest.h>

#include "test_support.h"
#include "test_tolerances.h"
#include "zhf/codegen/kernels.h"
#include "zhf/runtime/table_io.h"
#include "zhf/tolerances/tolerances.h"

namespace zhf {
namespace {

namespace fs = std::filesystem;

using namespace zhf::tolerance;

// The float tolerance of a lobe method: the runtime table path runs its lobe stage in double;
// the generated kernels where `auto` put it.
double lobe_float_tolerance(int order, const fs::path& table_path, bool runtime_path) {
  if (order < 3) return kFloatRotation;
  const runtime::LobeTable table = runtime::read_lobe_table(table_path.string());
  return float_rotation(order, table.worst_condition(),
                        runtime_path || codegen::automatic_lobe_stage(table) == runtime::LobeStage::kDouble);
}

TEST(Bench, QuickRunMeasuresEveryMethodWithinItsTolerance) {
  const test::TempDir dir;
  const std::string json = (dir / "bench.json").string();
  const test::RunResult r = test::run_zhf("bench --quick --quiet --out '" + json + "' --plot '" + (dir / "bench.svg").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json report = test::read_json(json);
  const fs::path root(test::source_path(""));
  std::map<std::pair<std::string, std::string>, std::set<int>> ran;
  for (const auto& row : report["rows"]) {
    const std::string method = row["method"], scenario = row["scenario"], precision = row["precision"];
    const std::string variant = row["variant"];
    const int order = row["order"];
    const std::string where = method + " " + scenario + " " + precision + " [" + variant + "] order " + std::to_string(order);
    EXPECT_GT(row["ns_median"].get<double>(), 0.0) << where;
    ran[{method, scenario}].insert(order);
    if (variant.rfind("pruned", 0) == 0 || variant == "conversion only") continue;  // knobs that trade accuracy away
    const double error = row["max_error"];
    double tolerance = kDouble;
    if (precision == "float") {
      if (method == "zxzxz") {
        tolerance = zxzxz_float(order);
      } else {
        fs::path table = runtime::table_path((root / "generated" / "lobes").string(), order);
        if (variant == "table cond<=50") table = root / "bench" / "tables" / "order_6_cond50.json";
        if (variant == "no sharing") table = root / "bench" / "tables" / ("order_" + std::to_string(order) + "_no_sharing.json");
        if (method == "zhf_lanes") {
          // The lanes tables; the all-float knob is held to its model, the default to the target.
          const runtime::LobeTable lanes =
              runtime::read_lobe_table(runtime::table_path((root / "generated" / "lobes").string(), order, runtime::TableKind::kLanes));
          tolerance = variant == "all float" ? std::max(kFloatRotation, kLanesFloatMargin * codegen::lanes_float_error_model(lanes))
                                             : kFloatRotation;
        } else if (method == "tight_frame") {  // condition 1 at every order: the plain float target
          tolerance = kFloatRotation;
        } else if (scenario == "product" || scenario == "square") {
          tolerance = kFloatProduct;
        } else if (scenario == "shade") {  // a rotation dotted with a unit vector: float_shading's model
          tolerance = order * lobe_float_tolerance(order, table, false);
        } else {
          tolerance = lobe_float_tolerance(order, table, method == "zhf_runtime");
        }
      }
    }
    EXPECT_LE(error, tolerance) << where;
    if (scenario == "single") {
      ASSERT_TRUE(row.contains("worst_unit_error")) << where;
      const double worst = row["worst_unit_error"];
      EXPECT_LE(worst, precision == "float" ? kWorstUnitInputFactor * tolerance : kDouble) << where << ", worst unit input";
    }
  }
  const std::set<int> generated = {2, 3, 4, 5, 6, 7, 8};
  const std::set<int> all = {2, 3, 4, 5, 6, 7, 8, 10, 12, 16};
  const std::set<int> tables = {3, 4, 5, 6, 7, 8, 10, 12, 16};
  EXPECT_EQ((ran[{"zhf", "single"}]), generated);
  EXPECT_EQ((ran[{"zhf_signal_tailored", "single"}]), generated);
  EXPECT_EQ((ran[{"zhf", "rgb"}]), generated);
  for (const char* scenario : {"product", "square"}) {
    EXPECT_EQ((ran[{"zhf", scenario}]), generated) << scenario;
    EXPECT_EQ((ran[{"gaunt_sparse", scenario}]), generated) << scenario;
  }
  EXPECT_EQ((ran[{"zhf_shade", "shade"}]), generated);
  EXPECT_EQ((ran[{"zhf_rotate_then_dot", "shade"}]), generated);
  EXPECT_EQ((ran[{"zhf_shade_lobes", "shade"}]), (std::set<int>{3, 4, 5, 6, 7, 8}));
  EXPECT_EQ((ran[{"zhf", "batch"}]), generated);
  EXPECT_EQ((ran[{"zhf_lanes", "single"}]), (std::set<int>{3, 4, 5, 6, 7, 8}));
  EXPECT_EQ((ran[{"zhf_batch_soa", "batch"}]), generated);
  EXPECT_EQ((ran[{"dense_apply", "shared"}]), generated);
  EXPECT_EQ((ran[{"zhf_runtime", "single"}]), tables);
  EXPECT_EQ((ran[{"zxzxz", "single"}]), all);
  EXPECT_EQ((ran[{"zxzxz", "batch"}]), generated);
  EXPECT_EQ((ran[{"ivanic_ruedenberg", "single"}]), all);
  EXPECT_EQ((ran[{"tight_frame", "single"}]), all);
  if (report["notes"].empty()) {  // else HealpixRowsWhenBuiltWithIt skips
    EXPECT_EQ((ran[{"healpix", "single"}]), all);
  }
  // The script a user reruns by hand writes the final SVGs, not zhf's temporary ones.
  const std::string script = test::read_text((dir / "bench.gp").string());
  for (const char* svg : {"bench.svg", "bench_scenarios.svg", "bench_scaling.svg"}) {
    EXPECT_NE(script.find("'" + (dir / svg).string() + "'"), std::string::npos) << svg << "\n" << script;
    EXPECT_GT(fs::file_size(dir / svg), 0u) << svg;
  }
  // Every row of the plotted CSV has its numeric columns first (order, ns, error), each a number,
  // whatever the series' name holds; every column the script plots as a coordinate is one of them.
  std::istringstream csv(test::read_text((dir / "bench.csv").string()));
  std::string line;
  int rows = 0;
  while (std::getline(csv, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> fields;
    std::stringstream split(line);
    for (std::string f; std::getline(split, f, ',');) fields.push_back(f);
    ASSERT_EQ(fields.size(), 4u) << "a series name split its row: " << line;
    for (int k = 0; k < 3; ++k) {
      char* end = nullptr;
      const double x = std::strtod(fields[k].c_str(), &end);
      EXPECT_TRUE(end == fields[k].c_str() + fields[k].size() && std::isfinite(x) && x > 0) << "column " << k + 1 << ": " << line;
    }
    ++rows;
  }
  EXPECT_GT(rows, 50);
  const std::regex using_columns("using ([0-9]+):([0-9]+)(:([0-9]+))?( with (labels|linespoints|points))?");
  int plotted = 0;
  for (auto it = std::sregex_iterator(script.begin(), script.end(), using_columns); it != std::sregex_iterator(); ++it, ++plotted) {
    const std::smatch& m = *it;
    EXPECT_LE(std::stoi(m[1]), 3) << m[0];
    EXPECT_LE(std::stoi(m[2]), 3) << m[0];
    if (m[3].matched) {
      EXPECT_EQ(m[6].str(), "labels") << "a third column is only a label: " << m[0];
    }
  }
  EXPECT_GT(plotted, 10);
  // The saved report redraws the same plots without measuring.
  const test::RunResult again = test::run_zhf("bench --from '" + json + "' --plot '" + (dir / "again.svg").string() + "'");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(test::read_text((dir / "again.csv").string()), test::read_text((dir / "bench.csv").string()));
  for (const auto& entry : fs::directory_iterator(dir))
    EXPECT_EQ(entry.path().string().find(".tmp."), std::string::npos) << "left behind: " << entry.path();
}

// HEALPix's rows need the library at build time (scripts/setup.sh installs it); without it the
// bench says so in its notes, and this test is skipped rather than passed.
TEST(Bench, HealpixRowsWhenBuiltWithIt) {
  const test::TempDir dir;
  const std::string json = (dir / "bench.json").string();
  const test::RunResult r = test::run_zhf("bench --quick --quiet --orders 2 --out '" + json + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json report = test::read_json(json);
  if (!report["notes"].empty()) GTEST_SKIP() << report["notes"][0];
  bool healpix = false;
  for (const auto& row : report["rows"]) healpix = healpix || row["method"] == "healpix";
  EXPECT_TRUE(healpix);
}

}  // namespace
}  // namespace zhf
