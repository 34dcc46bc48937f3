// libFuzzer target: a Zemax spectral source file as `inim triads form` reads it (readSdf): the
// header, the ray count against the file size, and every ray through the door (fuzz/README.md).
#include "triads/sdf.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return inim::fuzz::fuzzLoad(data, size, ".sdf", [](const std::string& p) { (void)inim::readSdf(p); });
}
