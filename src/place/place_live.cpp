#include "place/place_live.h"

#include "core/error.h"
#include "core/json_config.h"

namespace inim {

std::string liveImageFrame(const ImageAnswer& a) {
  Json h = {{"revision", a.revision}, {"level", 0}};
  if (a.status == ImageAnswer::Status::Ready)
    h["server_ms"] = a.serverMs, h["counts"] = a.counts;
  else
    h["error"] = a.error.empty() ? "the level-0 image failed" : a.error;
  const std::string head = jsonText(h);
  const uint32_t n = uint32_t(head.size());
  std::string frame{char(n >> 24), char(n >> 16), char(n >> 8), char(n)};
  frame += head;
  if (a.status == ImageAnswer::Status::Ready) frame += a.png;
  return frame;
}

LiveChannel::LiveChannel(PlaceSession& session, Send send, size_t maxMessageBytes,
                         std::chrono::milliseconds imageTimeout)
    : session_(session), send_(std::move(send)), maxBytes_(maxMessageBytes), imageTimeout_(imageTimeout) {
  pusher_ = std::thread([this] { pushLoop(); });
}

LiveChannel::~LiveChannel() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  pusher_.join();
}

void LiveChannel::onText(const std::string& text) {
  Json answer;
  try {
    if (text.size() > maxBytes_)
      throw InputError("message", "", "over " + std::to_string(maxBytes_) + " bytes", "a message of at most 1 MiB");
    answer = {{"state", session_.putState(text)}};
  } catch (const InputError& e) {
    answer = {{"error", e.what()}, {"status", 400}};
  } catch (const std::exception& e) {
    answer = {{"error", e.what()}, {"status", 500}};
  }
  send_(false, jsonText(answer));
  if (!answer.contains("state")) return;
  {  // after the answer, so that the page knows the revision before its image comes
    std::lock_guard<std::mutex> lock(mutex_);
    wanted_ = std::max(wanted_, answer["state"]["revision"].get<uint64_t>());
  }
  wake_.notify_all();
}

void LiveChannel::onBinary() {
  send_(false, jsonText(Json{{"error", "message: a JSON state patch as text expected"}, {"status", 400}}));
}

// Level 0 of `revision`, waited for in short steps so that closing the channel is not held up.
ImageAnswer LiveChannel::waitForLevel0(uint64_t revision) {
  const auto step = std::chrono::milliseconds(100);
  const auto deadline = std::chrono::steady_clock::now() + imageTimeout_;
  while (true) {
    ImageAnswer a = session_.image(ImageKind::Level0, revision, step);
    if (a.status != ImageAnswer::Status::Timeout || std::chrono::steady_clock::now() >= deadline) return a;
    std::lock_guard<std::mutex> lock(mutex_);
    if (stop_) return a;
  }
}

// Each revision changed here gets its level 0 pushed, in order, unless the session answers that
// it went stale unrendered (the newer one follows); as over HTTP, a level 0 that was under way
// when the state moved on is still sent, so a drag shows frames.
void LiveChannel::pushLoop() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    wake_.wait(lock, [this] { return stop_ || wanted_ > pushed_; });
    if (stop_) return;
    const uint64_t rev = wanted_;
    lock.unlock();
    ImageAnswer a = waitForLevel0(rev);
    lock.lock();
    if (stop_) return;
    pushed_ = std::max(pushed_, rev);
    using S = ImageAnswer::Status;
    if (a.status == S::Stale || a.status == S::Future) continue;  // a newer revision follows
    if (a.status == S::Timeout)
      a.status = S::Failed, a.error = "level 0 of revision " + std::to_string(rev) + " was not ready in time";
    lock.unlock();
    send_(true, liveImageFrame(a));
    lock.lock();
  }
}

}  // namespace inim
