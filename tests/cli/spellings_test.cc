// One spelling per concept (docs/usage.md, "Options"): --out is the file a command writes, --order N
// a band limit of bands 0..N-1, --count a number of things. Every earlier spelling still works and
// writes the same bytes; giving both spellings of one option is a usage error that names them.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "test_support.h"

namespace zhf {
namespace {

namespace fs = std::filesystem;

struct Renamed {
  std::string what;
  std::vector<std::string> args;    // the command, with {OUT} where the output file goes
  std::string old_option, old_value;  // the earlier spelling and its value
  std::string new_option, new_value;
  bool same_bytes = true;            // false where the output holds timings
};

std::vector<std::string> with(const std::vector<std::string>& args, const std::string& out) {
  std::vector<std::string> filled;
  for (const std::string& a : args) filled.push_back(a == "{OUT}" ? out : a);
  return filled;
}

TEST(Spellings, OldAndNewSpellingsDoTheSame) {
  const test::TempDir dir;
  const std::string coeffs = (dir / "f.json").string();
  test::write_text(coeffs, "[[1, 0.5, -0.25, 0.125]]");
  const std::string design = test::source_path("generated/designs/t_4.json");
  const std::vector<Renamed> cases = {
      {"analyze", {"analyze", "--coeffs", coeffs}, "--json", "{OUT}", "--out", "{OUT}"},
      {"candidates", {"candidates", "--order", "3"}, "--json", "{OUT}", "--out", "{OUT}"},
      {"designs output", {"designs", "--t", "3", "--quiet"}, "--json", "{OUT}", "--out", "{OUT}"},
      {"designs count", {"designs", "--t", "3", "--quiet", "--out", "{OUT}"}, "--points", "6", "--count", "6"},
      {"frame", {"frame", "--points", design, "--bands", "0..2"}, "--json", "{OUT}", "--out", "{OUT}"},
      {"verify", {"verify", "--orders", "2", "--langs", "cpp", "--rotations", "3", "--quiet"}, "--json", "{OUT}", "--out", "{OUT}"},
      {"needlets window output", {"needlets", "window", "--order", "9"}, "--json", "{OUT}", "--out", "{OUT}"},
      {"needlets window bands", {"needlets", "window", "--out", "{OUT}"}, "--lmax", "8", "--order", "9"},
      {"needlets tables", {"needlets", "tables", "--order", "4", "--sizes", "16", "--gauss"}, "--json", "{OUT}", "--out", "{OUT}",
       false},
      {"needlets tables bands", {"needlets", "tables", "--sizes", "16", "--gauss", "--out", "{OUT}"}, "--lmax", "3", "--order", "4",
       false},
      // The emitted banner records the command line, which differs.
      {"needlets emit bands", {"needlets", "emit", "--lang", "glsl", "--size", "16", "--gauss", "--out", "{OUT}"}, "--lmax", "3",
       "--order", "4", false},
      {"needlets profile", {"needlets", "profile", "--j", "1"}, "--csv", "{OUT}", "--out", "{OUT}"},
      {"bench", {"bench", "--quick", "--orders", "2", "--quiet"}, "--json", "{OUT}", "--out", "{OUT}", false},
  };
  for (const Renamed& c : cases) {
    const std::string old_out = (dir / (c.what + ".old")).string(), new_out = (dir / (c.what + ".new")).string();
    std::vector<std::string> old_args = with(c.args, old_out), new_args = with(c.args, new_out);
    old_args.insert(old_args.end(), {c.old_option, c.old_value == "{OUT}" ? old_out : c.old_value});
    new_args.insert(new_args.end(), {c.new_option, c.new_value == "{OUT}" ? new_out : c.new_value});
    const test::RunResult a = test::run_zhf(old_args), b = test::run_zhf(new_args);
    ASSERT_EQ(a.exit_code, 0) << c.what << " with " << c.old_option << ": " << a.err;
    ASSERT_EQ(b.exit_code, 0) << c.what << " with " << c.new_option << ": " << b.err;
    ASSERT_TRUE(fs::exists(old_out) && fs::exists(new_out)) << c.what;
    if (c.same_bytes) {
      EXPECT_EQ(test::read_text(old_out), test::read_text(new_out)) << c.what;
    } else {
      EXPECT_GT(fs::file_size(old_out), 0u) << c.what;
      EXPECT_GT(fs::file_size(new_out), 0u) << c.what;
    }
    // Both spellings at once: refused, naming the old one, nothing written.
    std::vector<std::string> both = new_args;
    both.insert(both.end(), {c.old_option, c.old_value == "{OUT}" ? new_out + ".both" : c.old_value});
    const test::RunResult r = test::run_zhf(both);
    EXPECT_EQ(r.exit_code, 2) << c.what << ": " << r.err;
    EXPECT_NE(r.err.find(c.old_option), std::string::npos) << c.what << ": " << r.err;
    EXPECT_NE(r.err.find("give one of them"), std::string::npos) << c.what << ": " << r.err;
    EXPECT_FALSE(fs::exists(new_out + ".both")) << c.what;
  }
}

// Usage errors point at the help of the command that was given.
TEST(Spellings, UsageErrorsNameTheCommandsHelp) {
  test::RunResult r = test::run_zhf("rotate --no-such-option 1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("(see zhf rotate --help)"), std::string::npos) << r.err;
  r = test::run_zhf("needlets tables --no-such-option 1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("(see zhf needlets tables --help)"), std::string::npos) << r.err;
  r = test::run_zhf("needlets tables --order 65");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--order: must be 2..64"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace zhf
