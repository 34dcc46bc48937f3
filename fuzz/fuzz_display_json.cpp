// libFuzzer target: a display JSON (loadDisplay: panel and MLA by name or path) (fuzz/README.md).
#include "display/display.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return inim::fuzz::fuzzLoad(data, size, ".json", [](const std::string& p) { (void)inim::loadDisplay(p); });
}
