#include "zhf/io/signals.h"

#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <mutex>
#include <set>
#include <thread>

#include "zhf/runtime/limits.h"

namespace zhf::io {
namespace {

std::atomic<bool> g_interrupted{false};
std::atomic<int> g_signal{0};
struct sigaction g_previous_int, g_previous_term, g_previous_pipe;
// The handler wakes the watchdog through this pipe (write is async-signal-safe).
int g_wake[2] = {-1, -1};

std::mutex g_temporaries_mutex;
std::set<std::string>& temporaries() {
  static std::set<std::string> paths;
  return paths;
}

extern "C" void on_signal(int signal) {
  int none = 0;
  g_signal.compare_exchange_strong(none, signal);
  g_interrupted.store(true);
  const char byte = 1;
  if (g_wake[1] >= 0) {
    const ssize_t written = ::write(g_wake[1], &byte, 1);
    (void)written;  // a full pipe already holds a wake-up
  }
}

// Waits for a signal (or the guard's end, a closed pipe); after the grace period, if the process
// is still here, removes the temporaries and exits with the signal's code.
void watch() {
  char byte = 0;
  if (::read(g_wake[0], &byte, 1) != 1) return;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(runtime::kInterruptGraceSeconds);
  pollfd wake{g_wake[0], POLLIN, 0};
  while (std::chrono::steady_clock::now() < deadline) {
    const int left = static_cast<int>(
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now()).count());
    if (poll(&wake, 1, std::max(1, left)) > 0 && (wake.revents & (POLLHUP | POLLERR))) return;  // the guard ended
    if (wake.revents & POLLIN) {
      const ssize_t got = ::read(g_wake[0], &byte, 1);
      if (got == 0) return;
    }
  }
  {
    std::lock_guard<std::mutex> lock(g_temporaries_mutex);
    std::error_code ignored;
    for (const std::string& path : temporaries()) std::filesystem::remove_all(path, ignored);
  }
  const char message[] = "zhf: interrupted; the work in progress did not stop, ended it; previous outputs are as they were\n";
  [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, message, sizeof message - 1);
  std::_Exit(interrupted_exit_code());
}

std::thread g_watchdog;

}  // namespace

const std::atomic<bool>& interrupt_requested() { return g_interrupted; }

int interrupted_exit_code() { return 128 + (g_signal.load() ? g_signal.load() : SIGINT); }

void throw_if_interrupted() {
  if (g_interrupted.load()) throw Interrupted();
}

void register_temporary(const std::string& path) {
  std::lock_guard<std::mutex> lock(g_temporaries_mutex);
  temporaries().insert(path);
}

void unregister_temporary(const std::string& path) {
  std::lock_guard<std::mutex> lock(g_temporaries_mutex);
  temporaries().erase(path);
}

InterruptGuard::InterruptGuard() {
  if (pipe2(g_wake, O_CLOEXEC) == 0) {
    fcntl(g_wake[1], F_SETFL, O_NONBLOCK);
    g_watchdog = std::thread(watch);
  }
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, &g_previous_int);
  sigaction(SIGTERM, &action, &g_previous_term);
  struct sigaction ignore {};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  sigaction(SIGPIPE, &ignore, &g_previous_pipe);
}

InterruptGuard::~InterruptGuard() {
  sigaction(SIGINT, &g_previous_int, nullptr);
  sigaction(SIGTERM, &g_previous_term, nullptr);
  sigaction(SIGPIPE, &g_previous_pipe, nullptr);
  if (g_watchdog.joinable()) {
    const int writer = g_wake[1];
    g_wake[1] = -1;
    ::close(writer);  // the watchdog reads end-of-file and returns
    g_watchdog.join();
    ::close(g_wake[0]);
  }
}

}  // namespace zhf::io
