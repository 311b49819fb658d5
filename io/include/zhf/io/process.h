// Starting other programs (compilers, shader tools, gnuplot): always from an argv vector, never
// through a shell, so no argument is ever interpreted; paths with spaces, quotes, '$', ';' or
// newlines are just paths.
#pragma once

#include <string>
#include <vector>

namespace zhf::io {

struct ProcessResult {
  int exit_code = -1;  // when it exited
  int signal = 0;      // when a signal ended it
  bool timed_out = false;  // stopped at ProcessOptions::time_limit_seconds
  bool ok() const { return exit_code == 0 && signal == 0; }
};

// Where a child's output goes: stdout to stdout_path and stderr to stderr_path, or both to
// stdout_path when stderr_path is empty; inherited when both are empty. It runs in working_dir
// (zhf's own when empty), with zhf's environment and the NAME=value entries of environment on top.
// A child still running after time_limit_seconds (when above 0) is stopped like an interrupted one.
struct ProcessOptions {
  std::string stdout_path;
  std::string stderr_path;
  std::string working_dir;
  std::vector<std::string> environment;
  double time_limit_seconds = 0;
};

// Runs argv[0] (searched on PATH) with argv, stdin from /dev/null, in a process group of its
// own; waits for it. When zhf is interrupted meanwhile (signals.h), the group gets SIGTERM
// (SIGKILL a second later if it is still there), is reaped, and Interrupted is thrown. A program
// that cannot be started exits 127, as from a shell.
ProcessResult run_process(const std::vector<std::string>& argv, const ProcessOptions& options);
// Both streams into one log (inherited when log_path is empty).
inline ProcessResult run_process(const std::vector<std::string>& argv, const std::string& log_path = "") {
  return run_process(argv, ProcessOptions{log_path, "", "", {}});
}

// Whether a program of that name is on PATH (executable).
bool program_available(const std::string& name);

// The first lines of a log, joined by " | ", escaped and cut short for a one-line message.
std::string log_excerpt(const std::string& log_path, int lines);

}  // namespace zhf::io
