// SIGINT/SIGTERM set a flag that long-running work polls, so it can stop cleanly and save
// what it has instead of dying mid-write.
#pragma once

#include <atomic>

namespace zhf::cli {

const std::atomic<bool>& interrupt_requested();

// Installs the handlers for its lifetime.
class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;
};

}  // namespace zhf::cli
