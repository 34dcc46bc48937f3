// libFuzzer target: a lens prescription as JSON (loadLens) (fuzz/README.md).
#include "camera/lens_loader.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return inim::fuzz::fuzzLoad(data, size, ".json", [](const std::string& p) { (void)inim::loadLens(p); });
}
