#include "zhf/io/signals.h"

#include <fcntl.h>
#include <poll.h>
#include <pthread.h>
#include <unistd.h>

#include <cerrno>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <mutex>
#include <set>
#include <thread>
#include <vector>

#include "zhf/io/limits.h"
#include "zhf/runtime/errors.h"


namespace zhf::io {
namespace {

std::atomic<bool> g_interrupted{false};
std::atomic<int> g_signal{0};
struct sigaction g_previous_int, g_previous_term, g_previous_pipe;
// The handler wakes the watchdog through this pipe (write is async-signal-safe); the write end is
// atomic because the handler reads it while the guard's end closes it.
int g_wake_reader = -1;
std::atomic<int> g_wake_writer{-1};

std::atomic<int> g_commit_sections{0};
std::mutex g_written_mutex;
std::vector<std::string> g_written;  // outputs committed after the interrupt

std::mutex g_temporaries_mutex;
std::set<std::string>& temporaries() {
  static std::set<std::string> paths;
  return paths;
}

extern "C" void on_signal(int signal) {
  const int saved_errno = errno;  // the interrupted code may be about to read it
  int none = 0;
  g_signal.compare_exchange_strong(none, signal);
  g_interrupted.store(true);
  const char byte = 1;
  const int writer = g_wake_writer.load();
  if (writer >= 0) {
    const ssize_t written = ::write(writer, &byte, 1);
    (void)written;  // a full pipe already holds a wake-up
  }
  errno = saved_errno;
}

// read(2) of one byte, retried when a signal interrupts it: 1, or 0 at end of file, or -1.
ssize_t read_byte(int fd, char* byte) {
  for (;;) {
    const ssize_t got = ::read(fd, byte, 1);
    if (got >= 0 || errno != EINTR) return got;
  }
}

// Waits for a signal (or the guard's end, a closed pipe); after the grace period, if the process
// is still here, removes the temporaries and exits with the signal's code.
void watch() {
  char byte = 0;
  if (read_byte(g_wake_reader, &byte) != 1) return;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(io::kInterruptGraceSeconds);
  pollfd wake{g_wake_reader, POLLIN, 0};
  while (std::chrono::steady_clock::now() < deadline) {
    const int left = static_cast<int>(
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now()).count());
    const int ready = poll(&wake, 1, std::max(1, left));
    if (ready < 0) continue;  // EINTR: the deadline decides
    if (ready > 0 && (wake.revents & (POLLHUP | POLLERR))) return;  // the guard ended
    if (ready > 0 && (wake.revents & POLLIN) && read_byte(g_wake_reader, &byte) == 0) return;
  }
  // A commit under way finishes first: its renames take microseconds.
  while (g_commit_sections.load() > 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  {
    std::lock_guard<std::mutex> lock(g_temporaries_mutex);
    std::error_code ignored;
    for (const std::string& path : temporaries()) std::filesystem::remove_all(path, ignored);
  }
  const std::string message = "zhf: interrupted; the work in progress did not stop, ended it; " + interrupted_message().substr(17) + "\n";
  [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, message.data(), message.size());
  std::_Exit(interrupted_exit_code());
}

std::thread g_watchdog;

}  // namespace

const std::atomic<bool>& interrupt_requested() { return g_interrupted; }

int interrupted_exit_code() { return 128 + (g_signal.load() ? g_signal.load() : SIGINT); }

void throw_if_interrupted() {
  if (g_interrupted.load()) throw Interrupted();
}

CommitSection::CommitSection() { ++g_commit_sections; }
CommitSection::~CommitSection() { --g_commit_sections; }

void note_output_written(const std::string& path) {
  if (!g_interrupted.load()) return;
  std::lock_guard<std::mutex> lock(g_written_mutex);
  g_written.push_back(path);
}

std::vector<std::string> outputs_written_after_interrupt() {
  std::lock_guard<std::mutex> lock(g_written_mutex);
  return g_written;
}

std::string interrupted_message() {
  const std::vector<std::string> written = outputs_written_after_interrupt();
  if (written.empty()) return "zhf: interrupted; previous outputs are as they were";
  std::string names;
  for (const std::string& path : written) names += (names.empty() ? "" : ", ") + runtime::excerpt(path, 200);
  return "zhf: interrupted after writing " + names + "; other previous outputs are as they were";
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
  int wake[2];
  if (pipe2(wake, O_CLOEXEC) == 0) {
    fcntl(wake[1], F_SETFL, O_NONBLOCK);
    g_wake_reader = wake[0];
    g_wake_writer.store(wake[1]);
    // The watchdog never takes SIGINT or SIGTERM (it inherits this mask): the handler runs on a
    // thread doing the work, and the watchdog's wait is never cut short.
    sigset_t stop, previous;
    sigemptyset(&stop);
    sigaddset(&stop, SIGINT);
    sigaddset(&stop, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &stop, &previous);
    g_watchdog = std::thread(watch);
    pthread_sigmask(SIG_SETMASK, &previous, nullptr);
  }
  struct sigaction action {};
  action.sa_handler = on_signal;
  action.sa_flags = SA_RESTART;  // the work's own reads and writes carry on; it polls the flag
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
    ::close(g_wake_writer.exchange(-1));  // the watchdog reads end-of-file and returns
    g_watchdog.join();
    ::close(g_wake_reader);
    g_wake_reader = -1;
  }
}

}  // namespace zhf::io
