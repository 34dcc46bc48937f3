// libFuzzer target: an EIA given to `inim view` or `inim triads export` as .exr (readImage with
// non-finite values refused, as the EIA reader calls it) (fuzz/README.md).
#include "core/image.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return inim::fuzz::fuzzLoad(data, size, ".exr", [](const std::string& p) { (void)inim::readImage(p, true); });
}
