#include "zhf/io/process.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>

#include "zhf/io/errors.h"
#include "zhf/io/signals.h"

extern char** environ;

namespace zhf::io {
namespace {

// posix_spawn's file actions and attributes, released on every path.
struct SpawnSetup {
  posix_spawn_file_actions_t actions;
  posix_spawnattr_t attributes;
  SpawnSetup() {
    posix_spawn_file_actions_init(&actions);
    posix_spawnattr_init(&attributes);
  }
  ~SpawnSetup() {
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attributes);
  }
};

void stop_group(pid_t pid) {
  kill(-pid, SIGTERM);
  for (int i = 0; i < 100; ++i) {
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  kill(-pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
}

}  // namespace

Process::Process(Process&& other) noexcept : pid_(other.pid_), reaped_(other.reaped_) { other.reaped_ = true; }

Process::~Process() {
  if (pid_ > 0 && !reaped_) stop_group(pid_);
}

void Process::signal(int sig) const {
  if (pid_ > 0 && !reaped_) kill(pid_, sig);
}

ProcessResult Process::wait(double time_limit_seconds, bool stop_on_interrupt) {
  ProcessResult result;
  if (pid_ <= 0) {
    result.exit_code = 127;  // as a shell reports a program it cannot start
    return result;
  }
  const auto started = std::chrono::steady_clock::now();
  while (!reaped_) {
    int status = 0;
    const pid_t done = waitpid(pid_, &status, WNOHANG);
    if (done == pid_) {
      reaped_ = true;
      if (WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
      if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
      return result;
    }
    if (done < 0 && errno != EINTR) {
      reaped_ = true;
      return result;
    }
    if (stop_on_interrupt && interrupt_requested().load()) {
      stop_group(pid_);
      reaped_ = true;
      throw Interrupted();
    }
    if (time_limit_seconds > 0 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count() > time_limit_seconds) {
      stop_group(pid_);
      reaped_ = true;
      result.timed_out = true;
      result.signal = SIGTERM;
      return result;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return result;
}

Process start_process(const std::vector<std::string>& argv, const ProcessOptions& output) {
  // Paths in output are opened after the chdir: callers pass absolute ones with a working_dir.
  SpawnSetup setup;
  posix_spawn_file_actions_addopen(&setup.actions, 0, "/dev/null", O_RDONLY, 0);
  if (!output.stdout_path.empty()) {
    posix_spawn_file_actions_addopen(&setup.actions, 1, output.stdout_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    if (output.stderr_path.empty()) posix_spawn_file_actions_adddup2(&setup.actions, 1, 2);
  }
  if (!output.stderr_path.empty())
    posix_spawn_file_actions_addopen(&setup.actions, 2, output.stderr_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  if (!output.working_dir.empty()) posix_spawn_file_actions_addchdir_np(&setup.actions, output.working_dir.c_str());
  // A group of its own: a terminal's Ctrl-C reaches zhf alone, which stops the child itself.
  posix_spawnattr_setpgroup(&setup.attributes, 0);
  // The child starts with default signal handling whatever zhf ignores.
  sigset_t defaults;
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGINT);
  sigaddset(&defaults, SIGTERM);
  sigaddset(&defaults, SIGPIPE);
  posix_spawnattr_setsigdefault(&setup.attributes, &defaults);
  posix_spawnattr_setflags(&setup.attributes, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGDEF);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  // zhf's environment with the overrides on top (an override replaces the same name).
  std::vector<char*> env;
  for (char** e = environ; *e; ++e) {
    const std::string entry(*e);
    const std::string name = entry.substr(0, entry.find('=') + 1);
    bool overridden = false;
    for (const std::string& o : output.environment) overridden = overridden || o.rfind(name, 0) == 0;
    if (!overridden) env.push_back(*e);
  }
  for (const std::string& o : output.environment) env.push_back(const_cast<char*>(o.c_str()));
  env.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawnp(&pid, args[0], &setup.actions, &setup.attributes, args.data(), env.data()) != 0) pid = -1;
  return Process(pid);
}

ProcessResult run_process(const std::vector<std::string>& argv, const ProcessOptions& options) {
  throw_if_interrupted();
  Process child = start_process(argv, options);
  return child.wait(options.time_limit_seconds);
}

bool program_available(const std::string& name) {
  if (name.find('/') != std::string::npos) return access(name.c_str(), X_OK) == 0;
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    const std::string candidate = (dir.empty() ? "." : dir) + "/" + name;
    struct stat st {};
    if (stat(candidate.c_str(), &st) == 0 && S_ISREG(st.st_mode) && access(candidate.c_str(), X_OK) == 0) return true;
  }
  return false;
}

std::string log_excerpt(const std::string& log_path, int lines) {
  std::ifstream in(log_path);
  std::string line, out;
  for (int i = 0; i < lines && std::getline(in, line); ++i) out += (i ? " | " : "") + line;
  return excerpt(out, 300);
}

}  // namespace zhf::io
