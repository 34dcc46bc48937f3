#pragma once
// What every fuzz target shares. inim's loaders read paths (as the CLI gives them), so each input
// is written to one temporary file per process, with the extension the loader dispatches on, and
// the loader is run on it. Bad input must end in an InputError (the CLI's exit status 2); any
// other exception, crash, leak or undefined behaviour is a finding: it propagates to libFuzzer.
//
//   extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
//     return fuzzLoad(data, size, ".json", [](const std::string& p) { loadDisplay(p); });
//   }
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/error.h"
#include "core/size_budget.h"

namespace inim::fuzz {

inline std::string inputPath(const char* extension) {
  const char* dir = std::getenv("TMPDIR");
  return std::string(dir && *dir ? dir : "/tmp") + "/inim-fuzz-" + std::to_string(getpid()) + extension;
}

// Below libFuzzer's 3 GiB memory limit, so that a size a file declares is refused by inim's
// budget (core/size_budget.h) before the fuzzer would report it as running out of memory.
constexpr uint64_t kFuzzMemoryLimitBytes = uint64_t(1) << 30;

template <class Load>
int fuzzLoad(const uint8_t* data, size_t size, const char* extension, Load load) {
  static const std::string path = inputPath(extension);
  static const bool limited = (setMemoryLimitBytes(kFuzzMemoryLimitBytes), true);
  (void)limited;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) std::abort();
  if (size > 0 && std::fwrite(data, 1, size, f) != size) std::abort();
  std::fclose(f);
  try {
    load(path);
  } catch (const InputError&) {
    // bad input, refused as promised
  }
  return 0;
}

}  // namespace inim::fuzz
