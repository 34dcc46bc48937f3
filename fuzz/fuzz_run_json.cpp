// libFuzzer target: a run file (loadRunFile) (fuzz/README.md).
#include "field/placement.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return inim::fuzz::fuzzLoad(data, size, ".json", [](const std::string& p) { (void)inim::loadRunFile(p); });
}
