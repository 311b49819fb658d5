#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "test_support.h"

namespace zhf::test {
namespace {


TEST(CliCandidates, PrintsSummaryAndWritesJson) {
  const test::TempDir temp;
  const std::string dir = temp.string();
  const RunResult r = run_zhf("candidates --order 4 --json " + dir + "/c.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("order 4: 9 theta values, 16 phi values, 114 candidate directions"), std::string::npos) << r.out;
  const nlohmann::json j = read_json(dir + "/c.json");
  EXPECT_EQ(j.at("format"), "zhf-candidates-1");
  EXPECT_EQ(j.at("directions").size(), 114u);
}

TEST(CliCandidates, RejectsOrderOutOfRangeWithOneLine) {
  for (const char* bad : {"2", "65", "x", "-3"}) {
    const RunResult r = run_zhf(std::string("candidates --order ") + bad);
    EXPECT_EQ(r.exit_code, 2) << bad;
    EXPECT_EQ(line_count(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("--order"), std::string::npos) << r.err;
  }
}

TEST(CliCandidates, UnwritablePathLeavesNothing) {
  const test::TempDir temp;
  const std::string dir = temp.string();
  const RunResult r = run_zhf("candidates --order 3 --json " + dir + "/missing/c.json");
  EXPECT_EQ(r.exit_code, 4);
  EXPECT_EQ(line_count(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(dir + "/missing/c.json"), std::string::npos) << r.err;
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

}  // namespace
}  // namespace zhf::test

namespace zhf::test {
namespace {

// Each checked-in table records the command that made it; running that command again (from a
// directory laid out like the repository) must give the same bytes.
TEST(CliOptimize, RecordedCommandsReproduceTheTablesByteForByte) {
  namespace fs = std::filesystem;
  for (int order : {3, 4}) {
    const fs::path table = test::checked_in_table(order);
    const nlohmann::json checked_in = read_json(table.string());
    std::string command = checked_in.at("provenance").at("command");
    ASSERT_EQ(command.rfind("zhf ", 0), 0u) << command;
    const test::TempDir temp;
  const std::string dir = temp.string();
    fs::create_directories(fs::path(dir) / "generated/lobes");
    std::vector<std::string> args = split_arguments(command.substr(4));
    args.push_back("--quiet");
    const RunResult r = run_zhf(args, dir);
    ASSERT_EQ(r.exit_code, 0) << command << ": " << r.err;
    EXPECT_EQ(read_text((fs::path(dir) / "generated/lobes" / table.filename()).string()), read_text(table.string()))
        << "order " << order << ": `" << command << "` made different bytes";
  }
}

TEST(CliOptimize, WithoutSharingEachBandHasItsOwnLobes) {
  const test::TempDir temp;
  const std::string dir = temp.string();
  const RunResult r = run_zhf("optimize --order 4 --no-sharing --quiet --stall 5 --local-search-stall 2 --out " + dir + "/t.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json t = read_json(dir + "/t.json");
  EXPECT_FALSE(t.at("lobe_sharing").get<bool>());
  EXPECT_EQ(t.at("lobes").size(), 12u);  // 5 + 7
  EXPECT_EQ(t.at("bands")[1].at("lobes")[0], 5);
}

// The operations objective through the CLI: the same table byte for byte on one and two threads,
// recorded as such, and a cheaper lobe rotation (the summary's count) than the sparsity
// objective's.
TEST(CliOptimize, OperationsObjectiveIsDeterministicAndCheaper) {
  namespace fs = std::filesystem;
  const test::TempDir temp;
  const std::string dir = temp.string();
  auto run = [&](const std::string& objective, int threads) {
    // Each run in a folder of its own, writing t.json there: the recorded command is the same.
    const fs::path folder = fs::path(dir) / (objective + std::to_string(threads));
    fs::create_directories(folder);
    const RunResult r = run_zhf(split_arguments("optimize --order 4 --quiet --stall 20 --local-search-stall 20 --objective " +
                                                objective + " --threads " + std::to_string(threads) + " --out t.json"),
                                folder.string());
    const std::string out = (folder / "t.json").string();
    EXPECT_EQ(r.exit_code, 0) << r.err;
    std::smatch m;
    EXPECT_TRUE(std::regex_search(r.out, m, std::regex("rotate_order4 by lobes [^:]*: ([0-9]+) multiplies"))) << r.out;
    return std::make_pair(out, m.size() > 1 ? std::stoi(m[1]) : -1);
  };
  const auto [one, cheap] = run("operations", 1);
  const auto [two, cheap_again] = run("operations", 2);
  const auto [sparse_table, sparse] = run("sparsity", 1);
  EXPECT_EQ(read_text(one), read_text(two)) << "the thread count changed the table";
  EXPECT_EQ(read_json(one).at("provenance").at("objective"), "operations");
  EXPECT_EQ(cheap, cheap_again);
  EXPECT_LT(cheap, sparse) << "operations " << cheap << " multiplies, sparsity " << sparse;
}

}  // namespace
}  // namespace zhf::test
