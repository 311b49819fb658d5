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
