// Bad input to every subcommand through the real binary: one line on stderr naming the file,
// field or option, the documented exit code, and nothing written or replaced.
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include <gtest/gtest.h>

#include "test_support.h"

namespace zhf::test {
namespace {

namespace fs = std::filesystem;
const fs::path kTable3 = source_path("generated/lobes/order_3.json");

void expect_one_line(const RunResult& r, int code, const std::string& needle, const std::string& what) {
  EXPECT_EQ(r.exit_code, code) << what << ": " << r.err;
  EXPECT_EQ(line_count(r.err), 1) << what << ": " << r.err;
  EXPECT_NE(r.err.find(needle), std::string::npos) << what << ": expected \"" << needle << "\" in " << r.err;
}

class BadInput : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = make_temp_dir(); }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (fs::path(dir_) / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    write_text(path(name), text);
    return path(name);
  }
  // A valid table with one change applied.
  std::string table_with(const std::string& name, void (*change)(nlohmann::json&)) const {
    nlohmann::json j = read_json(kTable3.string());
    change(j);
    return write(name, j.dump());
  }
  std::string dir_;
};

TEST_F(BadInput, OptionsOutOfRangeOrNotNumbers) {
  expect_one_line(run_zhf("optimize --order 2"), 2, "--order", "order 2");
  expect_one_line(run_zhf("optimize --order 33"), 2, "--order", "order 33");
  expect_one_line(run_zhf("optimize --order eight"), 2, "--order", "order eight");
  expect_one_line(run_zhf("optimize --order 4 --max-condition 0"), 2, "--max-condition", "max condition 0");
  expect_one_line(run_zhf("optimize --order 4 --population 1"), 2, "--population", "population 1");
  expect_one_line(run_zhf("optimize --order 4 --threads -1"), 2, "--threads", "threads -1");
  expect_one_line(run_zhf("optimize --order 4 --objective amplification --starts 0"), 2, "--starts", "starts 0");
  expect_one_line(run_zhf("optimize --order 4 --starts 4 --out " + path("t.json")), 2, "--starts: only --objective amplification",
                  "starts with the sparsity objective");
  expect_one_line(run_zhf("optimize --order 4 --objective amplification --no-sharing --out " + path("t.json")), 2,
                  "--objective amplification", "amplification without sharing");
  expect_one_line(run_zhf("emit --table " + kTable3.string() + " --lang metal --out " + dir_), 2, "--lang", "lang");
  expect_one_line(run_zhf("emit --table " + kTable3.string() + " --lang cpp --channels 2 --out " + dir_), 2, "--channels", "channels");
  expect_one_line(run_zhf("emit --table " + kTable3.string() + " --lang wgsl --precision double --out " + dir_), 2,
                  "--precision: double, but wgsl has no double type", "wgsl double");
  expect_one_line(run_zhf("emit --table " + kTable3.string() + " --lang cpp --convention y-down --out " + dir_), 2,
                  "--convention: 'y-down' is not one of", "convention");
  expect_one_line(run_zhf("verify --langs cpp,cuda"), 2, "--langs", "langs");
  expect_one_line(run_zhf("verify --orders two"), 2, "--orders", "orders");
  expect_one_line(run_zhf("bench --orders 1"), 2, "--orders: must be 2..16 (got '1')", "bench order 1");
  expect_one_line(run_zhf("bench --orders 3,x"), 2, "--orders: 'x' is not an integer", "bench orders x");
  expect_one_line(run_zhf("analyze --coeffs x.json --tolerance 2"), 2, "--tolerance", "tolerance 2");
  expect_one_line(run_zhf("analyze --coeffs x.json --channels 5"), 2, "--channels", "analyze channels 5");
  expect_one_line(run_zhf("rotate --coeffs x.json --zyz '1 2 3' --channels 0 --out y.json"), 2, "--channels", "rotate channels 0");
  expect_one_line(run_zhf("frobnicate"), 2, "frobnicate", "unknown subcommand");
  EXPECT_TRUE(fs::is_empty(dir_));
}

TEST_F(BadInput, TablesThatAreMissingEmptyTruncatedOrCorrupt) {
  const std::string emit = " --lang cpp --out " + path("out");
  expect_one_line(run_zhf("emit --table " + path("missing.json") + emit), 3, "missing.json: cannot open", "missing");
  expect_one_line(run_zhf("emit --table " + write("empty.json", "") + emit), 3, "empty.json: file is empty", "empty");
  const std::string text = read_text(kTable3.string());
  expect_one_line(run_zhf("emit --table " + write("cut.json", text.substr(0, text.size() / 2)) + emit), 3,
                  "cut.json: not valid JSON", "truncated");
  expect_one_line(run_zhf("emit --table " + write("junk.json", "{\"format\": zhf}") + emit), 3, "junk.json: not valid JSON",
                  "corrupt");
  expect_one_line(run_zhf("emit --table " + table_with("v0.json", [](nlohmann::json& j) { j["format"] = "zhf-lobes-0"; }) + emit),
                  3, "v0.json: format", "format version");
  expect_one_line(run_zhf("emit --table " + table_with("count.json", [](nlohmann::json& j) { j["lobes"].erase(4); }) + emit), 3,
                  "count.json: lobes: expected 5 entries, found 4", "lobe count");
  expect_one_line(run_zhf("emit --table " + table_with("xyz.json", [](nlohmann::json& j) { j["lobes"][1]["phi"] = 0.5; }) + emit),
                  3, "xyz.json: lobes[1].xyz: disagrees with theta/phi", "theta/phi vs xyz");
  expect_one_line(run_zhf("emit --table " +
                          table_with("tampered.json", [](nlohmann::json& j) { j["bands"][0]["inverse"][0][0] = 0.75; }) + emit),
                  3, "tampered.json: bands[0]", "tampered inverse");
  EXPECT_FALSE(fs::exists(path("out")));
}

TEST_F(BadInput, OutputsThatAreUserFilesOrUnwritable) {
  // An existing file zhf did not write is never replaced.
  fs::create_directories(path("mine"));
  const std::string mine = write("mine/zhf_order3.h", "// my own header\n");
  expect_one_line(run_zhf("emit --table " + kTable3.string() + " --lang cpp --out " + path("mine")), 4,
                  "was not generated by zhf", "user file");
  EXPECT_EQ(read_text(mine), "// my own header\n");
  // A non-empty directory that is not a zhf tree is refused whole.
  write("mine/notes.txt", "keep\n");
  expect_one_line(run_zhf("generate --out " + path("mine")), 4, "not empty and has no zhf manifest.json", "non-empty dir");
  EXPECT_EQ(read_text(path("mine/notes.txt")), "keep\n");
  // Unwritable: a path under a regular file.
  expect_one_line(run_zhf("optimize --order 3 --quiet --out " + mine + "/t.json"), 4, mine + "/t.json", "unwritable");
  expect_one_line(run_zhf("generate --tables " + path("nowhere")), 3, "nowhere/order_3.json: cannot open", "no tables");
}

TEST_F(BadInput, InterruptedOptimizeKeepsTheOldTableAndSavesTheBestSoFar) {
  const std::string out = write("order_8.json", "previous contents\n");
  io::Process zhf = start_zhf({"optimize", "--order", "8", "--quiet", "--out", out});
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  zhf.signal(SIGINT);
  EXPECT_EQ(exit_code_of(zhf), 130);
  EXPECT_EQ(read_text(out), "previous contents\n");
  const nlohmann::json saved = read_json(out + ".interrupted.json");
  EXPECT_EQ(saved.at("order"), 8);
  EXPECT_EQ(saved.at("provenance").at("stopped_by"), "interrupt");
  for (const auto& entry : fs::directory_iterator(dir_))
    EXPECT_EQ(entry.path().string().find(".tmp."), std::string::npos) << "left behind: " << entry.path();
}

}  // namespace
}  // namespace zhf::test
