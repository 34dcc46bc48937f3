// libFuzzer target: a camera description JSON (loadCameraDescription) (fuzz/README.md).
#include "camera/camera_config.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return inim::fuzz::fuzzLoad(data, size, ".json", [](const std::string& p) { (void)inim::loadCameraDescription(p); });
}
