#pragma once
// The page's live channel (docs/place-api.md, "Live channel"): over one WebSocket the page sends
// its state changes and the server pushes each changed revision's level 0 as soon as it is ready.
// The session calls are those of PUT /api/state and GET /api/preview?level=0; the channel only
// saves the page two requests per change. In the browser a fetch costs several milliseconds of
// a main thread busy with the drag, a message about one; the page falls back to HTTP without it.
//
// Messages: the page sends a JSON state patch (text). The server answers each with
// {"state": {...}} or {"error": "...", "status": 400} (text), in order, and later sends the
// revision's level 0 as a binary frame (liveImageFrame).
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include "place/place_session.h"

namespace inim {

// One binary frame: the header's length (4 bytes, big-endian), the header
// {"revision", "level": 0, "server_ms", "counts"} (or {"revision", "level", "error"}), the PNG.
std::string liveImageFrame(const ImageAnswer& a);

class LiveChannel {
 public:
  // `send` writes one message (binary or text) to the page. It is called from the caller's
  // thread (answers) and from the channel's own (images), so it serialises its writes itself
  // (the server holds civetweb's connection lock, which civetweb's own pings take too).
  using Send = std::function<void(bool binary, const std::string& bytes)>;
  LiveChannel(PlaceSession& session, Send send, size_t maxMessageBytes, std::chrono::milliseconds imageTimeout);
  ~LiveChannel();  // stops pushing; returns once no send is under way
  LiveChannel(const LiveChannel&) = delete;
  LiveChannel& operator=(const LiveChannel&) = delete;

  // A text message from the page: applied as PUT /api/state would, and answered.
  void onText(const std::string& text);
  // Anything else the page sends (binary): answered with a 400 error, changing nothing.
  void onBinary();

 private:
  void pushLoop();
  ImageAnswer waitForLevel0(uint64_t revision);

  PlaceSession& session_;
  Send send_;
  size_t maxBytes_;
  std::chrono::milliseconds imageTimeout_;
  std::mutex mutex_;
  std::condition_variable wake_;
  uint64_t wanted_ = 0, pushed_ = 0;  // revisions: the newest changed here, the newest handled
  bool stop_ = false;
  std::thread pusher_;
};

}  // namespace inim
