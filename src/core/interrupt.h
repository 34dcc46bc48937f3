#pragma once
// Ctrl-C (SIGINT) and SIGTERM stop a run cleanly. The handler only records the signal
// (async-signal-safe); long work polls it and throws Interrupted, whose unwinding reaches
// every OutputSet (removing its temporaries), and main exits with 128 + the signal.
// Polled by ProgressBar::add, the parallel loops, writeImage and OutputSet::commit.
//
//   installInterruptHandlers();            // once, in main
//   for (...) { throwIfInterrupted(); ... }
//   catch (const Interrupted& e) { return e.exitStatus(); }
namespace inim {

// Not a std::exception on purpose: handlers that turn failures into fallbacks must not
// swallow a stop request.
struct Interrupted {
  int signal;
  int exitStatus() const { return 128 + signal; }  // 130 for SIGINT, 143 for SIGTERM
};

// Catches SIGINT and SIGTERM (a second one gets the default action, so a run that does not
// poll can still be stopped). A signal ignored at start (a background job) stays ignored.
void installInterruptHandlers();
// The signal received, or 0.
int interruptSignal();
// Throws Interrupted once a signal was received.
void throwIfInterrupted();
// Forgets a received signal (tests).
void clearInterrupt();

}  // namespace inim
