#include "core/progress.h"

#include <unistd.h>

#include <cstdio>

#include "core/interrupt.h"

namespace inim {

bool ProgressBar::stderrIsTerminal() { return isatty(STDERR_FILENO) == 1; }

ProgressBar::ProgressBar(std::string label, uint64_t total, bool enabled)
    : label_(std::move(label)), total_(total ? total : 1), enabled_(enabled),
      start_(std::chrono::steady_clock::now()) {}

ProgressBar::~ProgressBar() { finish(); }

void ProgressBar::add(uint64_t n) {
  throwIfInterrupted();  // long work reports here, so it stops promptly on Ctrl-C
  uint64_t done = done_.fetch_add(n) + n;
  if (!enabled_) return;
  auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(
                std::chrono::steady_clock::now() - start_).count();
  int64_t last = lastDrawMs_.load();
  if (ms - last < 100) return;  // redraw at most 10 times a second
  if (!lastDrawMs_.compare_exchange_strong(last, ms)) return;
  std::lock_guard<std::mutex> lock(drawMutex_);
  draw(done, false);
}

void ProgressBar::setNote(std::string note) {
  std::lock_guard<std::mutex> lock(drawMutex_);
  note_ = std::move(note);
  if (enabled_ && !finished_) draw(done_.load(), false);
}

void ProgressBar::finish() {
  std::lock_guard<std::mutex> lock(drawMutex_);
  if (finished_ || !enabled_) {
    finished_ = true;
    return;
  }
  finished_ = true;
  draw(done_.load(), true);
}

void ProgressBar::draw(uint64_t done, bool final) {
  double frac = std::min(1.0, double(done) / double(total_));
  double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  constexpr int kWidth = 30;
  int filled = int(frac * kWidth);
  std::string bar(filled, '#');
  bar.resize(kWidth, '.');
  double eta = frac > 0.0 ? secs * (1.0 - frac) / frac : 0.0;
  std::fprintf(stderr, "\r%s [%s] %5.1f%%  %.1fs elapsed, %.1fs left %s", label_.c_str(), bar.c_str(),
               100.0 * frac, secs, final ? 0.0 : eta, note_.empty() ? "" : ("  " + note_ + " ").c_str());
  if (final) std::fputc('\n', stderr);
  std::fflush(stderr);
}

}  // namespace inim
