#include <algorithm>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "cli_runner.h"
#include "zhf/io/files.h"

namespace zhf::test {
namespace {

int line_count(const std::string& s) { return static_cast<int>(std::count(s.begin(), s.end(), '\n')); }

TEST(CliCandidates, PrintsSummaryAndWritesJson) {
  const std::string dir = make_temp_dir();
  const RunResult r = run_zhf("candidates --order 4 --json " + dir + "/c.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("order 4: 9 theta values, 16 phi values, 114 candidate directions"), std::string::npos) << r.out;
  const nlohmann::json j = io::read_json_file(dir + "/c.json");
  EXPECT_EQ(j.at("format"), "zhf-candidates-1");
  EXPECT_EQ(j.at("directions").size(), 114u);
  std::filesystem::remove_all(dir);
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
  const std::string dir = make_temp_dir();
  const RunResult r = run_zhf("candidates --order 3 --json " + dir + "/missing/c.json");
  EXPECT_EQ(r.exit_code, 4);
  EXPECT_EQ(line_count(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(dir + "/missing/c.json"), std::string::npos) << r.err;
  EXPECT_TRUE(std::filesystem::is_empty(dir));
  std::filesystem::remove_all(dir);
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
    const fs::path table = fs::path(ZHF_SOURCE_DIR) / "generated/lobes" / ("order_" + std::to_string(order) + ".json");
    const nlohmann::json checked_in = io::read_json_file(table.string());
    std::string command = checked_in.at("provenance").at("command");
    ASSERT_EQ(command.rfind("zhf ", 0), 0u) << command;
    const std::string dir = make_temp_dir();
    fs::create_directories(fs::path(dir) / "generated/lobes");
    const RunResult r = run_zhf("--version >/dev/null && cd '" + dir + "' && " + ZHF_BINARY + command.substr(3) + " --quiet");
    ASSERT_EQ(r.exit_code, 0) << command << ": " << r.err;
    EXPECT_EQ(io::read_text_file((fs::path(dir) / "generated/lobes" / table.filename()).string()),
              io::read_text_file(table.string()))
        << "order " << order << ": `" << command << "` made different bytes";
    fs::remove_all(dir);
  }
}

TEST(CliOptimize, WithoutSharingEachBandHasItsOwnLobes) {
  const std::string dir = make_temp_dir();
  const RunResult r = run_zhf("optimize --order 4 --no-sharing --quiet --stall 5 --local-search-stall 2 --out " + dir + "/t.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json t = io::read_json_file(dir + "/t.json");
  EXPECT_FALSE(t.at("lobe_sharing").get<bool>());
  EXPECT_EQ(t.at("lobes").size(), 12u);  // 5 + 7
  EXPECT_EQ(t.at("bands")[1].at("lobes")[0], 5);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace zhf::test
