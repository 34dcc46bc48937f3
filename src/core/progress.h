#pragma once
// A progress bar on stderr, shown only when stderr is a terminal (quiet when piped), and the
// wall-clock seconds that commands and runs report.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace inim {

// Wall-clock seconds since `start`.
inline double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

class ProgressBar {
 public:
  ProgressBar(std::string label, uint64_t total, bool enabled = stderrIsTerminal());
  ~ProgressBar();
  void add(uint64_t n);  // thread safe; throws Interrupted after SIGINT/SIGTERM (core/interrupt.h)
  void finish();
  // Text shown after the bar ("3 done, 1 failed"); thread safe.
  void setNote(std::string note);
  static bool stderrIsTerminal();

 private:
  void draw(uint64_t done, bool final);
  std::string label_;
  uint64_t total_;
  bool enabled_;
  std::atomic<uint64_t> done_{0};
  std::atomic<int64_t> lastDrawMs_{-1000};
  std::chrono::steady_clock::time_point start_;
  std::mutex drawMutex_;
  bool finished_ = false;
  std::string note_;
};

}  // namespace inim
