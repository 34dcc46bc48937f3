// libFuzzer target: Zemax ray text as the paper's macro writes it (readZemaxRayText) (fuzz/README.md).
#include "rays/zemax_ray_text.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return inim::fuzz::fuzzLoad(data, size, ".txt", [](const std::string& p) { (void)inim::readZemaxRayText(p); });
}
