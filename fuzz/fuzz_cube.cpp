// libFuzzer target: a .cube 3D LUT (readCube) (fuzz/README.md).
#include "calibration/lut_io.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return inim::fuzz::fuzzLoad(data, size, ".cube", [](const std::string& p) { (void)inim::readCube(p); });
}
