#include "place/place_server.h"

#include <arpa/inet.h>
#include <civetweb.h>

#include <charconv>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>

#include "core/error.h"
#include "core/json_config.h"
#include "core/output_file.h"
#include "place/place_jobs.h"
#include "place/place_live.h"
#include "place/place_session.h"
#include "core/file_kinds.h"

namespace inim {

std::string randomToken() {
  std::random_device rd;
  static const char* hex = "0123456789abcdef";
  std::string t;
  for (int i = 0; i < 32; ++i) t += hex[rd() & 15u];
  return t;
}

bool constantTimeEqual(const std::string& a, const std::string& b) {
  unsigned diff = unsigned(a.size() ^ b.size());
  const size_t n = std::max(a.size(), b.size());
  for (size_t i = 0; i < n; ++i) {
    const unsigned char x = i < a.size() ? a[i] : 0, y = i < b.size() ? b[i] : 0;
    diff |= unsigned(x ^ y);
  }
  return diff == 0;
}

void checkListenHost(const std::string& host) {
  const std::string bare = host.size() > 2 && host.front() == '[' && host.back() == ']' ? host.substr(1, host.size() - 2) : host;
  unsigned char address[16];
  if (host == "localhost" || inet_pton(AF_INET, host.c_str(), address) == 1 ||
      inet_pton(AF_INET6, bare.c_str(), address) == 1)
    return;
  throw InputError("", "host", "\"" + host + "\"",
                   "an IPv4 address (127.0.0.1, or 0.0.0.0 for every interface), an IPv6 address or localhost");
}

bool isLoopbackHost(const std::string& host) {
  return host == "localhost" || host == "::1" || host == "[::1]" || host.rfind("127.", 0) == 0;
}

namespace {

struct MethodNotAllowed {
  std::string allowed;
};

struct Answer {
  int status = 200;
  std::string type = "application/json", body, headers;
};

const char* statusText(int s) {
  switch (s) {
    case 200: return "OK";
    case 202: return "Accepted";
    case 400: return "Bad Request";
    case 403: return "Forbidden";
    case 404: return "Not Found";
    case 405: return "Method Not Allowed";
    case 409: return "Conflict";
    case 503: return "Service Unavailable";
    default: return "Internal Server Error";
  }
}

Answer json(const Json& j, int status = 200) { return {status, "application/json", jsonText(j), ""}; }
Answer error(int status, const std::string& message) { return json({{"error", message}}, status); }

// Head and body in one write: with TCP_NODELAY (which the live channel needs: without it a
// message waited for the page's delayed ACK, about 40 ms), a second write is its own segment.
// Each answer closes its connection: a client's kept-alive socket that the server closed as idle
// fails the next request in clients that do not retry (Node's fetch did), and the requests left
// on HTTP are few since the live channel carries the drag.
void send(mg_connection* c, const Answer& a) {
  std::string out = "HTTP/1.1 " + std::to_string(a.status) + " " + statusText(a.status) +
                    "\r\nContent-Type: " + a.type + "\r\nContent-Length: " + std::to_string(a.body.size()) +
                    "\r\nCache-Control: no-store\r\nX-Content-Type-Options: nosniff\r\n" + a.headers +
                    "Connection: close\r\n\r\n";
  out += a.body;
  mg_write(c, out.data(), out.size());
}

// The value of query parameter `name`, spelt exactly so (civetweb's own look-up ignores case:
// "?Token=" would pass for "?token="), URL-decoded; "" when absent.
std::string queryVar(const mg_request_info* ri, const char* name) {
  if (!ri->query_string) return {};
  const std::string query = ri->query_string, key = std::string(name) + "=";
  for (size_t at = 0; at <= query.size();) {
    const size_t end = std::min(query.find('&', at), query.size());
    if (query.compare(at, key.size(), key) == 0 && at + key.size() <= end) {
      const std::string raw = query.substr(at + key.size(), end - at - key.size());
      std::string decoded(raw.size() + 1, '\0');
      const int n = mg_url_decode(raw.data(), int(raw.size()), decoded.data(), int(decoded.size()), 1);
      return n >= 0 ? decoded.substr(0, size_t(n)) : std::string();
    }
    at = end + 1;
  }
  return {};
}

// A whole number from a query parameter; InputError naming it otherwise.
uint64_t queryNumber(const mg_request_info* ri, const char* name) {
  const std::string s = queryVar(ri, name);
  uint64_t v = 0;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || p != s.data() + s.size())
    throw InputError("request", name, "\"" + s.substr(0, 40) + "\"", "a whole number");
  return v;
}

std::string readFile(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return {};
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

// The request body, or nullopt when it is over `limit` bytes. The rest of a body over the limit
// is read and dropped (up to 64 MiB), so that the client gets the 400 instead of a reset.
std::optional<std::string> readBody(mg_connection* c, size_t limit) {
  std::string body;
  char buf[16384];
  int n;
  size_t total = 0;
  while (total < (size_t(64) << 20) && (n = mg_read(c, buf, sizeof buf)) > 0) {
    total += size_t(n);
    if (total <= limit) body.append(buf, size_t(n));
  }
  if (total > limit) return std::nullopt;
  return body;
}

Answer imageAnswer(const ImageAnswer& a, int level) {
  using S = ImageAnswer::Status;
  if (a.status == S::Stale) return error(409, "revision " + std::to_string(a.revision) + " is stale");
  if (a.status == S::Future) return error(400, "revision " + std::to_string(a.revision) + " does not exist yet");
  if (a.status == S::Timeout) return error(503, "the image is not ready yet");
  if (a.status == S::Failed) return error(500, a.error);
  char ms[32];
  std::snprintf(ms, sizeof ms, "%.1f", a.serverMs);
  Answer r{200, "image/png", a.png, ""};
  r.headers = "X-Inim-Revision: " + std::to_string(a.revision) + "\r\nX-Inim-Level: " + std::to_string(level) +
              "\r\nX-Inim-Server-Ms: " + ms + "\r\nX-Inim-Counts: " + jsonText(a.counts) + "\r\n";
  return r;
}

Answer forbidden() { return error(403, "forbidden: open the URL inim place printed (it carries the access token)"); }

Answer staticFile(const std::string& name, const std::string& type) {
  const std::string body = readFile(dataPath("web/place/" + name));
  if (body.empty()) return error(404, "web/place/" + name + " is missing");
  return {200, type, body, ""};
}

}  // namespace

PlaceServer::PlaceServer(PlaceSession& session, const PlaceServerOptions& options)
    : session_(session), options_(options), token_(options.token.empty() ? randomToken() : options.token) {
  checkListenHost(options.host);
  mg_init_library(0);
  const std::string host = options.host.find(':') != std::string::npos && options.host[0] != '['
                               ? "[" + options.host + "]" : options.host;
  const std::string ports = host + ":" + std::to_string(options.port);
  // Workers for every client the page can have and then some: a connection holds a worker until
  // it is answered (at once without the token) or idle for request_timeout_ms, and a live
  // channel holds one while open (at most kMaxLiveChannels), so idle or slow clients cannot take
  // them all (tests/place: 64 idle and 64 slow connections, and the page is still served).
  const char* opts[] = {"listening_ports", ports.c_str(), "num_threads", "256", "request_timeout_ms", "10000",
                        "tcp_nodelay", "1",
                        // An idle live channel is pinged, not closed.
                        "websocket_timeout_ms", "30000", "enable_websocket_ping_pong", "yes", nullptr};
  mg_callbacks callbacks{};
  ctx_ = mg_start(&callbacks, this, opts);
  if (!ctx_) {
    mg_exit_library();
    throw InputError("", "--port", ports, "an address and port this machine can listen on (free, permitted)");
  }
  mg_set_request_handler(ctx_, "/", &PlaceServer::handleRequest, this);
  mg_set_websocket_handler(ctx_, "/api/live", &PlaceServer::liveConnect, &PlaceServer::liveReady,
                           &PlaceServer::liveData, &PlaceServer::liveClose, this);
  mg_server_port sp[4];
  const int n = mg_get_server_ports(ctx_, 4, sp);
  port_ = n > 0 ? sp[0].port : options.port;
}

PlaceServer::~PlaceServer() {
  mg_stop(ctx_);
  mg_exit_library();
}

std::string PlaceServer::url() const {
  const std::string host = options_.host.find(':') != std::string::npos && options_.host[0] != '['
                               ? "[" + options_.host + "]" : options_.host;
  return "http://" + host + ":" + std::to_string(port_) + "/?token=" + token_;
}

// No exception may cross civetweb's C frames: whatever escapes the handler is a 500.
int PlaceServer::handleRequest(mg_connection* c, void* self) {
  try {
    return static_cast<PlaceServer*>(self)->handle(c);
  } catch (...) {
    send(c, Answer{500, "application/json", "{\"error\":\"internal error\"}", ""});
    return 500;
  }
}

// Access: the token as query parameter, header or (for plain requests) the page's cookie. The
// live channel takes no cookie: a WebSocket handshake is not bound to its origin as a fetch is.
bool PlaceServer::allowed(const mg_connection* c, bool plainRequest) const {
  std::string given = queryVar(mg_get_request_info(c), "token");
  if (plainRequest && given.empty() && mg_get_header(c, "X-Inim-Token")) given = mg_get_header(c, "X-Inim-Token");
  if (plainRequest && given.empty() && mg_get_header(c, "Cookie")) {
    char buf[128];
    const int n = mg_get_cookie(mg_get_header(c, "Cookie"), "inim_token", buf, sizeof buf);
    if (n > 0) given.assign(buf, size_t(n));
  }
  return constantTimeEqual(given, token_);
}

// The live channel (place/place_live.h): one LiveChannel per WebSocket, kept as the
// connection's user data from the handshake to the close.
int PlaceServer::liveConnect(const mg_connection* c, void* self) {
  auto* server = static_cast<PlaceServer*>(self);
  // civetweb sends nothing for a refused handshake: the 403 or 503 is this handler's answer.
  if (!server->allowed(c, false)) return send(const_cast<mg_connection*>(c), forbidden()), 1;
  if (++server->liveChannels_ > kMaxLiveChannels) {
    --server->liveChannels_;
    send(const_cast<mg_connection*>(c), error(503, "too many live channels open (" + std::to_string(kMaxLiveChannels) + ")"));
    return 1;
  }
  return 0;
}

void PlaceServer::liveReady(mg_connection* c, void* self) {
  auto* server = static_cast<PlaceServer*>(self);
  auto write = [c](bool binary, const std::string& bytes) {
    mg_lock_connection(c);
    mg_websocket_write(c, binary ? MG_WEBSOCKET_OPCODE_BINARY : MG_WEBSOCKET_OPCODE_TEXT, bytes.data(), bytes.size());
    mg_unlock_connection(c);
  };
  mg_set_user_connection_data(c, new LiveChannel(server->session_, write, server->options_.maxBodyBytes,
                                                 std::chrono::milliseconds(server->options_.imageTimeoutMs)));
}

int PlaceServer::liveData(mg_connection* c, int bits, char* data, size_t size, void*) {
  auto* channel = static_cast<LiveChannel*>(mg_get_user_connection_data(c));
  const int opcode = bits & 0xf;
  if (opcode == MG_WEBSOCKET_OPCODE_CONNECTION_CLOSE) return 0;
  if (!channel || opcode == MG_WEBSOCKET_OPCODE_PING || opcode == MG_WEBSOCKET_OPCODE_PONG) return 1;
  if (opcode == MG_WEBSOCKET_OPCODE_TEXT) channel->onText(std::string(data, size));
  else channel->onBinary();
  return 1;
}

void PlaceServer::liveClose(const mg_connection* c, void* self) {
  delete static_cast<LiveChannel*>(mg_get_user_connection_data(c));
  --static_cast<PlaceServer*>(self)->liveChannels_;
}

int PlaceServer::handle(mg_connection* c) {
  const mg_request_info* ri = mg_get_request_info(c);
  const std::string method = ri->request_method ? ri->request_method : "", path = ri->local_uri ? ri->local_uri : "";
  Answer a;
  if (!allowed(c, true)) {
    a = forbidden();
    send(c, a);
    return a.status;
  }
  try {
    std::optional<std::string> body;
    if (method == "PUT" || method == "POST") {
      body = readBody(c, options_.maxBodyBytes);
      if (!body) throw InputError("request body", "", "over " + std::to_string(options_.maxBodyBytes) + " bytes",
                                  "a body of at most 1 MiB");
    }
    const auto timeout = std::chrono::milliseconds(options_.imageTimeoutMs);
    auto only = [&](const char* m) {
      if (method != m) throw MethodNotAllowed{m};
    };
    if (path == "/" || path == "/index.html") {
      only("GET");
      a = staticFile("index.html", "text/html; charset=utf-8");
      a.headers = "Set-Cookie: inim_token=" + token_ + "; Path=/; HttpOnly; SameSite=Strict\r\n";
    } else if (path == "/place.js") {
      only("GET"), a = staticFile("place.js", "text/javascript; charset=utf-8");
    } else if (path == "/place.css") {
      only("GET"), a = staticFile("place.css", "text/css; charset=utf-8");
    } else if (path == "/api/info") {
      only("GET"), a = json(session_.info());
    } else if (path == "/api/state") {
      if (method == "GET") a = json(session_.state());
      else only("PUT"), a = json(session_.putState(*body));
    } else if (path == "/api/preview") {
      only("GET");
      const uint64_t level = queryNumber(ri, "level");
      if (level > 2) throw InputError("request", "level", std::to_string(level), "0, 1 or 2");
      a = imageAnswer(session_.image(ImageKind(level), queryNumber(ri, "revision"), timeout), int(level));
    } else if (path == "/api/diagram") {
      only("GET");
      a = imageAnswer(session_.image(ImageKind::Diagram, queryNumber(ri, "revision"), timeout), -1);
    } else if (path == "/api/write" || path == "/api/predict") {
      only("POST");
      const uint64_t id = session_.jobs().submit(parseJsonText(*body, "request body"), session_.jobInput(),
                                                 path == "/api/predict");
      a = json({{"job", id}}, 202);
    } else if (path == "/api/jobs") {
      only("GET"), a = json(session_.jobs().list());
    } else if (path.rfind("/api/jobs/", 0) == 0) {
      only("GET");
      uint64_t id = 0;
      const std::string s = path.substr(10);
      auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), id);
      auto j = (ec == std::errc() && p == s.data() + s.size()) ? session_.jobs().get(id) : std::nullopt;
      a = j ? json(*j) : error(404, "no job " + s.substr(0, 40));
    } else if (path == "/api/file") {
      only("GET");
      const std::string name = sanitizeOutputName(queryVar(ri, "name"));
      if (!isFileKind(name, FileKind::Png))
        throw InputError("request", "name", "\"" + name + "\"", "the name of a .png in the output folder");
      const std::string bytes = readFile(session_.outDir() + "/" + name);
      a = bytes.empty() ? error(404, "no file " + name) : Answer{200, "image/png", bytes, ""};
    } else if (path == "/api/latency") {
      only("GET"), a = json(session_.latency());
    } else {
      a = error(404, "no such path: " + path.substr(0, 100));
    }
  } catch (const InputError& e) {
    a = error(400, e.what());
  } catch (const MethodNotAllowed& e) {
    a = error(405, method.substr(0, 10) + " not allowed; " + path.substr(0, 100) + " takes " + e.allowed);
  } catch (const std::exception& e) {
    a = error(500, e.what());
  }
  send(c, a);
  return a.status;
}

}  // namespace inim
