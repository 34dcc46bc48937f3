// libFuzzer target: a NumPy .npy array (readNpy) (fuzz/README.md).
#include "core/npy.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return inim::fuzz::fuzzLoad(data, size, ".npy", [](const std::string& p) { (void)inim::readNpy(p); });
}
