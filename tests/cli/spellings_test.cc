// One spelling per concept (docs/usage.md, "Options"): --out is the file a command writes, --order N
// a band limit of bands 0..N-1, --count a number of things. Every earlier spelling still works and
// writes the same bytes; giving both spellings of one option is a usage error that names them.
#include <filesystem>
#include <map>
#include <regex>
#include <set>
#include <sstream>
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
      {"frame", {"frame", "--directions", design, "--bands", "0..2"}, "--json", "{OUT}", "--out", "{OUT}"},
      {"frame directions", {"frame", "--bands", "0..2", "--out", "{OUT}"}, "--points", design, "--directions", design},
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
      {"needlets profile", {"needlets", "profile", "--level", "1"}, "--csv", "{OUT}", "--out", "{OUT}"},
      {"needlets profile level", {"needlets", "profile", "--out", "{OUT}"}, "--j", "2", "--level", "2"},
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

// Every command and subcommand ("needlets prt") -> the options its --help lists.
std::map<std::string, std::set<std::string>> options_of_every_command() {
  const std::regex subcommand(R"(^  ([a-z][a-z0-9-]*)\s{2,})"), option(R"(^\s+(?:-\w,)?(--[a-z0-9-]+))");
  std::map<std::string, std::set<std::string>> options;
  std::vector<std::string> pending = {""};
  while (!pending.empty()) {
    const std::string command = pending.back();
    pending.pop_back();
    const test::RunResult r = test::run_zhf(command.empty() ? "--help" : command + " --help");
    EXPECT_EQ(r.exit_code, 0) << "zhf " << command << " --help: " << r.err;
    std::istringstream lines(r.out);
    bool in_subcommands = false;
    for (std::string line; std::getline(lines, line);) {
      if (line.rfind("Subcommands:", 0) == 0 || line.rfind("Options:", 0) == 0) in_subcommands = line[0] == 'S';
      std::smatch m;
      if (in_subcommands && std::regex_search(line, m, subcommand)) {
        pending.push_back(command.empty() ? m[1].str() : command + " " + m[1].str());
      } else if (!command.empty() && !in_subcommands && std::regex_search(line, m, option)) {
        options[command].insert(m[1].str());
      }
    }
  }
  return options;
}

// The cells of the rows of docs/usage.md's table whose header row starts with `first`.
std::vector<std::vector<std::string>> usage_table(const std::string& first) {
  std::istringstream lines(test::read_text(test::source_path("docs/usage.md")));
  std::vector<std::vector<std::string>> rows;
  bool in_table = false;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("| " + first + " |", 0) == 0) {
      in_table = true;
      continue;
    }
    if (!in_table || line.rfind("| ---", 0) == 0) continue;
    if (line.rfind("|", 0) != 0) break;
    std::vector<std::string> cells;
    std::istringstream cell_text(line.substr(1));
    for (std::string cell; std::getline(cell_text, cell, '|');) cells.push_back(cell.substr(1, cell.size() - 2));
    rows.push_back(cells);
  }
  return rows;
}

// "candidates, needlets window" -> {"candidates", "needlets window"}.
std::set<std::string> commands_in(const std::string& cell) {
  std::set<std::string> out;
  std::istringstream items(cell);
  for (std::string item; std::getline(items, item, ',');) out.insert(item.substr(item.find_first_not_of(' ')));
  return out;
}

// The first option a cell spells: "`--out FILE`" -> "--out".
std::string option_in(const std::string& cell) {
  std::smatch m;
  return std::regex_search(cell, m, std::regex("--[a-z0-9-]+")) ? m[0].str() : "";
}

// docs/usage.md's options tables against every command's --help: the commands with --threads,
// --compiler and --level are the ones the table names; each earlier spelling is out of the help of
// the commands it names, which list its current spelling; every option a help lists is written in
// docs/usage.md.
TEST(Spellings, TheOptionsTablesMatchEveryHelp) {
  const std::map<std::string, std::set<std::string>> options = options_of_every_command();
  ASSERT_TRUE(options.count("rotate") && options.count("needlets prt") && options.count("designs")) << options.size() << " commands";
  for (const std::string what : {"threads", "a C++ compiler", "a needlet level"}) {
    const auto rows = usage_table("concept");
    const auto row = std::find_if(rows.begin(), rows.end(), [&](const auto& r) { return r.at(0) == what; });
    ASSERT_NE(row, rows.end()) << "docs/usage.md: no row for " << what;
    const std::string name = option_in(row->at(1));
    std::set<std::string> having;
    for (const auto& [command, listed] : options)
      if (listed.count(name)) having.insert(command);
    EXPECT_EQ(having, commands_in(row->at(2))) << what << " (" << name << "): the commands whose --help lists it";
  }
  const auto renamed = usage_table("earlier spelling");
  ASSERT_GE(renamed.size(), 7u);
  for (const auto& row : renamed) {
    const std::string old_name = option_in(row.at(0)), current = option_in(row.at(1));
    for (const std::string& command : commands_in(row.at(2))) {
      ASSERT_TRUE(options.count(command)) << "docs/usage.md names '" << command << "', which has no --help";
      EXPECT_EQ(options.at(command).count(old_name), 0u) << "zhf " << command << " --help lists the old " << old_name;
      EXPECT_EQ(options.at(command).count(current), 1u) << "zhf " << command << " --help lacks " << current;
    }
  }
  const std::string usage = test::read_text(test::source_path("docs/usage.md"));
  for (const auto& [command, listed] : options)
    for (const std::string& name : listed)
      EXPECT_TRUE(std::regex_search(usage, std::regex(name + "(?![a-z0-9-])")))
          << "zhf " << command << " " << name << " is not in docs/usage.md";
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
