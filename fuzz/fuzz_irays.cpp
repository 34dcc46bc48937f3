// libFuzzer target: inim's binary ray file .irays (readRayBinary) (fuzz/README.md).
#include "rays/ray_binary.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return inim::fuzz::fuzzLoad(data, size, ".irays", [](const std::string& p) { (void)inim::readRayBinary(p); });
}
