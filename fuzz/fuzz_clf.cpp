// libFuzzer target: an ACES/OCIO Common LUT Format file (readClf) (fuzz/README.md).
#include "calibration/lut_io.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return inim::fuzz::fuzzLoad(data, size, ".clf", [](const std::string& p) { (void)inim::readClf(p); });
}
