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

// A started child: argv[0] (searched on PATH) with argv, stdin from /dev/null, in a process group
// of its own. Dropped while still running, its group is stopped (SIGTERM, SIGKILL a second later).
class Process {
 public:
  Process(Process&& other) noexcept;
  Process& operator=(Process&&) = delete;
  ~Process();

  int pid() const { return pid_; }  // -1: it could not be started
  // Sends sig to the child alone (a user's Ctrl-C, a test's interrupt).
  void signal(int sig) const;
  // Waits until it ends. After time_limit_seconds (when above 0) its group is stopped and the
  // result says timed_out. With stop_on_interrupt, zhf's own interrupt (signals.h) stops the group
  // and throws Interrupted. A program that could not be started exits 127, as from a shell.
  ProcessResult wait(double time_limit_seconds = 0, bool stop_on_interrupt = true);

 private:
  friend Process start_process(const std::vector<std::string>& argv, const ProcessOptions& options);
  explicit Process(int pid) : pid_(pid) {}
  int pid_;
  bool reaped_ = false;
};

Process start_process(const std::vector<std::string>& argv, const ProcessOptions& options);

// start_process, then wait with the options' time limit: what zhf does with every tool it runs.
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
