// libFuzzer target: a Middlebury multi-view _par.txt (readMiddleburyPar) (fuzz/README.md).
#include "dataset/middlebury.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return inim::fuzz::fuzzLoad(data, size, ".txt", [](const std::string& p) { (void)inim::readMiddleburyPar(p); });
}
