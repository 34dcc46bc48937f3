// libFuzzer target: a trained radiance field .inimrf (RadianceField::load) (fuzz/README.md).
#include "radiance/radiance_field.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return inim::fuzz::fuzzLoad(data, size, ".inimrf", [](const std::string& p) { (void)inim::RadianceField::load(p); });
}
