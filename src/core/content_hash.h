#pragma once
// SHA-256 (OpenSSL's libcrypto) for content-addressed caches: a key is the hash of everything
// a result depends on, so a cached result is found again only for the same inputs.
//
//   Sha256 h;
//   h.add("reference v1");
//   h.addValue(spp);
//   std::string key = h.hex();  // 64 hex digits
#include <cstddef>
#include <memory>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace inim {

class Sha256 {
 public:
  Sha256();
  ~Sha256();
  Sha256(const Sha256&) = delete;
  Sha256& operator=(const Sha256&) = delete;

  void add(const void* bytes, size_t n);
  // The text with its length first, so that "ab" + "c" and "a" + "bc" differ.
  void add(std::string_view text);
  template <typename T>
  void addValue(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    add(&v, sizeof(T));
  }
  // The hash of what was added (the object is finished after this).
  std::string hex();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// inim's cache folders, the preferred first: $INIM_CACHE_DIR, $XDG_CACHE_HOME/inim,
// ~/.cache/inim (each when its variable is set and not empty), then the temporary folder's
// inim-cache.
std::vector<std::string> cacheDirs();

// The hash of a file's bytes (InputError naming the file when it cannot be read).
std::string fileSha256(const std::string& path);

// The hash of the running program (/proc/self/exe), once per process: a rebuild changes every
// key, so no result of other code is ever read back.
const std::string& programSha256();

}  // namespace inim
