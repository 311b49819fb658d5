#include "zhf/io/signals.h"

#include <csignal>

namespace zhf::io {
namespace {

std::atomic<bool> g_interrupted{false};
std::atomic<int> g_signal{0};
struct sigaction g_previous_int, g_previous_term, g_previous_pipe;

extern "C" void on_signal(int signal) {
  int none = 0;
  g_signal.compare_exchange_strong(none, signal);
  g_interrupted.store(true);
}

}  // namespace

const std::atomic<bool>& interrupt_requested() { return g_interrupted; }

int interrupted_exit_code() { return 128 + (g_signal.load() ? g_signal.load() : SIGINT); }

void throw_if_interrupted() {
  if (g_interrupted.load()) throw Interrupted();
}

InterruptGuard::InterruptGuard() {
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
}

}  // namespace zhf::io
