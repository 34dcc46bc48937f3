// The live channel (src/place/place_live.h) over loopback, through civetweb's own WebSocket
// client: the token, each change answered in order and its level 0 pushed, the newest revision's
// level 0 always arriving after a burst of changes, and bad messages refused without a change.
#include <civetweb.h>
#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <optional>

#include "core/json_config.h"
#include "core/output_file.h"
#include "fixtures.h"
#include "place/served_session.h"
#include "place/place_live.h"
#include "place/place_server.h"
#include "place/place_session.h"

using namespace inim;

namespace {

struct Message {
  bool binary = false;
  std::string bytes;
};

// A WebSocket client that queues what the server sends.
class LiveClient {
 public:
  LiveClient(int port, const std::string& path) {
    c_ = mg_connect_websocket_client("127.0.0.1", port, 0, err_, sizeof err_, path.c_str(), nullptr, &onData,
                                     nullptr, this);
  }
  ~LiveClient() {
    if (!c_) return;
    // A close frame first: the server's answer ends the client's reader at once.
    mg_websocket_client_write(c_, MG_WEBSOCKET_OPCODE_CONNECTION_CLOSE, "", 0);
    mg_close_connection(c_);
  }
  bool connected() const { return c_ != nullptr; }
  std::string error() const { return err_; }
  void send(const std::string& s, bool binary = false) {
    mg_websocket_client_write(c_, binary ? MG_WEBSOCKET_OPCODE_BINARY : MG_WEBSOCKET_OPCODE_TEXT, s.data(), s.size());
  }
  std::optional<Message> next(std::chrono::seconds timeout = std::chrono::seconds(60)) {
    std::unique_lock<std::mutex> lock(m_);
    if (!cv_.wait_for(lock, timeout, [this] { return !got_.empty(); })) return std::nullopt;
    Message msg = std::move(got_.front());
    got_.pop_front();
    return msg;
  }
  Json nextText() {
    auto msg = next();
    if (!msg || msg->binary) return Json();
    return Json::parse(msg->bytes);
  }

 private:
  static int onData(mg_connection*, int bits, char* data, size_t n, void* self) {
    auto* me = static_cast<LiveClient*>(self);
    const int op = bits & 0xf;
    if (op == MG_WEBSOCKET_OPCODE_TEXT || op == MG_WEBSOCKET_OPCODE_BINARY) {
      std::lock_guard<std::mutex> lock(me->m_);
      me->got_.push_back({op == MG_WEBSOCKET_OPCODE_BINARY, std::string(data, n)});
      me->cv_.notify_all();
    }
    return 1;
  }
  mg_connection* c_ = nullptr;
  char err_[256] = "";
  std::mutex m_;
  std::condition_variable cv_;
  std::deque<Message> got_;
};

// liveImageFrame's parts: header and PNG.
struct LiveFrame {
  Json header;
  std::string png;
};
LiveFrame parseFrame(const std::string& f) {
  const auto b = [&f](size_t i) { return uint32_t(uint8_t(f[i])); };
  const uint32_t n = b(0) << 24 | b(1) << 16 | b(2) << 8 | b(3);
  return {Json::parse(f.substr(4, n)), f.substr(4 + n)};
}

class PlaceLiveTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { served_ = new fixtures::ServedSession("place_live"); }
  static void TearDownTestSuite() { delete served_; }
  static std::string livePath() { return "/api/live?token=" + served_->server.token(); }
  static uint64_t revision() { return served_->session.state()["revision"].get<uint64_t>(); }
  static fixtures::ServedSession* served_;
};
fixtures::ServedSession* PlaceLiveTest::served_ = nullptr;

}  // namespace

TEST(LiveImageFrame, HeaderLengthHeaderThenPng) {
  ImageAnswer a;
  a.revision = 7, a.serverMs = 12.5, a.png = "\x89PNG..", a.counts = {{"real", 1}};
  const std::string f = liveImageFrame(a);
  const std::string head = R"({"counts":{"real":1},"level":0,"revision":7,"server_ms":12.5})";
  const std::string length{0, 0, 0, char(head.size())};
  EXPECT_EQ(f, length + head + "\x89PNG..");
  a.status = ImageAnswer::Status::Failed, a.error = "boom";
  const LiveFrame failed = parseFrame(liveImageFrame(a));
  EXPECT_EQ(failed.header["error"], "boom");
  EXPECT_TRUE(failed.png.empty());
}

TEST_F(PlaceLiveTest, TheHandshakeNeedsTheToken) {
  for (const std::string& path : {std::string("/api/live"), "/api/live?token=" + std::string(32, '0')}) {
    LiveClient ws(served_->server.port(), path);
    EXPECT_FALSE(ws.connected()) << path;  // the 403 itself: test_place_server.cpp
  }
  LiveClient ws(served_->server.port(), livePath());
  EXPECT_TRUE(ws.connected()) << ws.error();
}

TEST_F(PlaceLiveTest, EachChangeIsAnsweredThenItsLevel0Pushed) {
  LiveClient ws(served_->server.port(), livePath());
  ASSERT_TRUE(ws.connected()) << ws.error();
  const uint64_t r0 = revision();
  ws.send(R"({"vcp_mm": 61})");
  const Json answer = ws.nextText();
  ASSERT_TRUE(answer.contains("state")) << answer.dump();
  EXPECT_EQ(answer["state"]["revision"], r0 + 1);
  EXPECT_EQ(answer["state"]["vcp_mm"], 61.0);
  const auto msg = ws.next();
  ASSERT_TRUE(msg && msg->binary);
  const LiveFrame f = parseFrame(msg->bytes);
  EXPECT_EQ(f.header["revision"], r0 + 1);
  EXPECT_EQ(f.header["level"], 0);
  EXPECT_GT(f.header["server_ms"].get<double>(), 0.0);
  EXPECT_GT(f.header["counts"]["on_plane"].get<int>(), 0);
  // The image GET /api/preview?level=0 serves for that revision, byte for byte.
  EXPECT_EQ(f.png, served_->session.image(ImageKind::Level0, r0 + 1, std::chrono::seconds(60)).png);
}

// A drag: changes faster than level 0 renders. Every change is answered, in order; frames in
// between may be skipped, but the last revision's level 0 always comes.
TEST_F(PlaceLiveTest, AfterABurstOfChangesTheNewestLevel0Comes) {
  LiveClient ws(served_->server.port(), livePath());
  ASSERT_TRUE(ws.connected()) << ws.error();
  const uint64_t r0 = revision();
  for (int k = 1; k <= 6; ++k) ws.send(R"({"placement": {"translate_mm": [0, 0, )" + std::to_string(k) + "]}}");
  uint64_t answered = r0, newestImage = 0;
  while (newestImage < r0 + 6) {
    const auto msg = ws.next();
    ASSERT_TRUE(msg) << "no level 0 of revision " << r0 + 6 << " came";
    if (msg->binary) {
      const uint64_t rev = parseFrame(msg->bytes).header["revision"].get<uint64_t>();
      EXPECT_GT(rev, newestImage);
      EXPECT_LE(rev, answered);  // never before its answer
      newestImage = rev;
    } else {
      EXPECT_EQ(Json::parse(msg->bytes)["state"]["revision"], ++answered);
    }
  }
  EXPECT_EQ(answered, r0 + 6);
}

TEST_F(PlaceLiveTest, BadMessagesAre400AndChangeNothing) {
  LiveClient ws(served_->server.port(), livePath());
  ASSERT_TRUE(ws.connected()) << ws.error();
  const Json before = served_->session.state();
  for (const std::string& body : {std::string("{\"vcp_mm\": "), std::string("{\"vcp_mm\": 1e400}"),
                                 std::string("{\"vcp_mm\": 1e9}"), std::string("[]"),
                                 "{\"vcp_mm\": 1, \"pad\": \"" + std::string(1 << 20, 'x') + "\"}"}) {
    ws.send(body);
    const Json a = ws.nextText();
    EXPECT_EQ(a["status"], 400) << body.substr(0, 60) << ": " << a.dump().substr(0, 200);
    EXPECT_TRUE(a.contains("error") && !a.contains("state"));
  }
  ws.send(R"({"vcp_mm": 62})", true);  // binary
  EXPECT_EQ(ws.nextText()["status"], 400);
  EXPECT_EQ(served_->session.state(), before);
  ws.send(R"({"vcp_mm": 62})");  // the channel still works
  EXPECT_EQ(ws.nextText()["state"]["vcp_mm"], 62.0);
}
