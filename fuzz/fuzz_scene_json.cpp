// libFuzzer target: an analytic scene JSON (loadSceneDescription) (fuzz/README.md).
#include "scene/scene_loader.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return inim::fuzz::fuzzLoad(data, size, ".json", [](const std::string& p) { (void)inim::loadSceneDescription(p); });
}
