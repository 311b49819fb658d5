#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <regex>
#include <sstream>

#include <gtest/gtest.h>

#include "test_support.h"
#include "zhf/codegen/path_headers.h"
#include "zhf/codegen/generate.h"
#include "zhf/codegen/path_tables.h"
#include "zhf/candidates/candidates.h"
#include "zhf/codegen/kernels.h"
#include "zhf/optimizer/objective.h"
#include "zhf/runtime/table_io.h"
#include "zhf/io/process.h"

namespace zhf::codegen {
namespace {

namespace fs = std::filesystem;
const fs::path kGenerated = test::source_path("generated");

std::string slurp(const fs::path& p) { return test::read_text(p.string()); }

TEST(ExpressionGraph, FoldsConstantsSignsAndSharesSubexpressions) {
  Graph g;
  const int x = g.input(0, 0), y = g.input(0, 1);
  EXPECT_EQ(g.mul(g.constant(1), x), x);
  EXPECT_TRUE(g.is_const(g.mul(g.constant(0), x), 0));
  EXPECT_EQ(g.add(x, g.constant(0)), x);
  EXPECT_EQ(g.add(x, y), g.add(y, x));  // shared, commutative
  EXPECT_EQ(g.neg(g.neg(x)), x);
  EXPECT_EQ(g.add(x, g.neg(y)), g.sub(x, y));
  // -(2 x) folds the sign into the constant: one multiply, no negation.
  const int n = g.neg(g.scale(2, x));
  EXPECT_EQ(g.node(n).op, Op::kMul);
  EXPECT_EQ(g.node(g.node(n).a).value, -2);
  // 3x - 3y + 2x: the two magnitude-3 terms share one multiply.
  const int l = g.linear({{3, x}, {-3, y}, {2, g.input(0, 2)}});
  const OpCount c = g.count({l});
  EXPECT_EQ(c.multiplies, 2);
  EXPECT_EQ(c.adds, 2);
}

// Counts the operators of each emitted function from the text alone: binary operators are
// printed with spaces around them, negations as "-name"; loops and index arithmetic (std::size_t:
// the batch loop's tiles) are not the kernel's.
std::map<std::string, OpCount> count_operators(const std::string& text) {
  std::map<std::string, OpCount> counts;
  const std::regex header(R"(^(?:(?:ZHF_HOST_DEVICE )?(?:inline )?void|fn) (\w+)\()");
  const std::regex subscript(R"(\[[^\]]*\])");
  std::istringstream in(text);
  std::string line, current;
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_search(line, m, header)) {
      current = m[1];
      counts[current];
      continue;
    }
    if (line == "}") current.clear();
    if (current.empty() || line.find(" = ") == std::string::npos || line.find("for (") != std::string::npos ||
        line.find("std::size_t") != std::string::npos)
      continue;
    std::string rhs = std::regex_replace(line.substr(line.find(" = ") + 3), subscript, "");
    OpCount& c = counts[current];
    for (size_t p = rhs.find(" * "); p != std::string::npos; p = rhs.find(" * ", p + 1)) ++c.multiplies;
    for (const char* op : {" + ", " - "})
      for (size_t p = rhs.find(op); p != std::string::npos; p = rhs.find(op, p + 1)) ++c.adds;
    if (rhs.size() > 1 && rhs[0] == '-' && std::isalpha(static_cast<unsigned char>(rhs[1]))) ++c.adds;
  }
  return counts;
}

TEST(GeneratedFiles, BannerCountsEqualTheOperatorsInTheCode) {
  const nlohmann::json manifest = test::read_json((kGenerated / "manifest.json").string());
  int checked = 0;
  for (const auto& file : manifest.at("files")) {
    const std::string path = file.at("path");
    if (file.at("kind") == "lobe-table") continue;
    const std::string text = slurp(kGenerated / path);
    const auto counted = count_operators(text);
    for (const auto& f : file.at("functions")) {
      const std::string name = f.at("name");
      ASSERT_TRUE(counted.count(name)) << path << ": no function " << name;
      EXPECT_EQ(counted.at(name).multiplies, f.at("multiplies").get<int>()) << path << " " << name;
      EXPECT_EQ(counted.at(name).adds, f.at("adds").get<int>()) << path << " " << name;
      // The banner says the same as the manifest.
      EXPECT_NE(text.find("//   " + name + ": " + std::to_string(f.at("multiplies").get<int>()) + " multiplies, " +
                          std::to_string(f.at("adds").get<int>()) + " adds"),
                std::string::npos)
          << path << " " << name;
      ++checked;
    }
    EXPECT_EQ(file.at("fnv1a64"), content_hash(text)) << path;
  }
  EXPECT_GT(checked, 100);
}

// Band 2 by its quadratic form: 45 multiplies (zxzxz 56, lobes 70).
TEST(GeneratedFiles, Order3RotationNeedsAtMost57Multiplies) {
  const nlohmann::json manifest = test::read_json((kGenerated / "manifest.json").string());
  for (const auto& file : manifest.at("files"))
    for (const auto& f : file.value("functions", nlohmann::json::array()))
      if (f.at("name") == "rotate_order3") {
        EXPECT_LE(f.at("multiplies").get<int>(), 57) << file.at("path");
      }
}

// Every language prints the same graph: each function's operation count in a shader file (GLSL,
// HLSL, WGSL) is its count in the C++ file of that order (WGSL prints every node in f32, which
// changes types, not operations).
TEST(GeneratedFiles, EveryLanguageCountsTheSameOperationsAsCpp) {
  const nlohmann::json manifest = test::read_json((kGenerated / "manifest.json").string());
  std::map<std::string, std::pair<int, int>> cpp;
  for (const auto& file : manifest.at("files"))
    if (file.at("kind") == "kernels" && file.at("language") == "cpp")
      for (const auto& f : file.at("functions"))
        cpp[f.at("name").get<std::string>()] = {f.at("multiplies").get<int>(), f.at("adds").get<int>()};
  std::map<std::string, int> checked;
  for (const auto& file : manifest.at("files")) {
    if (file.at("kind") != "kernels" || file.at("language") == "cpp") continue;
    for (const auto& f : file.at("functions")) {
      const std::string name = f.at("name");
      if (f.at("channels").get<int>() > 1) continue;  // shaders count a float3 operation once
      ASSERT_TRUE(cpp.count(name)) << file.at("path") << ": " << name << " has no C++ counterpart";
      EXPECT_EQ(f.at("multiplies").get<int>(), cpp.at(name).first) << file.at("path") << " " << name;
      EXPECT_EQ(f.at("adds").get<int>(), cpp.at(name).second) << file.at("path") << " " << name;
      ++checked[file.at("language").get<std::string>()];
    }
  }
  for (const char* language : {"glsl", "hlsl", "wgsl"}) EXPECT_GT(checked[language], 40) << language;
}

// The product kernels against Snyder 2006's greedy pair factoring (multiplies, orders 3..7), and
// the one-function shading kernels against the two-step rotate-then-dot.
TEST(GeneratedFiles, ProductKernelsNeedFewerMultipliesThanSnyderAndShadingNoMoreThanTwoSteps) {
  const std::map<int, int> snyder = {{3, 120}, {4, 399}, {5, 1135}, {6, 2527}, {7, 5351}};
  const nlohmann::json manifest = test::read_json((kGenerated / "manifest.json").string());
  std::map<std::string, int> multiplies;
  for (const auto& file : manifest.at("files"))
    for (const auto& f : file.value("functions", nlohmann::json::array()))
      if (file.at("language") == "cpp") multiplies[f.at("name").get<std::string>()] = f.at("multiplies").get<int>();
  for (const auto& [order, count] : snyder)
    EXPECT_LT(multiplies.at("product_order" + std::to_string(order)), count) << "order " << order;
  for (int order = 2; order <= 8; ++order) {
    const std::string n = std::to_string(order);
    EXPECT_LE(multiplies.at("square_order" + n), multiplies.at("product_order" + n)) << "order " << order;
    EXPECT_LE(multiplies.at("shade_order" + n), multiplies.at("rotate_order" + n) + order * order) << "order " << order;
  }
}

// From lobe weights, shading skips the sparse stage: never dearer than shading every band by lobes.
TEST(Kernels, ShadingFromLobeWeightsCostsNoMoreThanByLobes) {
  for (int order = 3; order <= 8; ++order) {
    ModuleOptions options;
    options.band_method = BandMethod::kLobes;
    const Module module = build_module(runtime::read_lobe_table(runtime::table_path(kGenerated / "lobes", order)), options);
    std::map<KernelKind, int> multiplies;
    for (const Function& f : module.functions) multiplies[f.kind] = f.graph.count(f.output_nodes()).multiplies;
    EXPECT_LE(multiplies.at(KernelKind::kShadeLobes), multiplies.at(KernelKind::kShade)) << "order " << order;
  }
}

// The search's count of a band's lobe weights is what the emitted lobe_weights kernel costs, band
// by band summed, and never more than the optimizer's model (equal magnitudes per column).
TEST(Kernels, LobeWeightCountIsTheEmittedOneAndWithinTheModel) {
  for (int order = 3; order <= 8; ++order) {
    const runtime::LobeTable table = runtime::read_lobe_table(runtime::table_path(kGenerated / "lobes", order));
    int counted = 0;
    for (const runtime::TableBand& band : table.bands) {
      const int multiplies = lobe_weight_multiplies(band.inverse);
      Eigen::MatrixXd inverse(band.inverse.rows, band.inverse.cols);
      for (int i = 0; i < band.inverse.rows; ++i)
        for (int j = 0; j < band.inverse.cols; ++j) inverse(i, j) = band.inverse(i, j);
      EXPECT_LE(multiplies, optimizer::multiply_cost(inverse)) << "order " << order << ", band " << band.l;
      EXPECT_GT(multiplies, 0) << "order " << order << ", band " << band.l;
      counted += multiplies;
    }
    const Module module = build_module(table, ModuleOptions());
    for (const Function& f : module.functions) {
      if (f.kind != KernelKind::kLobeWeights) continue;
      EXPECT_EQ(counted, f.graph.count(f.output_nodes()).multiplies) << "order " << order;
    }
  }
}

// The operations objective's count is the whole lobe rotation less a part that is the same for
// every lobe set of an order and lobe sharing, so ranking by it ranks by the kernel. Checked on
// the checked-in tables and on random invertible sets of candidates (generic, axis-aligned and
// repeated coordinates, without sharing repeated directions; conditions that put the lobe stage
// in float and in double).
TEST(Kernels, LobeDependentCountIsTheKernelsLessAConstant) {
  std::mt19937_64 rng(5);
  for (int order = 3; order <= 7; ++order)
    for (bool sharing : {true, false}) {
      SCOPED_TRACE("order " + std::to_string(order) + (sharing ? ", lobe sharing" : ", no sharing"));
      const candidates::CandidateSet set = candidates::enumerate_candidates(order);
      const optimizer::LobeEvaluator evaluator(set, sharing, optimizer::kDefaultMaxCondition);
      std::vector<runtime::LobeTable> tables;
      if (sharing) tables.push_back(runtime::read_lobe_table(runtime::table_path(kGenerated / "lobes", order)));
      for (int tries = 0; tables.size() < 10 && tries < 1000; ++tries) {
        optimizer::Genome genome(evaluator.genes());
        for (int& gene : genome) gene = static_cast<int>(rng() % set.directions.size());
        if (evaluator.evaluate(genome).invertible)
          tables.push_back(optimizer::make_table(evaluator, genome, nlohmann::json::object()));
      }
      ASSERT_EQ(tables.size(), 10u);
      std::set<int> rest, dependent, stages;
      for (const runtime::LobeTable& table : tables) {
        const int part = lobe_dependent_multiplies(table);
        rest.insert(lobe_rotation_multiplies(table) - part);
        dependent.insert(part);
        stages.insert(static_cast<int>(automatic_lobe_stage(table)));
      }
      EXPECT_EQ(rest.size(), 1u) << "the part not counted changed with the lobes";
      EXPECT_GT(dependent.size(), 2u) << "the sets should differ in cost";
      // The float stage needs a condition that, of these, only order 3's sets and order 4's
      // checked-in table reach: there both stages occur.
      if (order == 3 || (order == 4 && sharing)) {
        EXPECT_EQ(stages.size(), 2u) << "both lobe stages should occur";
      }
    }
}

// auto takes the cheapest assignment: never dearer than any method forced.
TEST(Kernels, AutomaticBandMethodsCostNoMoreThanAnyMethodForced) {
  for (int order = 3; order <= 8; ++order) {
    const runtime::LobeTable table = runtime::read_lobe_table(runtime::table_path(kGenerated / "lobes", order));
    auto rotate_ops = [&](std::optional<BandMethod> method) {
      ModuleOptions options;
      options.band_method = method;
      const Module module = build_module(table, options);
      for (const Function& f : module.functions)
        if (f.kind == KernelKind::kRotate && f.channels == 1) {
          const OpCount c = f.graph.count(f.output_nodes());
          return c.multiplies + c.adds + c.others;
        }
      return -1;
    };
    const int automatic = rotate_ops(std::nullopt);
    EXPECT_LE(automatic, rotate_ops(BandMethod::kLobes)) << "order " << order;
    EXPECT_LE(automatic, rotate_ops(BandMethod::kZxzxz)) << "order " << order;
    EXPECT_LE(automatic, rotate_ops(BandMethod::kQuadratic)) << "order " << order;
  }
}

// generated/ is exactly what the generator makes from the checked-in tables. After changing
// the generator, run `zhf generate` from the repository root (or this test with
// ZHF_UPDATE_GENERATED=1) and commit the result.
TEST(GeneratedFiles, MatchWhatTheGeneratorMakes) {
  const bool update = std::getenv("ZHF_UPDATE_GENERATED") != nullptr;
  const test::TempDir temp;
  const fs::path out = update ? kGenerated : fs::path(temp);
  GenerateOptions options;
  options.tables_dir = (kGenerated / "lobes").string();
  options.paths_dir = (kGenerated / "paths").string();
  options.out_dir = out.string();
  const GenerateResult result = generate(options);
  if (update) GTEST_SKIP() << "ZHF_UPDATE_GENERATED set: rewrote " << kGenerated;
  for (const std::string& relative : result.files) {
    const std::string fresh = slurp(out / relative);
    const fs::path checked_in = kGenerated / relative;
    ASSERT_TRUE(fs::exists(checked_in)) << relative << " is generated but not checked in";
    if (fresh != slurp(checked_in)) {
      const std::string log = out.string() + "/diff.log";
      io::run_process({"diff", "-u", checked_in.string(), (out / relative).string()}, log);
      FAIL() << relative << " differs from what the generator makes; run `zhf generate`. The diff begins:\n"
             << slurp(log).substr(0, 3000);
    }
  }
}

// The measured path tables: one naming a path its instruction set, type or order lacks, an order
// that is not generated or twice, naming another instruction set or holding more than JSON is
// refused in one line naming the file and the field; a build without a table of its own follows
// the one below it.
TEST(PathTables, RefusedInOneLineNamingFileAndField) {
  const test::TempDir temp;
  const std::string dir = fs::path(temp).string();
  const std::string file = (fs::path(dir) / "sse2.json").string();
  const std::vector<int> orders = {2, 3};
  const std::string scalar = R"({"fastest": "scalar", "ns": {"scalar": 1.5}})";
  const auto table = [&](const std::string& isa, const std::string& float2, const std::string& rest) {
    return R"({"format": "zhf-paths-1", "isa": ")" + isa + R"(", "measured_on": "a test", "orders": [{"order": 2, "float": )" +
           float2 + R"(, "double": )" + scalar + "}" + rest + "]}";
  };
  const std::string order3 = R"(, {"order": 3, "float": )" + scalar + R"(, "double": )" + scalar + "}";
  test::write_text(file, table("sse2", scalar, order3));
  ASSERT_EQ(read_path_tables(dir).size(), 1u);
  const struct {
    std::string text, field;
  } bad[] = {
      {table("sse2", R"({"fastest": "bands01", "ns": {"bands01": 1}})", order3), "orders[0].float.fastest"},
      {table("sse2", R"({"fastest": "lanes", "ns": {"lanes": 1}})", order3), "orders[0].float.fastest"},
      {table("sse2", R"({"fastest": "scalar", "ns": {"scalar": 1, "band_rows": 0.5}})", order3), "orders[0].float.ns.band_rows"},
      {table("sse2", R"({"fastest": "scalar", "ns": {"lanes_": 1}})", order3), "orders[0].float.ns"},
      {table("sse2", scalar, R"(, {"order": 9, "float": )" + scalar + R"(, "double": )" + scalar + "}"), "orders[1].order"},
      {table("sse2", scalar, R"(, {"order": 2, "float": )" + scalar + R"(, "double": )" + scalar + "}"), "orders[1].order"},
      {table("avx2", scalar, order3), "isa"},
      {table("sse2", scalar, order3) + " x", "sse2.json"},
  };
  for (const auto& b : bad) {
    test::write_text(file, b.text);
    try {
      read_path_tables(dir);
      ADD_FAILURE() << "accepted: " << b.text;
    } catch (const std::exception& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("sse2.json"), std::string::npos) << message;
      EXPECT_NE(message.find(b.field), std::string::npos) << "expected " << b.field << " in: " << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
  }
  // Band rows for float at order 2 (bands 0 and 1) are an avx2 path: an avx512 build follows avx2's table.
  test::write_text(file, table("sse2", scalar, order3));
  test::write_text((fs::path(dir) / "avx2.json").string(),
                   table("avx2", R"({"fastest": "bands01", "ns": {"scalar": 2, "bands01": 1}})", order3));
  const std::string header = emit_paths_header(orders, {}, read_path_tables(dir), "test").text;
  EXPECT_NE(header.find("// avx512: no table of its own; avx2's, generated/paths/avx2.json"), std::string::npos) << header;
  EXPECT_NE(header.find("case 2: return is_float ? Path::kBands01 : Path::kScalar;"), std::string::npos) << header;
  EXPECT_NE(header.find("// neon: no table measured; the scalar kernels."), std::string::npos) << header;
}

// The path tables follow the tree: an order whose measured fastest path is lanes takes the next
// fastest where the tree has no lanes tables (a user's own lobe tables), and an order the table
// does not list runs the scalar kernels.
TEST(PathTables, FollowTheTreesKernels) {
  const test::TempDir temp;
  const std::string dir = fs::path(temp).string();
  const std::string scalar = R"({"fastest": "scalar", "ns": {"scalar": 1.5}})";
  const std::string lanes = R"({"fastest": "lanes", "ns": {"scalar": 3, "lanes": 1}})";
  test::write_text((fs::path(dir) / "sse2.json").string(),
                   R"({"format": "zhf-paths-1", "isa": "sse2", "measured_on": "a test", "orders": [{"order": 2, "float": )" +
                       scalar + R"(, "double": )" + scalar + R"(}, {"order": 3, "float": )" + lanes + R"(, "double": )" + scalar + "}]}");
  const std::vector<PathTable> tables = read_path_tables(dir);
  const std::string with_lanes = emit_paths_header({2, 3, 9}, {3}, tables, "test").text;
  EXPECT_NE(with_lanes.find("case 3: return is_float ? Path::kLanes : Path::kScalar;"), std::string::npos) << with_lanes;
  EXPECT_NE(with_lanes.find("//   order 9: not measured; scalar"), std::string::npos) << with_lanes;
  const std::string without = emit_paths_header({2, 3}, {}, tables, "test").text;
  EXPECT_EQ(without.find("case 3:"), std::string::npos) << without;
  EXPECT_NE(without.find("//   order 3: scalar (scalar 3, lanes 1)"), std::string::npos) << without;
}

// An interrupt before the commit leaves the previous tree exactly as it was.
TEST(Generate, InterruptedRunLeavesThePreviousOutputs) {
  const test::TempDir out;
  GenerateOptions options;
  options.tables_dir = (kGenerated / "lobes").string();
  options.out_dir = out.string();
  options.orders = {2, 3};
  generate(options);
  const std::string before = slurp(out / "cpp/zhf_order3.h");
  test::write_text((out / "cpp/zhf_order3.h").string(), before + "// previous run\n");
  std::atomic<bool> stop{true};
  options.stop = &stop;
  const GenerateResult result = generate(options);
  EXPECT_TRUE(result.interrupted);
  EXPECT_EQ(slurp(out / "cpp/zhf_order3.h"), before + "// previous run\n");
  for (const auto& entry : fs::directory_iterator(out))
    EXPECT_EQ(entry.path().filename().string().find(".zhf-staging"), std::string::npos) << entry.path();
}

}  // namespace
}  // namespace zhf::codegen
