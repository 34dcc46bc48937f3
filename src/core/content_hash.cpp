#include "core/content_hash.h"

#include <openssl/evp.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "core/error.h"

namespace inim {

struct Sha256::State {
  EVP_MD_CTX* ctx = nullptr;
};

Sha256::Sha256() : state_(std::make_unique<State>()) {
  state_->ctx = EVP_MD_CTX_new();
  if (!state_->ctx || EVP_DigestInit_ex(state_->ctx, EVP_sha256(), nullptr) != 1)
    throw std::runtime_error("SHA-256: OpenSSL could not start a digest");
}

Sha256::~Sha256() { EVP_MD_CTX_free(state_->ctx); }

void Sha256::add(const void* bytes, size_t n) {
  if (n > 0 && EVP_DigestUpdate(state_->ctx, bytes, n) != 1) throw std::runtime_error("SHA-256: update failed");
}

void Sha256::add(std::string_view text) {
  addValue(uint64_t(text.size()));
  add(text.data(), text.size());
}

std::string Sha256::hex() {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int n = 0;
  if (EVP_DigestFinal_ex(state_->ctx, digest, &n) != 1) throw std::runtime_error("SHA-256: final failed");
  static const char* digits = "0123456789abcdef";
  std::string out;
  for (unsigned int i = 0; i < n; ++i) {
    out += digits[digest[i] >> 4];
    out += digits[digest[i] & 15];
  }
  return out;
}

std::string fileSha256(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "(unreadable)", "a readable file");
  Sha256 h;
  std::vector<char> buf(1 << 20);
  while (in) {
    in.read(buf.data(), std::streamsize(buf.size()));
    h.add(buf.data(), size_t(in.gcount()));
  }
  if (in.bad()) throw InputError(path, "", "(read error)", "a readable file");
  return h.hex();
}

std::vector<std::string> cacheDirs() {
  namespace fs = std::filesystem;
  std::vector<std::string> dirs;
  auto env = [](const char* name) -> std::string {
    const char* v = std::getenv(name);
    return v && *v ? v : "";
  };
  if (auto d = env("INIM_CACHE_DIR"); !d.empty()) dirs.push_back(d);
  if (auto d = env("XDG_CACHE_HOME"); !d.empty()) dirs.push_back((fs::path(d) / "inim").string());
  if (auto d = env("HOME"); !d.empty()) dirs.push_back((fs::path(d) / ".cache" / "inim").string());
  std::error_code ec;
  const fs::path tmp = fs::temp_directory_path(ec);
  dirs.push_back(((ec ? fs::path("/tmp") : tmp) / "inim-cache").string());
  return dirs;
}

const std::string& programSha256() {
  static const std::string hash = fileSha256("/proc/self/exe");
  return hash;
}

}  // namespace inim
