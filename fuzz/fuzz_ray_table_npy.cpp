// libFuzzer target: a query-ray table as `inim query` and `inim eia --field-colors` read it
// (readRayTable, .npy): every row through the ray tracer's door (fuzz/README.md).
#include "field/ray_table.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return inim::fuzz::fuzzLoad(data, size, ".npy", [](const std::string& p) { (void)inim::readRayTable(p, 1); });
}
