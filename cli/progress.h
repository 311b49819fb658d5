// The progress line of a long command (optimize, designs, verify, bench, project, needlets
// tables, splat): on a terminal, one line on stderr rewritten in place with what is being done,
// how far it is and an estimate of the time left; elsewhere nothing, unless --verbose asks for a
// line per step (at most one a second). --quiet silences it everywhere.
#pragma once

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <utility>

namespace zhf::cli {

class Progress {
 public:
  Progress(std::string command, bool quiet, bool verbose = false)
      : command_(std::move(command)), tty_(!quiet && isatty(STDERR_FILENO)), log_(!quiet && !tty_ && verbose) {}
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  ~Progress() { done(); }

  // done of total steps (total 0: unknown), and what the steps are.
  void update(double done, double total, const std::string& what) {
    if (!due()) return;
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    char line[256];
    if (total > 0 && done > 0 && done < total) {
      std::snprintf(line, sizeof line, "%.0f of %.0f %s, %.0f s, about %.0f s left", done, total, what.c_str(), elapsed,
                    elapsed * (total - done) / done);
    } else {
      std::snprintf(line, sizeof line, "%.0f %s, %.0f s", done, what.c_str(), elapsed);
    }
    show(line);
  }
  // A state in words, where no count says it (a search's best so far).
  void say(const std::string& text) {
    if (due()) show(text);
  }
  // Clears a terminal's line (the command's own summary follows on stdout).
  void done() {
    if (tty_ && shown_) std::fprintf(stderr, "\r%-79s\r", "");
    shown_ = false;
  }

 private:
  using Clock = std::chrono::steady_clock;

  bool due() {
    if (!tty_ && !log_) return false;
    const Clock::time_point now = Clock::now();
    if (shown_ && now - last_ < (tty_ ? std::chrono::milliseconds(200) : std::chrono::milliseconds(1000))) return false;
    last_ = now;
    return true;
  }
  void show(const std::string& text) {
    std::string line = "zhf " + command_ + ": " + text;
    if (tty_ && line.size() > 79) line.resize(79);
    if (tty_) {
      std::fprintf(stderr, "\r%-79s", line.c_str());
    } else {
      std::fprintf(stderr, "%s\n", line.c_str());
    }
    std::fflush(stderr);
    shown_ = true;
  }

  std::string command_;
  bool tty_, log_;
  bool shown_ = false;
  Clock::time_point start_ = Clock::now(), last_{};
};

}  // namespace zhf::cli
