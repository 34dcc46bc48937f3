// The measured-OLED variant of the paper prototype: the same display with the primaries read
// from spectra/oled_iphone13pro_rgb.csv. Peaks and widths are measured on the loaded spectra
// and compared with the values the data's source states (peaks 622/526/461 nm, blue FWHM
// about 20.5 nm); the white of drive (1, 1, 1) is the measured white the CSV was balanced to.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "core/output_file.h"
#include "display/display.h"
#include "spectral/cie.h"

using namespace inim;

namespace {

const char* kVariant = "optics/displays/paper-prototype-measured-oled.json";

struct PeakAndWidth {
  double peakNm = 0.0, fwhmNm = 0.0;
};

// The arg-max on a 0.01 nm grid, and the width between the half-maximum crossings nearest to
// it on either side (linear between grid points; the tails' noise stays far below half).
PeakAndWidth peakAndWidth(const Spectrum& s) {
  const double step = 0.01, lo = 360.0, hi = 830.0;
  const int n = int(std::lround((hi - lo) / step));
  auto at = [&](int i) { return double(s(float(lo + i * step))); };
  int peak = 0;
  for (int i = 1; i <= n; ++i)
    if (at(i) > at(peak)) peak = i;
  const double half = 0.5 * at(peak);
  auto crossing = [&](int direction) {
    int i = peak;
    while (i + direction >= 0 && i + direction <= n && at(i + direction) >= half) i += direction;
    const double a = at(i), b = at(i + direction);  // a >= half > b
    return lo + (i + direction * (a - half) / (a - b)) * step;
  };
  return {lo + peak * step, crossing(+1) - crossing(-1)};
}

// (x, y) of an XYZ.
std::pair<double, double> chromaticity(const Vec3d& xyz) {
  const double sum = xyz.x + xyz.y + xyz.z;
  return {xyz.x / sum, xyz.y / sum};
}

}  // namespace

TEST(MeasuredOled, VariantIsThePrototypeWithCsvPrimaries) {
  const Display v = loadDisplay(dataPath(kVariant));
  const Display p = loadDisplay(defaultDisplayPath());
  EXPECT_EQ(v.panel.widthPx, p.panel.widthPx);
  EXPECT_EQ(v.panel.heightPx, p.panel.heightPx);
  EXPECT_EQ(v.panel.pixelPitchMm, p.panel.pixelPitchMm);
  EXPECT_EQ(v.panel.peakLuminanceCdM2, p.panel.peakLuminanceCdM2);
  EXPECT_EQ(v.panel.subpixels.type, p.panel.subpixels.type);
  EXPECT_EQ(v.mla.pitchMm, p.mla.pitchMm);
  EXPECT_EQ(v.mla.focalLengthMm, p.mla.focalLengthMm);
  EXPECT_EQ(v.generationGapMm, p.generationGapMm);
  EXPECT_EQ(v.reconstructionGapMm, p.reconstructionGapMm);
  EXPECT_EQ(v.eiCols, p.eiCols);
  EXPECT_EQ(v.eiRows, p.eiRows);
  EXPECT_EQ(v.eiWidthPx, p.eiWidthPx);
  for (int c = 0; c < kNumPrimaries; ++c) {
    EXPECT_EQ(v.panel.primaries[size_t(c)].kind, PrimarySpec::Kind::Csv) << channelName(c);
    EXPECT_EQ(v.panel.primaries[size_t(c)].scale, 1.0) << channelName(c);
  }
}

TEST(MeasuredOled, PeaksAndBlueWidthAreTheMeasuredOnes) {
  const Display v = loadDisplay(dataPath(kVariant));
  const double expectedPeak[3] = {622.0, 526.0, 461.0};
  PeakAndWidth measured[3];
  for (int c = 0; c < kNumPrimaries; ++c) {
    SCOPED_TRACE(channelName(c));
    measured[c] = peakAndWidth(*primarySpectrum(v.panel.primaries[size_t(c)]));
    EXPECT_NEAR(measured[c].peakNm, expectedPeak[c], 2.0);
    EXPECT_NEAR(primaryPeakNm(v.panel.primaries[size_t(c)]), measured[c].peakNm, 0.5);  // triads' default
  }
  EXPECT_NEAR(measured[2].fwhmNm, 20.5, 1.5);
  // Narrower than the blue placeholder (30 nm), as measured OLED blues are.
  const Display p = loadDisplay(defaultDisplayPath());
  EXPECT_LT(measured[2].fwhmNm, p.panel.primaries[2].fwhmNm - 5.0);
}

// The CSV's channels were scaled so that their sum fits the measured full-white patch
// (x 0.3115, y 0.3226, stated in its header); with scale 1 the panel white is that white.
TEST(MeasuredOled, WhiteIsTheMeasuredWhite) {
  const Display v = loadDisplay(dataPath(kVariant));
  Vec3d white(0.0);
  for (int c = 0; c < kNumPrimaries; ++c) white += spectrumToXYZ(*primarySpectrum(v.panel.primaries[size_t(c)]));
  const auto [x, y] = chromaticity(white);
  EXPECT_NEAR(x, 0.3115, 0.001);
  EXPECT_NEAR(y, 0.3226, 0.001);
}
