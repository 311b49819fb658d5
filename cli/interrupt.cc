#include "interrupt.h"

#include <csignal>

namespace zhf::cli {
namespace {

std::atomic<bool> g_interrupted{false};
struct sigaction g_previous_int, g_previous_term;

extern "C" void on_signal(int) { g_interrupted.store(true); }

}  // namespace

const std::atomic<bool>& interrupt_requested() { return g_interrupted; }

InterruptGuard::InterruptGuard() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, &g_previous_int);
  sigaction(SIGTERM, &action, &g_previous_term);
}

InterruptGuard::~InterruptGuard() {
  sigaction(SIGINT, &g_previous_int, nullptr);
  sigaction(SIGTERM, &g_previous_term, nullptr);
}

}  // namespace zhf::cli
