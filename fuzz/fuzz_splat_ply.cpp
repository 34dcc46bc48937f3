// libFuzzer target: a Gaussian-splat scene as .ply (loadGaussians; fuzz/README.md).
#include "fuzz_input.h"
#include "splats/splat_loaders.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return inim::fuzz::fuzzLoad(data, size, ".ply", [](const std::string& p) { (void)inim::loadGaussians(p); });
}
