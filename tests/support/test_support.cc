#include "test_support.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "zhf/io/private_dir.h"
#include "zhf/io/process.h"
#include "zhf/runtime/table_io.h"

namespace zhf::test {

std::vector<std::string> split_arguments(const std::string& args) {
  std::vector<std::string> out;
  std::string current;
  bool in_word = false;
  char quote = 0;
  for (char c : args) {
    if (quote) {
      if (c == quote) {
        quote = 0;
      } else {
        current += c;
      }
    } else if (c == '\'' || c == '"') {
      quote = c;
      in_word = true;
    } else if (c == ' ') {
      if (in_word) out.push_back(current);
      current.clear();
      in_word = false;
    } else {
      current += c;
      in_word = true;
    }
  }
  if (in_word) out.push_back(current);
  return out;
}

RunResult run_zhf(const std::string& args) { return run_zhf(split_arguments(args)); }

std::string zhf_binary() {
  const char* other = std::getenv("ZHF_TEST_BINARY");
  return other && *other ? other : ZHF_BINARY;
}

RunResult run_zhf(const std::vector<std::string>& args, const std::string& working_dir,
                  const std::vector<std::string>& environment) {
  const std::string dir = make_temp_dir();
  std::vector<std::string> argv = {zhf_binary()};
  argv.insert(argv.end(), args.begin(), args.end());
  const io::ProcessResult process = io::run_process(argv, io::ProcessOptions{dir + "/out", dir + "/err", working_dir, environment, kRunTimeLimitSeconds});
  RunResult result;
  result.exit_code = process.exit_code;
  result.signal = process.signal;
  result.out = read_text(dir + "/out");
  result.err = read_text(dir + "/err");
  remove_dir(dir);
  return result;
}

io::Process start_zhf(const std::vector<std::string>& args, const std::string& stderr_path,
                      const std::vector<std::string>& environment) {
  std::vector<std::string> argv = {zhf_binary()};
  argv.insert(argv.end(), args.begin(), args.end());
  return io::start_process(argv, io::ProcessOptions{"/dev/null", stderr_path.empty() ? "/dev/null" : stderr_path, "", environment, 0});
}

int exit_code_of(io::Process& zhf) {
  const io::ProcessResult r = zhf.wait(kRunTimeLimitSeconds, false);
  return r.signal ? 128 + r.signal : r.exit_code;
}

std::string make_temp_dir() { return io::make_private_dir("zhf-test"); }

void remove_dir(const std::string& dir) {
  std::error_code ignored;
  std::filesystem::remove_all(dir, ignored);
}

std::string source_path(const std::string& relative) { return std::string(ZHF_SOURCE_DIR) + "/" + relative; }

bool browser_available(std::string& why) {
  const char* chromium = std::getenv("ZHF_CHROMIUM");
  if (!(chromium && *chromium) && !io::program_available("chromium")) why = "chromium not found (scripts/setup_web.sh)";
  else if (!io::program_available("node")) why = "node not found";
  else if (!std::filesystem::is_directory(source_path("tools/node/node_modules/puppeteer-core")))
    why = "puppeteer-core not in tools/node (scripts/setup_web.sh)";
  else return true;
  return false;
}

bool browser_required() {
  const char* required = std::getenv("ZHF_REQUIRE_BROWSER");
  return required && std::string(required) == "1";
}

std::string checked_in_table(int order) { return runtime::table_path(source_path("generated/lobes"), order); }

std::string data_path(const std::string& name) { return source_path("tests/data/" + name); }

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

nlohmann::json read_json(const std::string& path) { return nlohmann::json::parse(read_text(path)); }

void write_text(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

int line_count(const std::string& text) { return static_cast<int>(std::count(text.begin(), text.end(), '\n')); }

}  // namespace zhf::test
