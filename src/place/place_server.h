#pragma once
// The placement page's HTTP server (docs/place-api.md) on civetweb: the page's files from
// web/place/ under the data folder, the JSON API over a PlaceSession, the live channel (a
// WebSocket, place/place_live.h), and access by token.
// civetweb parses HTTP; this file only routes, checks and answers.
//
//   PlaceServer server(session, {"127.0.0.1", 0});
//   std::puts(server.url().c_str());  // http://127.0.0.1:PORT/?token=...
#include <atomic>
#include <cstddef>
#include <string>

struct mg_context;
struct mg_connection;

namespace inim {

class PlaceSession;

struct PlaceServerOptions {
  std::string host = "127.0.0.1";
  int port = 0;                          // 0: a free port
  std::string token;                     // "": 32 random hex digits
  size_t maxBodyBytes = 1 << 20;         // larger bodies get 400
  int imageTimeoutMs = 60000;            // a preview request waits at most this long
};

// A random token of 32 hex digits (from the system's random device).
std::string randomToken();
// Equal strings, in time that does not depend on where they differ.
bool constantTimeEqual(const std::string& a, const std::string& b);
// InputError naming `host` unless it is an IPv4 address (dotted quad, each part 0-255), an
// IPv6 address (bracketed or not) or localhost: nothing else is bound or resolved.
void checkListenHost(const std::string& host);
// Whether `host` names a loopback interface (127.0.0.0/8, ::1, localhost).
bool isLoopbackHost(const std::string& host);

class PlaceServer {
 public:
  // Starts listening; std::runtime_error when the port cannot be had.
  PlaceServer(PlaceSession& session, const PlaceServerOptions& options);
  ~PlaceServer();
  PlaceServer(const PlaceServer&) = delete;
  PlaceServer& operator=(const PlaceServer&) = delete;

  int port() const { return port_; }
  const std::string& token() const { return token_; }
  std::string url() const;

 private:
  static int handleRequest(mg_connection* c, void* self);
  int handle(mg_connection* c);
  // The token: in the query (every request), or the X-Inim-Token header or the page's cookie
  // (plain requests only; a live channel gives it in its address, docs/place-api.md).
  bool allowed(const mg_connection* c, bool plainRequest) const;
  static int liveConnect(const mg_connection* c, void* self);
  static void liveReady(mg_connection* c, void* self);
  static int liveData(mg_connection* c, int bits, char* data, size_t size, void* self);
  static void liveClose(const mg_connection* c, void* self);

  PlaceSession& session_;
  PlaceServerOptions options_;
  std::string token_;
  int port_ = 0;
  mg_context* ctx_ = nullptr;
  static constexpr int kMaxLiveChannels = 32;  // more are answered 503: each holds a worker
  std::atomic<int> liveChannels_{0};
};

}  // namespace inim
