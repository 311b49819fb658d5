// zhf's one signal policy. For the whole run of a command, SIGINT and SIGTERM only set a flag:
// long work polls it and stops, child processes are stopped with their process group, nothing
// half-written is committed, and the command exits 130 (SIGINT) or 143 (SIGTERM), its previous
// outputs intact. Work that cannot poll (a driver compiling a shader, one long search start) is
// ended by a watchdog: io::kInterruptGraceSeconds after the signal it removes every
// registered temporary (PendingFile's, private directories) and exits with the same code. SIGPIPE
// is ignored, so a closed pipe is a write error, not a silent death.
#pragma once

#include <atomic>
#include <stdexcept>
#include <string>
#include <vector>

#include "zhf/io/limits.h"

namespace zhf::io {

// Installs the handlers and the watchdog for its lifetime (main holds one).
class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;
};

// Set once SIGINT or SIGTERM has arrived.
const std::atomic<bool>& interrupt_requested();
// The exit code for the signal that arrived: 130 (SIGINT) or 143 (SIGTERM).
int interrupted_exit_code();

// While one exists, the watchdog leaves the process alone: the renames of a commit (a few
// microseconds each) run to their end, and an interrupt that arrived meanwhile is acted on after.
class CommitSection {
 public:
  CommitSection();
  ~CommitSection();
  CommitSection(const CommitSection&) = delete;
  CommitSection& operator=(const CommitSection&) = delete;
};

// The outputs written since the interrupt arrived (a commit it could not stop, or one it asked
// for), so that the message at the end names them; empty when the previous outputs are as they
// were.
void note_output_written(const std::string& path);
std::vector<std::string> outputs_written_after_interrupt();
// The one line zhf ends an interrupted run with: what was left as it was, and what was written.
std::string interrupted_message();

// Thrown where work stops for an interrupt; main turns it into interrupted_exit_code().
struct Interrupted : std::runtime_error {
  Interrupted() : std::runtime_error("interrupted") {}
};
// Throws Interrupted when a signal has arrived: the check before committing an output.
void throw_if_interrupted();

// Temporaries the watchdog removes if it has to end the process: a file, or a directory with
// everything in it. Registered while they exist.
void register_temporary(const std::string& path);
void unregister_temporary(const std::string& path);

}  // namespace zhf::io
