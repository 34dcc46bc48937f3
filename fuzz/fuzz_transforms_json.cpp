// libFuzzer target: a NeRF transforms.json (readTransformsJson) (fuzz/README.md).
#include "dataset/transforms_json.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return inim::fuzz::fuzzLoad(data, size, ".json", [](const std::string& p) { (void)inim::readTransformsJson(p); });
}
