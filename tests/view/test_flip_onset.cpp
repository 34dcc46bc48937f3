// Physics that must come out of the simulation: turning the display, the view through a
// lenslet flips to the neighbouring elemental image at half the viewing angle,
// psi / 2 = atan(P / (2 g)) (DESIGN.md 4b), within 10%, for the ideal and the real MLA.
#include <gtest/gtest.h>

#include <cmath>

#include "core/output_file.h"
#include "display/display.h"
#include "display/ei_layout.h"
#include "mla/real_mla.h"
#include "view/ideal_mla.h"

using namespace inim;

namespace {

// Fraction of the light that a parallel bundle at angle theta (degrees, in the x-z plane,
// coming from the +x side) through lenslet (k, l) delivers into that lenslet's own EI.
double ownEiFraction(const MlaModel& mla, const EiLayout& L, double pitch, int k, int l, double thetaDeg) {
  const double th = thetaDeg * M_PI / 180.0;
  const Vec3 d(float(-std::sin(th)), 0.0f, float(-std::cos(th)));
  const double cx = L.lensX[size_t(k)], cy = L.lensY[size_t(l)];
  const double eiX = L.eiCentreX(k), halfEi = 0.5 * L.eiW * L.pixelMm;
  const int n = 48;
  double own = 0.0, all = 0.0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Point3 target(float(cx + ((i + 0.5) / n - 0.5) * pitch), float(cy + ((j + 0.5) / n - 0.5) * pitch), 0.0f);
      const float s = (mla.frontZ() + 1.0f) / std::abs(d.z);
      Ray r{target - s * d, d};
      Rng rng = Rng::forSample(3, uint64_t(j) * n + i);
      PanelArrival a;
      if (!mla.traceToPanel(r, 550.0f, rng, a)) continue;
      all += a.throughput;
      if (std::abs(a.p.x - eiX) <= halfEi) own += a.throughput;
    }
  return all > 0.0 ? own / all : 0.0;
}

// The first angle (0.05 degree steps) at which less than half the light comes from the own EI.
double flipAngle(const MlaModel& mla, const EiLayout& L, double pitch) {
  const int k = L.eiCols / 2, l = L.eiRows / 2;
  for (double t = 0.0; t < 20.0; t += 0.05)
    if (ownEiFraction(mla, L, pitch, k, l, t) < 0.5) return t;
  return 90.0;
}

}  // namespace

TEST(FlipOnset, MatchesHalfViewingAngleForIdealAndRealMla) {
  Display d = loadDisplay(defaultDisplayPath());
  EiLayout L = computeLayout(d);
  const double g = d.reconstructionGapMm, P = d.mla.pitchMm;
  const double predicted = std::atan(P / (2.0 * g)) * 180.0 / M_PI;  // psi / 2

  IdealLensletMla ideal(L, P, lensletFocus(d.mla).focalLengthMm, g);
  const double idealFlip = flipAngle(ideal, L, P);
  auto real = makeRealMla(d, L, g);
  const double realFlip = flipAngle(*real, L, P);
  RecordProperty("predicted_deg", std::to_string(predicted));
  RecordProperty("ideal_deg", std::to_string(idealFlip));
  RecordProperty("real_deg", std::to_string(realFlip));
  std::printf("flip onset at g = %.2f mm: predicted psi/2 = %.3f deg; ideal MLA %.2f deg; real MLA %.2f deg\n", g,
              predicted, idealFlip, realFlip);
  EXPECT_NEAR(idealFlip, predicted, 0.10 * predicted);
  EXPECT_NEAR(realFlip, predicted, 0.10 * predicted);
  // Below the flip the lenslet shows its own EI almost entirely.
  EXPECT_GT(ownEiFraction(*real, L, P, L.eiCols / 2, L.eiRows / 2, 0.0), 0.95);
}
