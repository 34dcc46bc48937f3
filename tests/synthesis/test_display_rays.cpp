// SynthesisSettings::displayRays: precomputed display rays (e.g. real-lens rays) replace the
// pinhole rays of the synthesis.
#include <gtest/gtest.h>

#include <cmath>

#include "rays/pinhole_rays.h"
#include "synth_test_util.h"
#include "synthesis/eia_synthesis.h"

using namespace inim;
using namespace synth_test;

namespace {

MockField softEmitter() {
  return MockField({{{0.2, -0.1, 5.0}, 2.0, Vec3(0.7f, 0.4f, 0.2f), 1.2, nullptr}}, FieldEncoding::RGB);
}

double maxAbsDiff(const std::vector<float>& a, const std::vector<float>& b) {
  double m = 0.0;
  for (size_t i = 0; i < a.size(); ++i) m = std::max(m, double(std::abs(a[i] - b[i])));
  return m;
}

}  // namespace

// The pinhole rays passed in explicitly give the synthesis' own result (up to their float
// storage); other rays give another EIA; a ray set of the wrong size is an input error.
TEST(EiaSynthesis, PrecomputedDisplayRaysReplacePinholeRays) {
  Display disp = squareDisplay({.cols = 7, .rows = 5, .eiPx = 9});
  EiLayout L = computeLayout(disp);
  MockField f = softEmitter();
  SynthesisSettings s = quietSettings(40.0);
  s.spp = 1;
  SynthesisResult ref = synthesizeEia(L, disp.panel, f, s);

  RaySet pin = generatePinholeRays(L);
  s.displayRays = &pin;
  SynthesisResult same = synthesizeEia(L, disp.panel, f, s);
  ASSERT_EQ(same.drive.size(), ref.drive.size());
  EXPECT_LT(maxAbsDiff(same.drive, ref.drive), 1e-5);

  // Every ray tilted by 2 degrees about y: the EIA changes.
  RaySet tilted = pin;
  const double c = std::cos(0.035), sn = std::sin(0.035);
  for (size_t i = 0; i < tilted.size(); ++i) {
    const double x = tilted.dx[i], z = tilted.dz[i];
    tilted.dx[i] = float(c * x + sn * z);
    tilted.dz[i] = float(-sn * x + c * z);
  }
  s.displayRays = &tilted;
  SynthesisResult other = synthesizeEia(L, disp.panel, f, s);
  EXPECT_GT(maxAbsDiff(other.drive, ref.drive), 1e-2);

  RaySet few = pin;
  few.ox.pop_back();
  s.displayRays = &few;
  InputError e = expectInputError([&] { (void)synthesizeEia(L, disp.panel, f, s); });
  EXPECT_EQ(e.key(), "display rays");
}
