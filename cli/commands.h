// Each subcommand registers itself on the app and returns the action to run once parsing
// succeeded. Actions throw UsageError, io::InputError, io::OutputError or io::Interrupted; main maps
// them to the exit codes below (docs/usage.md has the same table).
#pragma once

#include <functional>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>

namespace zhf::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;      // a check failed (verify), or an internal error
inline constexpr int kExitUsage = 2;        // bad command line (the message names the option)
inline constexpr int kExitBadInput = 3;     // an input file is missing or malformed (names the file and field)
inline constexpr int kExitOutput = 4;       // an output could not be written (names the path)
inline constexpr int kExitNoDevice = 5;     // verify: no Vulkan device for the shader languages
// Interrupted: 130 (SIGINT) or 143 (SIGTERM), previous outputs intact (io/signals.h).

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

using Action = std::function<int()>;

void add_candidates_command(CLI::App& app, Action& action);
// command_line is how the invocation is recorded in provenance and banners (see main.cc).
void add_optimize_command(CLI::App& app, Action& action, const std::string& command_line);
void add_codegen_commands(CLI::App& app, Action& action, const std::string& command_line);
void add_verify_command(CLI::App& app, Action& action);
void add_analyze_command(CLI::App& app, Action& action);
void add_bench_command(CLI::App& app, Action& action);
void add_rotate_command(CLI::App& app, Action& action);
void add_splat_command(CLI::App& app, Action& action);
void add_product_command(CLI::App& app, Action& action);
void add_project_command(CLI::App& app, Action& action);
void add_designs_command(CLI::App& app, Action& action);
void add_frame_command(CLI::App& app, Action& action);
void add_needlets_command(CLI::App& app, Action& action, const std::string& command_line);

}  // namespace zhf::cli
