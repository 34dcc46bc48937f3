// libFuzzer target: a Gaussian-splat scene as .splat (loadGaussians; fuzz/README.md).
#include "fuzz_input.h"
#include "splats/splat_loaders.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return inim::fuzz::fuzzLoad(data, size, ".splat", [](const std::string& p) { (void)inim::loadGaussians(p); });
}
