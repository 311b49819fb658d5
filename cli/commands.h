// Each subcommand registers itself on the app and returns the action to run once parsing
// succeeded. Actions throw zhf::io errors or UsageError; main maps them to exit codes.
#pragma once

#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>

namespace zhf::cli {

// Exit codes (documented in README.md).
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;      // a check failed (e.g. verify), or an internal error
inline constexpr int kExitUsage = 2;        // bad command line
inline constexpr int kExitBadInput = 3;     // an input file is missing or malformed
inline constexpr int kExitOutput = 4;       // an output could not be written
inline constexpr int kExitNoDevice = 5;     // verify: no Vulkan device for the shader languages
inline constexpr int kExitInterrupted = 130;

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

using Action = std::function<int()>;

// A project path (e.g. "generated/lobes") as found here, in the working directory, or else in
// the source tree zhf was built from: zhf works from the checkout and from anywhere else.
// An empty directory of that name does not count.
inline std::string project_path(const std::string& relative) {
  std::error_code ec;
  const bool here = std::filesystem::is_directory(relative, ec) ? !std::filesystem::is_empty(relative, ec)
                                                               : std::filesystem::exists(relative, ec);
  return here ? relative : std::string(ZHF_SOURCE_DIR) + "/" + relative;
}

void add_candidates_command(CLI::App& app, Action& action);
// command_line is how the invocation is recorded in provenance (see main.cc).
void add_optimize_command(CLI::App& app, Action& action, const std::string& command_line);
void add_codegen_commands(CLI::App& app, Action& action, const std::string& command_line);
void add_verify_command(CLI::App& app, Action& action);
void add_analyze_command(CLI::App& app, Action& action);
void add_bench_command(CLI::App& app, Action& action);
void add_rotate_command(CLI::App& app, Action& action);

}  // namespace zhf::cli
