// The placement page's server over loopback (src/place/place_server.h): access by token, the
// state API, previews by revision, bad requests, and writes that stay in the output folder.
// Requests go through civetweb's own client, as a browser's would over TCP.
#include <arpa/inet.h>
#include <civetweb.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <thread>

#include "core/json_config.h"
#include "core/output_file.h"
#include "fixtures.h"
#include "place/served_session.h"
#include "place/place_server.h"
#include "place/place_session.h"
#include "runs/run_file.h"

using namespace inim;
namespace fs = std::filesystem;

namespace {

struct Http {
  int status = 0;
  std::string body;
  std::map<std::string, std::string> headers;
  Json json() const { return Json::parse(body); }
};

Http request(int port, const std::string& method, const std::string& target, const std::string& body = "",
             const std::string& headers = "") {
  char err[256] = "";
  mg_connection* c = mg_connect_client("127.0.0.1", port, 0, err, sizeof err);
  if (!c) return {-1, err, {}};
  mg_printf(c, "%s %s HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Length: %zu\r\n%s\r\n", method.c_str(), target.c_str(),
            body.size(), headers.c_str());
  mg_write(c, body.data(), body.size());
  Http h;
  if (mg_get_response(c, err, sizeof err, 60000) >= 0) {
    const mg_response_info* ri = mg_get_response_info(c);
    h.status = ri->status_code;
    for (int i = 0; i < ri->num_headers; ++i) h.headers[ri->http_headers[i].name] = ri->http_headers[i].value;
    char buf[16384];
    int n;
    while ((n = mg_read(c, buf, sizeof buf)) > 0) h.body.append(buf, size_t(n));
  } else {
    h.status = -1, h.body = err;
  }
  mg_close_connection(c);
  return h;
}

class PlaceServerTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { served_ = new fixtures::ServedSession("place_server"); }
  static void TearDownTestSuite() { delete served_; }
  static std::string tok() { return "token=" + served_->server.token(); }
  static Http get(const std::string& target) {
    return request(served_->server.port(), "GET", target, "", "X-Inim-Token: " + served_->server.token() + "\r\n");
  }
  static Http send(const std::string& method, const std::string& target, const std::string& body) {
    return request(served_->server.port(), method, target, body, "X-Inim-Token: " + served_->server.token() + "\r\n");
  }
  static uint64_t revision() { return get("/api/state").json()["revision"].get<uint64_t>(); }
  static Json waitForJob(uint64_t id) {
    for (int i = 0; i < 600; ++i) {
      Json j = get("/api/jobs/" + std::to_string(id)).json();
      if (j["state"] == "done" || j["state"] == "failed") return j;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    return {};
  }
  static fixtures::ServedSession* served_;
};
fixtures::ServedSession* PlaceServerTest::served_ = nullptr;

}  // namespace

TEST_F(PlaceServerTest, EveryRequestWithoutTheTokenIsForbidden) {
  const int port = served_->server.port();
  ASSERT_GT(port, 0);
  EXPECT_EQ(served_->server.url().rfind("http://127.0.0.1:" + std::to_string(port) + "/?token=", 0), 0u) << served_->server.url();
  for (const char* target : {"/", "/place.js", "/api/info", "/api/state", "/api/preview?level=0&revision=0",
                             "/api/jobs", "/nowhere"}) {
    EXPECT_EQ(request(port, "GET", target).status, 403) << target;
    EXPECT_EQ(request(port, "GET", std::string(target) + (std::strchr(target, '?') ? "&" : "?") + "token=0123").status, 403)
        << target;
    EXPECT_EQ(request(port, "GET", target, "", "Cookie: inim_token=" + served_->server.token() + "x\r\n").status, 403) << target;
  }
  // The live channel's handshake: the token in its address only (a cookie is not enough).
  const std::string upgrade = "Upgrade: websocket\r\nConnection: Upgrade\r\nSec-WebSocket-Version: 13\r\n"
                              "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n";
  EXPECT_EQ(request(port, "GET", "/api/live", "", upgrade).status, 403);
  EXPECT_EQ(request(port, "GET", "/api/live?token=0123", "", upgrade).status, 403);
  EXPECT_EQ(request(port, "GET", "/api/live", "", upgrade + "Cookie: inim_token=" + served_->server.token() + "\r\n").status, 403);
  const uint64_t before = revision();
  EXPECT_EQ(request(port, "PUT", "/api/state", R"({"vcp_mm": 50})").status, 403);
  EXPECT_EQ(revision(), before);  // and nothing changed
  EXPECT_TRUE(constantTimeEqual("abc", "abc"));
  EXPECT_FALSE(constantTimeEqual("abc", "abd"));
  EXPECT_FALSE(constantTimeEqual("abc", "abcd"));
}

TEST_F(PlaceServerTest, ThePageAndItsCookie) {
  Http page = request(served_->server.port(), "GET", "/?" + tok());
  ASSERT_EQ(page.status, 200) << page.body;
  EXPECT_NE(page.body.find("<html"), std::string::npos);
  EXPECT_NE(page.headers["Set-Cookie"].find("inim_token=" + served_->server.token()), std::string::npos);
  EXPECT_NE(page.headers["Set-Cookie"].find("HttpOnly"), std::string::npos);
  EXPECT_EQ(request(served_->server.port(), "GET", "/place.js", "", "Cookie: inim_token=" + served_->server.token() + "\r\n").status, 200);
}

TEST_F(PlaceServerTest, AStateChangeGivesANewRevisionAndItsPreview) {
  const Json info = get("/api/info").json();
  EXPECT_EQ(info["display"]["lenslets"], Json::array({153, 65}));
  const uint64_t r0 = revision();
  const Http put = send("PUT", "/api/state", R"({"placement": {"translate_mm": [0, 0, 5]}})");
  ASSERT_EQ(put.status, 200) << put.body;
  const uint64_t r1 = put.json()["revision"].get<uint64_t>();
  EXPECT_EQ(r1, r0 + 1);
  EXPECT_EQ(put.json()["placement"]["translate_mm"], Json::array({0.0, 0.0, 5.0}));
  Http p = get("/api/preview?level=0&revision=" + std::to_string(r1));
  ASSERT_EQ(p.status, 200) << p.body;
  EXPECT_EQ(p.headers["Content-Type"], "image/png");
  EXPECT_EQ(p.body.substr(1, 3), "PNG");
  EXPECT_EQ(p.headers["X-Inim-Revision"], std::to_string(r1));
  const Json counts = Json::parse(p.headers["X-Inim-Counts"]);
  EXPECT_GT(counts["on_plane"].get<int>(), 0);
  EXPECT_GT(std::stod(p.headers["X-Inim-Server-Ms"]), 0.0);
  EXPECT_EQ(get("/api/diagram?revision=" + std::to_string(r1)).status, 200);
  EXPECT_EQ(get("/api/preview?level=2&revision=" + std::to_string(r1)).status, 200);
  // An older revision is stale at once; a newer one does not exist.
  EXPECT_EQ(get("/api/preview?level=0&revision=" + std::to_string(r0)).status, 409);
  EXPECT_EQ(get("/api/preview?level=0&revision=" + std::to_string(r1 + 5)).status, 400);
  EXPECT_EQ(get("/api/preview?level=7&revision=" + std::to_string(r1)).status, 400);
  EXPECT_EQ(get("/api/preview?level=0&revision=x").status, 400);
  EXPECT_GE(get("/api/latency").json()["level0"]["count"].get<int>(), 1);
}

TEST_F(PlaceServerTest, BadRequestsAre400AndChangeNothing) {
  const Json before = get("/api/state").json();
  for (const std::string& body : {std::string("{\"vcp_mm\": "), std::string("{\"vcp_mm\": 1e400}"),
                                 std::string("{\"vcp_mm\": 1e9}"), std::string("{\"vcp\": 1}"),
                                 std::string("{\"placement\": {\"scale\": -1}}"), std::string("[]"),
                                 std::string("{\"display\": \"../../etc/passwd\"}"),
                                 "{\"vcp_mm\": 1, \"pad\": \"" + std::string(1 << 20, 'x') + "\"}"}) {
    const Http h = send("PUT", "/api/state", body);
    EXPECT_EQ(h.status, 400) << body.substr(0, 60) << ": " << h.body.substr(0, 200);
    if (h.status == 400) {
      EXPECT_TRUE(h.json().contains("error"));
    }
  }
  EXPECT_EQ(get("/api/state").json(), before);
  EXPECT_EQ(send("POST", "/api/state", "{}").status, 405);
  EXPECT_EQ(get("/api/nothing").status, 404);
  EXPECT_EQ(get("/api/jobs/99999").status, 404);
  EXPECT_EQ(get("/api/file?name=../../etc/passwd").status, 400);
  EXPECT_EQ(get("/api/file?name=placement.json").status, 400);  // only PNGs are served back
}

TEST_F(PlaceServerTest, WritesStayInTheOutputFolderAndAreWhole) {
  for (const char* name : {"../escape", "/tmp/abs", ".hidden", "a/b"}) {
    const Http h = send("POST", "/api/write", std::string(R"({"what": "run", "name": ")") + name + "\"}");
    EXPECT_EQ(h.status, 400) << name << ": " << h.body;
  }
  EXPECT_EQ(send("POST", "/api/write", R"({"what": "everything"})").status, 400);
  EXPECT_EQ(send("POST", "/api/predict", R"({"angle_deg": 90})").status, 400);
  EXPECT_FALSE(fs::exists(served_->out.path("escape.json")));

  const Http w = send("POST", "/api/write", R"({"what": "run", "name": "placed"})");
  ASSERT_EQ(w.status, 202) << w.body;
  const Json j = waitForJob(w.json()["job"].get<uint64_t>());
  ASSERT_EQ(j["state"], "done") << j.dump();
  const std::string file = served_->session.outDir() + "/placed.json";
  const RunFile run = loadRunFile(file);
  EXPECT_EQ(*run.vcpMm, get("/api/state").json()["vcp_mm"].get<double>());

  // A write that cannot complete (its name is taken by a folder) fails and leaves no temporary.
  fs::create_directories(served_->session.outDir() + "/blocked.json");
  const Json f = waitForJob(send("POST", "/api/write", R"({"what": "run", "name": "blocked"})").json()["job"].get<uint64_t>());
  EXPECT_EQ(f["state"], "failed");
  EXPECT_FALSE(f["error"].get<std::string>().empty());
  for (const auto& e : fs::directory_iterator(served_->session.outDir()))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

namespace {

// Whether `s` is valid UTF-8 (what every answer must be, whatever bytes a request held).
bool validUtf8(const std::string& s) {
  for (size_t i = 0; i < s.size();) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    const int n = c < 0x80 ? 1 : (c >> 5) == 6 ? 2 : (c >> 4) == 14 ? 3 : (c >> 3) == 30 ? 4 : 0;
    if (n == 0 || i + size_t(n) > s.size()) return false;
    for (int k = 1; k < n; ++k)
      if ((static_cast<unsigned char>(s[i + size_t(k)]) >> 6) != 2) return false;
    i += size_t(n);
  }
  return true;
}

// A TCP connection to the server that says nothing (idle) or only part of a request (slow).
int openRaw(int port, const std::string& say) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(uint16_t(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) return close(fd), -1;
  if (!say.empty()) (void)!write(fd, say.data(), say.size());
  return fd;
}

}  // namespace

TEST_F(PlaceServerTest, NonUtf8BytesInARequestGiveAValidAnswerAndTheServerLives) {
  const std::vector<Http> answers = {
      send("PUT", "/api/state", "{\"layout\": \"\xff\"}"),
      get("/api/file?name=%FF.png"),
      get("/api/preview?level=%FF&revision=0"),
      get("/%FF"),
      get("/api/jobs/%FF%FE"),
  };
  for (const Http& h : answers) {
    EXPECT_GE(h.status, 400) << h.body;
    EXPECT_LT(h.status, 500) << h.body;
    EXPECT_TRUE(validUtf8(h.body)) << h.body;
    EXPECT_NO_THROW(h.json()) << h.body;
  }
  EXPECT_EQ(get("/api/state").status, 200);
}

TEST_F(PlaceServerTest, TheTokenCountsOnlyWhereTheDocsSayIt) {
  const int port = served_->server.port();
  const std::string token = served_->server.token();
  EXPECT_EQ(request(port, "GET", "/api/state?token=" + token).status, 200);
  EXPECT_EQ(request(port, "GET", "/api/state?Token=" + token).status, 403);
  EXPECT_EQ(request(port, "GET", "/api/state?TOKEN=" + token).status, 403);
  EXPECT_EQ(request(port, "GET", "/api/state?xtoken=" + token).status, 403);
  // The live channel takes the token in its address only, not in a header.
  const std::string upgrade = "Upgrade: websocket\r\nConnection: Upgrade\r\nSec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\n"
                              "Sec-WebSocket-Version: 13\r\n";
  EXPECT_EQ(request(port, "GET", "/api/live", "", upgrade + "X-Inim-Token: " + token + "\r\n").status, 403);
}

TEST_F(PlaceServerTest, IdleAndSlowClientsCannotLockThePage) {
  const int port = served_->server.port();
  std::vector<int> held;
  for (int i = 0; i < 64; ++i) held.push_back(openRaw(port, ""));                       // idle, no token
  for (int i = 0; i < 64; ++i) held.push_back(openRaw(port, "GET /api/state HTTP/1.1\r\nHo"));  // slow
  for (int fd : held) ASSERT_GE(fd, 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // every one accepted and waiting
  const auto t0 = std::chrono::steady_clock::now();
  const uint64_t r = revision();
  const Http p = get("/api/preview?level=0&revision=" + std::to_string(r));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(p.status, 200) << p.body;
  // Served while all 128 are held: well before any of them times out (10 s), not after.
  EXPECT_LT(seconds, 5.0);
  for (int fd : held) close(fd);
}
