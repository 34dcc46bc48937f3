#pragma once
// Helpers shared by the camera tests.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "camera/lens_system.h"
#include "core/error.h"
#include "expect_input_error.h"
#include "scratch_dir.h"

namespace inim::test {

// A scratch file for the tests of this process (the folder is removed when it ends).
inline std::string scratchFile(const std::string& name, const std::string& text) {
  static ScratchDir scratch("test_camera");
  std::string p = scratch.path(name);
  std::ofstream(p) << text;
  return p;
}


// A single lens in air: front radius r1, back radius r2 (0 = flat), centre thickness t,
// constant index n, clear aperture diameter d; the stop sits just in front (flat, t 0).
inline LensSystem singlet(double r1, double r2, double t, double n, double d, double k1 = 0.0, double k2 = 0.0) {
  std::vector<LensSurface> s(3);
  s[0].isStop = true;
  s[0].apertureMm = d;
  s[0].thicknessMm = 0.0;
  s[1].radiusMm = r1;
  s[1].conic = k1;
  s[1].thicknessMm = t;
  s[1].apertureMm = d;
  s[1].medium = std::make_shared<ConstantIor>(float(n));
  s[2].radiusMm = r2;
  s[2].conic = k2;
  s[2].apertureMm = d;
  LensSystem lens(s, "singlet");
  lens.validate();
  return lens;
}

}  // namespace inim::test
