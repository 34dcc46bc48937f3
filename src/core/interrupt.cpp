#include "core/interrupt.h"

#include <signal.h>

#include <atomic>

namespace inim {

namespace {

// Lock-free, so storing to it is async-signal-safe.
std::atomic<int> received{0};
static_assert(std::atomic<int>::is_always_lock_free);

extern "C" void recordSignal(int sig) { received.store(sig, std::memory_order_relaxed); }

void catchSignal(int sig) {
  struct sigaction old {};
  if (sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) return;
  struct sigaction sa {};
  sa.sa_handler = recordSignal;
  sigemptyset(&sa.sa_mask);
  // SA_RESTART: library I/O (OIIO, streams) never sees EINTR; SA_RESETHAND: the second
  // signal stops the process at once.
  sa.sa_flags = SA_RESTART | SA_RESETHAND;
  sigaction(sig, &sa, nullptr);
}

}  // namespace

void installInterruptHandlers() {
  catchSignal(SIGINT);
  catchSignal(SIGTERM);
}

int interruptSignal() { return received.load(std::memory_order_relaxed); }

void throwIfInterrupted() {
  if (int sig = interruptSignal()) throw Interrupted{sig};
}

void clearInterrupt() { received.store(0); }

}  // namespace inim
