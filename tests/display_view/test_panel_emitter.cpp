// PanelEmitter: subpixel geometry, black matrix, area normalisation to the panel white, drive
// values, angular profile, cover glass (refraction offset and Fresnel), bad input, and the
// estimators' lookups: the exact box averages (all channels and one), the channel lookup.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>

#include "camera/lens_system.h"
#include "core/error.h"
#include "core/rng.h"
#include "spectral/cie.h"
#include "spectral/dispersion.h"
#include "display_view/panel_emitter.h"
#include "view_test_util.h"

using namespace inim;
using namespace view_test;

namespace {

// Display-frame point of continuous panel pixel coordinates (u right, v down from the top-left).
Point3 panelPoint(const EiLayout& L, double u, double v, double g) {
  const double uOff = 0.5 * L.eiaW + L.panelCol0, vOff = 0.5 * L.eiaH + L.panelRow0;
  return Point3(float((u - uOff) * L.pixelMm), float((vOff - v) * L.pixelMm), float(-g));
}

const Vec3 kDown(0.0f, 0.0f, -1.0f);

// XYZ of the emission averaged over an area of the panel: a midpoint grid of n x n points
// over [u0, u0 + w] x [v0, v0 + h] (pixel units), integrated over 360-830 nm at 1 nm.
Vec3d averageXyz(const PanelEmitter& e, const EiLayout& L, double u0, double v0, double w, double h, int n) {
  std::vector<double> chan(3, 0.0);  // mean weight per channel
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Point3 p = panelPoint(L, u0 + (i + 0.5) * w / n, v0 + (j + 0.5) * h / n, e.gapMm());
      const PanelEmission em = e.emit(p, kDown, 550.0f);
      if (em.channel >= 0) chan[size_t(em.channel)] += em.weight;
    }
  for (auto& c : chan) c /= double(n) * n;
  Vec3d xyz(0.0);
  for (int l = 360; l <= 830; ++l) {
    double L0 = 0.0;
    for (int c = 0; c < 3; ++c) L0 += chan[size_t(c)] * e.channelSpectrum(c, float(l));
    const double w = (l == 360 || l == 830) ? 0.5 : 1.0;
    xyz += w * L0 * Vec3d(cie::X()(float(l)), cie::Y()(float(l)), cie::Z()(float(l)));
  }
  return xyz / cie::yIntegral();
}

}  // namespace

TEST(PanelEmitter, FullWhitePixelAveragesToPanelWhite) {
  Display d = smallDisplay(4, 3, 6, 0.05, 0.3, 1.0, 1.2);
  const EiLayout L = computeLayout(d);
  PanelEmitter e(d.panel, L, uniformEia(L, 1, 1, 1), "white.exr", 1.2);
  const Vec3d white = e.whiteXyz();
  EXPECT_NEAR(white.y, d.panel.peakLuminanceCdM2, 1e-6 * d.panel.peakLuminanceCdM2);
  // The stripe's edges sit on multiples of 1/30 px: a 600 x 600 midpoint grid counts areas exactly.
  const Vec3d avg = averageXyz(e, L, 7.0, 5.0, 1.0, 1.0, 600);
  std::printf("[ measured ] stripe pixel average / panel white XYZ: %.6f %.6f %.6f\n", avg.x / white.x, avg.y / white.y,
              avg.z / white.z);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(avg[k] / white[k], 1.0, 1e-3) << "XYZ component " << k;
  // The same white from the other pixel of the panel.
  const Vec3d avg2 = averageXyz(e, L, 20.0, 11.0, 1.0, 1.0, 600);
  EXPECT_NEAR(avg2.y / white.y, 1.0, 1e-3);
}

TEST(PanelEmitter, DiamondTileAveragesToPanelWhite) {
  Display d = smallDisplay(4, 3, 6, 0.05, 0.3, 1.0, 1.2);
  d.panel.subpixels = diamondLayout(0.8);
  const EiLayout L = computeLayout(d);
  PanelEmitter e(d.panel, L, uniformEia(L, 1, 1, 1), "white.exr", 1.2);
  const Vec3d white = e.whiteXyz();
  const Vec3d avg = averageXyz(e, L, 6.0, 4.0, 2.0, 2.0, 1600);
  std::printf("[ measured ] diamond tile average / panel white XYZ: %.6f %.6f %.6f\n", avg.x / white.x, avg.y / white.y,
              avg.z / white.z);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(avg[k] / white[k], 1.0, 2e-3) << "XYZ component " << k;
}

TEST(PanelEmitter, BlackMatrixEmitsNothing) {
  Display d = smallDisplay(4, 3, 6, 0.05, 0.3, 1.0, 1.2);
  const EiLayout L = computeLayout(d);
  PanelEmitter e(d.panel, L, uniformEia(L, 1, 1, 1), "white.exr", 1.2);
  // Fill 0.8: margins of 0.1 of each stripe's width and of the pixel height.
  for (auto uv : {std::pair{8.01, 6.5}, std::pair{8.5, 6.05}, std::pair{8.5, 6.97}, std::pair{8.34, 6.5}}) {
    const Point3 p = panelPoint(L, uv.first, uv.second, 1.2);
    const PanelEmission em = e.emit(p, kDown, 550.0f);
    EXPECT_EQ(em.channel, -1) << uv.first << ", " << uv.second;
    EXPECT_EQ(e.radiance(p, kDown, 530.0f), 0.0f);
  }
  // Off the panel: nothing either.
  EXPECT_EQ(e.emit(panelPoint(L, -0.5, 3.0, 1.2), kDown, 550.0f).channel, -1);
  EXPECT_EQ(e.emit(panelPoint(L, 3.0, L.panelH + 0.5, 1.2), kDown, 550.0f).channel, -1);
}

TEST(PanelEmitter, StripeRedSubpixelEmitsOnlyRedPrimary) {
  Display d = smallDisplay(4, 3, 6, 0.05, 0.3, 1.0, 1.2);
  const EiLayout L = computeLayout(d);
  Image eia = uniformEia(L, 0.3f, 0.6f, 0.9f);
  PanelEmitter e(d.panel, L, eia, "eia.exr", 1.2);
  const SpectrumPtr red = primarySpectrum(d.panel.primaries[0]);
  const double K = e.areaFactor(0) * e.luminanceScale();
  EXPECT_NEAR(e.areaFactor(0), 1.0 / (0.8 * 0.8 / 3.0), 1e-9);
  for (double u : {1.0 / 6.0, 0.05, 0.29}) {  // centre and near both edges of the R stripe
    const Point3 p = panelPoint(L, 9.0 + u, 4.5, 1.2);
    const PanelEmission em = e.emit(p, kDown, 550.0f);
    ASSERT_EQ(em.channel, 0);
    EXPECT_FLOAT_EQ(em.weight, 0.3f);
    for (float l : {450.0f, 530.0f, 600.0f, 625.0f, 700.0f})
      EXPECT_NEAR(e.radiance(p, kDown, l), 0.3 * K * (*red)(l), 1e-6 * K) << l;
  }
  // Green and blue stripes of the same pixel.
  EXPECT_EQ(e.emit(panelPoint(L, 9.5, 4.5, 1.2), kDown, 550.0f).channel, 1);
  EXPECT_FLOAT_EQ(e.emit(panelPoint(L, 9.5, 4.5, 1.2), kDown, 550.0f).weight, 0.6f);
  EXPECT_EQ(e.emit(panelPoint(L, 9.83, 4.5, 1.2), kDown, 550.0f).channel, 2);
}

TEST(PanelEmitter, PixelAddressingFollowsTheLayout) {
  Display d = smallDisplay(4, 3, 6, 0.05, 0.3, 1.0, 1.2);
  const EiLayout L = computeLayout(d);
  Image eia = uniformEia(L, 0, 0, 0);
  eia.at(L.panelCol0 + 5, L.panelRow0 + 2, 1) = 1.0f;  // one green subpixel lit
  PanelEmitter e(d.panel, L, eia, "eia.exr", 1.2);
  // EIA pixel (5, 2) has its centre at x = (5.5 - W/2) p, y = (H/2 - 2.5) p.
  const double x = L.pixelCentreX(5), y = L.pixelCentreY(2);
  PanelEmission em = e.lookup(x, y);
  EXPECT_EQ(em.channel, 1);
  EXPECT_EQ(em.weight, 1.0f);
  EXPECT_EQ(e.lookup(x + L.pixelMm, y).weight, 0.0f);
  EXPECT_EQ(e.lookup(x, y - L.pixelMm).weight, 0.0f);
  // An EIA-area-sized image is placed the same way.
  Image area(L.eiaW, L.eiaH, {"R", "G", "B"});
  area.at(5, 2, 1) = 1.0f;
  PanelEmitter e2(d.panel, L, area, "area.exr", 1.2);
  EXPECT_EQ(e2.lookup(x, y).weight, 1.0f);
}

TEST(PanelEmitter, CustomPolygonLayout) {
  Display d = smallDisplay(4, 3, 6, 0.05, 0.3, 1.0, 1.2);
  SubpixelLayout s;
  s.type = "custom";
  s.tileW = 1;
  s.tileH = 1;
  s.subpixels = {{0, {{0.0, 0.0}, {0.5, 0.0}, {0.0, 0.5}}},      // red triangle, top-left
                 {1, {{1.0, 0.0}, {1.0, 1.0}, {0.5, 0.5}}},      // green triangle, right
                 {2, {{0.0, 1.0}, {0.4, 0.6}, {0.6, 1.0}}}};     // blue triangle, bottom
  d.panel.subpixels = s;
  const EiLayout L = computeLayout(d);
  PanelEmitter e(d.panel, L, uniformEia(L, 1, 1, 1), "eia.exr", 1.2);
  EXPECT_EQ(e.emit(panelPoint(L, 3.1, 2.1, 1.2), kDown, 550.0f).channel, 0);
  EXPECT_EQ(e.emit(panelPoint(L, 3.3, 2.3, 1.2), kDown, 550.0f).channel, -1);  // beyond the hypotenuse
  EXPECT_EQ(e.emit(panelPoint(L, 3.9, 2.5, 1.2), kDown, 550.0f).channel, 1);
  EXPECT_EQ(e.emit(panelPoint(L, 3.3, 2.95, 1.2), kDown, 550.0f).channel, 2);
  EXPECT_NEAR(e.areaFactor(0), 1.0 / 0.125, 1e-12);
}

TEST(PanelEmitter, AngularProfiles) {
  Display d = smallDisplay(4, 3, 6, 0.05, 0.3, 1.0, 1.2);
  const EiLayout L = computeLayout(d);
  const Point3 p = panelPoint(L, 9.5, 4.5, 1.2);
  const float th = 0.5f;
  const Vec3 dir(std::sin(th), 0.0f, -std::cos(th));
  PanelEmitter lam(d.panel, L, uniformEia(L, 1, 1, 1), "eia.exr", 1.2);
  EXPECT_FLOAT_EQ(lam.emit(p, dir, 550.0f).weight, lam.emit(p, kDown, 550.0f).weight);  // Lambertian
  EmitterSettings s;
  s.cosExponent = 3.0;
  PanelEmitter cosn(d.panel, L, uniformEia(L, 1, 1, 1), "eia.exr", 1.2, s);
  EXPECT_NEAR(cosn.emit(p, dir, 550.0f).weight, std::pow(std::cos(th), 3.0f), 1e-6);
  EXPECT_FLOAT_EQ(cosn.emit(p, kDown, 550.0f).weight, 1.0f);
  d.panel.angularProfile = "uniform";
  PanelEmitter uni(d.panel, L, uniformEia(L, 1, 1, 1), "eia.exr", 1.2);
  EXPECT_NEAR(uni.emit(p, dir, 550.0f).weight, 1.0f / std::cos(th), 1e-5);
  // Relative units: the panel white has Y = 1.
  EmitterSettings rel;
  rel.absolute = false;
  PanelEmitter r(d.panel, L, uniformEia(L, 1, 1, 1), "eia.exr", 1.2, rel);
  EXPECT_NEAR(r.whiteXyz().y, 1.0, 1e-9);
}

TEST(PanelEmitter, CoverGlassOffsetsAndFresnel) {
  Display d = smallDisplay(6, 4, 8, 0.05, 0.4, 1.0, 1.5);
  d.panel.coverGlass = CoverGlass{0.5, "N-BK7"};
  const EiLayout L = computeLayout(d);
  // Every pixel a different drive value, so the lookup point can be identified.
  Image eia = uniformEia(L, 0, 0, 0);
  for (int y = 0; y < L.panelH; ++y)
    for (int x = 0; x < L.panelW; ++x) eia.at(x, y, 1) = float(1 + x + y * L.panelW) / float(1 + L.panelW * L.panelH);
  PanelEmitter glass(d.panel, L, eia, "eia.exr", 1.5);
  d.panel.coverGlass.reset();
  PanelEmitter bare(d.panel, L, eia, "eia.exr", 1.5);
  ASSERT_TRUE(glass.hasCoverGlass());
  EXPECT_TRUE(glass.isDispersive());
  EXPECT_FALSE(bare.isDispersive());
  const float lambda = 530.0f;
  const double n = MaterialCatalog::standard().dielectric("N-BK7")->n(lambda);
  const double th = 0.6, thG = std::asin(std::sin(th) / n);
  const Vec3 dir(float(std::sin(th)), 0.0f, float(-std::cos(th)));
  // The glass moves the emitting point back by t (tan th - tan thG) against the ray's x travel:
  // aim so that it lands on the centre of a green stripe.
  const double shift = 0.5 * (std::tan(th) - std::tan(thG));
  const Point3 target = panelPoint(L, 12.5, 10.5, 1.5);
  const Point3 p = panelPoint(L, 12.5 + shift / L.pixelMm, 10.5, 1.5);
  const PanelEmission eg = glass.emit(p, dir, lambda);
  const PanelEmission eb = bare.lookup(target.x, target.y);
  EXPECT_NE(bare.lookup(p.x, p.y).weight, eb.weight);  // without the offset: another pixel
  ASSERT_EQ(eg.channel, 1);
  ASSERT_EQ(eb.channel, 1);
  const double T = fresnelTransmittance(std::cos(th), 1.0, n) / fresnelTransmittance(1.0, 1.0, n);
  EXPECT_NEAR(eg.weight, eb.weight * T, 1e-5);
  EXPECT_LT(T, 1.0);
  // At normal incidence the glass changes nothing.
  EXPECT_FLOAT_EQ(glass.emit(target, kDown, lambda).weight, bare.emit(target, kDown, lambda).weight);
}

TEST(PanelEmitter, ResolutionMismatchIsAnInputError) {
  Display d = smallDisplay(4, 3, 6, 0.05, 0.3, 1.0, 1.2);
  const EiLayout L = computeLayout(d);
  Image wrong(L.panelW + 1, L.panelH, {"R", "G", "B"});
  try {
    PanelEmitter e(d.panel, L, wrong, "my-eia.exr", 1.2);
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_EQ(e.file(), "my-eia.exr");
    EXPECT_EQ(e.key(), "resolution");
    EXPECT_NE(m.find(std::to_string(L.panelW + 1) + " x " + std::to_string(L.panelH)), std::string::npos) << m;
    EXPECT_NE(m.find(std::to_string(L.panelW) + " x " + std::to_string(L.panelH)), std::string::npos) << m;
  }
}

TEST(PanelEmitter, NonFiniteDriveIsAnInputError) {
  Display d = smallDisplay(4, 3, 6, 0.05, 0.3, 1.0, 1.2);
  const EiLayout L = computeLayout(d);
  Image eia = uniformEia(L, 1, 1, 1);
  eia.at(3, 2, 1) = std::numeric_limits<float>::quiet_NaN();
  try {
    PanelEmitter e(d.panel, L, eia, "nan-eia.exr", 1.2);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "nan-eia.exr");
    EXPECT_NE(std::string(e.what()).find("NaN"), std::string::npos);
  }
  Image two(L.panelW, L.panelH, {"R", "G"});
  EXPECT_THROW(PanelEmitter(d.panel, L, two, "two.exr", 1.2), InputError);
}

TEST(PanelEmitter, DriveValuesAreClampedAndEncodedImagesDecoded) {
  Display d = smallDisplay(4, 3, 6, 0.05, 0.3, 1.0, 1.2);
  const EiLayout L = computeLayout(d);
  PanelEmitter over(d.panel, L, uniformEia(L, 2.0f, -1.0f, 0.5f), "eia.exr", 1.2);
  EXPECT_EQ(over.emit(panelPoint(L, 9.17, 4.5, 1.2), kDown, 550.0f).weight, 1.0f);
  EXPECT_EQ(over.emit(panelPoint(L, 9.5, 4.5, 1.2), kDown, 550.0f).weight, 0.0f);
  EmitterSettings s;
  s.encoded = true;  // sRGB EOTF: 0.5 encoded -> 0.214 linear
  PanelEmitter enc(d.panel, L, uniformEia(L, 0.5f, 0.5f, 0.5f), "eia.png", 1.2, s);
  EXPECT_NEAR(enc.emit(panelPoint(L, 9.17, 4.5, 1.2), kDown, 550.0f).weight, d.panel.eotf.decode(0.5), 1e-6);
}

namespace {

// Dense midpoint-grid average of lookupPx over a box, per channel.
std::array<double, 3> gridAverage(const PanelEmitter& e, double u0, double v0, double u1, double v1, int n) {
  std::array<double, 3> s{0, 0, 0};
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const PanelEmission em = e.lookupPx(u0 + (i + 0.5) / n * (u1 - u0), v0 + (j + 0.5) / n * (v1 - v0));
      if (em.channel >= 0) s[size_t(em.channel)] += em.weight;
    }
  for (auto& v : s) v /= double(n) * n;
  return s;
}

void checkBoxAverages(const Display& d, const char* name) {
  const EiLayout L = computeLayout(d);
  PanelEmitter e(d.panel, L, patternEia(L), "pattern.exr", 1.2);
  Rng rng(7, 3);
  double worst = 0.0;
  for (int i = 0; i < 60; ++i) {
    // Boxes from 0.05 to 3 px, anywhere on the panel and across its edges.
    const double w = 0.05 + 2.95 * rng.uniformDouble(), h = 0.05 + 2.95 * rng.uniformDouble();
    const double u0 = -1.0 + (L.panelW + 1.0) * rng.uniformDouble(), v0 = -1.0 + (L.panelH + 1.0) * rng.uniformDouble();
    const auto a = e.boxAveragePx(u0, v0, u0 + w, v0 + h);
    const auto g = gridAverage(e, u0, v0, u0 + w, v0 + h, 600);
    for (int c = 0; c < 3; ++c) {
      worst = std::max(worst, std::abs(a[size_t(c)] - g[size_t(c)]));
      EXPECT_NEAR(a[size_t(c)], g[size_t(c)], 4e-3) << name << " box " << i << " channel " << c;
    }
  }
  std::printf("[ measured ] %s: largest |box average - 600 x 600 grid average| = %.2g\n", name, worst);
}

}  // namespace

TEST(PanelEmitterBox, StripeBoxAverageIsTheAreaIntegral) {
  checkBoxAverages(smallDisplay(4, 3, 6, 0.05, 0.3, 1.0, 1.2), "rgb stripe");
}

TEST(PanelEmitterBox, DiamondBoxAverageIsTheAreaIntegral) {
  Display d = smallDisplay(4, 3, 6, 0.05, 0.3, 1.0, 1.2);
  d.panel.subpixels = diamondLayout(0.8);
  checkBoxAverages(d, "diamond (clipped polygons)");
}

TEST(PanelEmitterBox, WholeTilesOfWhiteGiveTheFillFactorAndZeroBoxesThePoint) {
  for (bool diamond : {false, true}) {
    Display d = smallDisplay(4, 3, 6, 0.05, 0.3, 1.0, 1.2);
    if (diamond) d.panel.subpixels = diamondLayout(0.8);
    const EiLayout L = computeLayout(d);
    PanelEmitter e(d.panel, L, uniformEia(L, 1, 1, 1), "white.exr", 1.2);
    const int t = diamond ? 2 : 1;
    const auto a = e.boxAveragePx(2.0 * t, 4.0 * t, 5.0 * t, 6.0 * t);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[size_t(c)], 1.0 / e.areaFactor(c), 1e-6) << c;
    // Half of the box off the panel's left edge: half the light.
    const auto h = e.boxAveragePx(-3.0 * t, 4.0 * t, 3.0 * t, 6.0 * t);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(h[size_t(c)], 0.5 / e.areaFactor(c), 1e-6) << c;
    EXPECT_EQ(e.boxAveragePx(-5.0, -5.0, -1.0, -1.0)[0], 0.0f);
  }
  // A box of zero area is the point lookup, and emit() is lookupPx at emissionPointPx.
  Display d = smallDisplay(4, 3, 6, 0.05, 0.3, 1.0, 1.2);
  d.panel.coverGlass = CoverGlass{0.3, "N-BK7"};
  const EiLayout L = computeLayout(d);
  PanelEmitter e(d.panel, L, patternEia(L), "pattern.exr", 1.2);
  Rng rng(11, 5);
  for (int i = 0; i < 500; ++i) {
    const double u = L.panelW * rng.uniformDouble(), v = L.panelH * rng.uniformDouble();
    const PanelEmission p = e.lookupPx(u, v);
    const auto b = e.boxAveragePx(u, v, u, v);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(b[size_t(c)], p.channel == c ? p.weight : 0.0f);
    const Point3 pt(float((u - 0.5 * L.eiaW - L.panelCol0) * L.pixelMm),
                    float((0.5 * L.eiaH + L.panelRow0 - v) * L.pixelMm), -1.2f);
    const Vec3 dir = glm::normalize(Vec3(float(rng.uniform() - 0.5), float(rng.uniform() - 0.5), -1.0f));
    Vec2d uv;
    float factor = 0.0f;
    ASSERT_TRUE(e.emissionPointPx(pt, dir, 550.0f, uv, factor));
    const PanelEmission em = e.emit(pt, dir, 550.0f), lk = e.lookupPx(uv.x, uv.y);
    EXPECT_EQ(em.channel, lk.channel);
    if (lk.channel >= 0 && lk.weight > 0.0f) {
      EXPECT_EQ(em.weight, lk.weight * factor);
    }
  }
}

TEST(PanelEmitter, ChannelBoxAverageMatchesTheAllChannelBoxAverage) {
  for (bool diamond : {false, true}) {
    Display d = smallDisplay(4, 3, 6, 0.05, 0.3, 1.0, 1.2);
    if (diamond) d.panel.subpixels = diamondLayout(0.8);
    const EiLayout L = computeLayout(d);
    PanelEmitter e(d.panel, L, patternEia(L), "pattern.exr", 1.2);
    Rng rng(9, 2);
    double worst = 0.0;
    for (int i = 0; i < 5000; ++i) {
      const double u = -1.0 + (L.panelW + 2.0) * rng.uniformDouble(), v = -1.0 + (L.panelH + 2.0) * rng.uniformDouble();
      // Boxes up to the estimators' cap of 8 px half-width (the stripe's separable path) and a
      // few wider than the panel.
      const double reach = i % 10 == 0 ? 30.0 : i % 3 == 0 ? 8.0 : 2.0;
      const double hu = reach * rng.uniformDouble() * rng.uniformDouble();
      const double hv = reach * rng.uniformDouble() * rng.uniformDouble();
      const auto all = e.boxAveragePx(u - hu, v - hv, u + hu, v + hv);
      for (int c = 0; c < 3; ++c)
        worst = std::max(worst, double(std::abs(e.channelBoxAveragePx(c, u - hu, v - hv, u + hu, v + hv) - all[size_t(c)])));
    }
    EXPECT_LT(worst, 1e-6) << (diamond ? "diamond" : "stripe");
  }
}

// The three-channel lookup is the quadrature's when nothing is dispersive: it must give the
// one-channel lookups' values bit for bit (shared rows and columns, not a new sum), for a
// stripe layout, whole-pixel squares (the error budget's uniform pixels, all columns shared)
// and a diamond layout (no shared path).
TEST(PanelEmitter, ThreeChannelBoxAverageIsTheOneChannelAverages) {
  for (const char* layout : {"stripe", "uniform", "diamond"}) {
    Display d = smallDisplay(4, 3, 6, 0.05, 0.3, 1.0, 1.2);
    if (std::string(layout) == "diamond") d.panel.subpixels = diamondLayout(0.8);
    if (std::string(layout) == "uniform") {
      d.panel.subpixels.subpixels.clear();
      for (int c = 0; c < 3; ++c)
        d.panel.subpixels.subpixels.push_back({c, {{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}}});
    }
    const EiLayout L = computeLayout(d);
    PanelEmitter e(d.panel, L, patternEia(L), "pattern.exr", 1.2);
    Rng rng(11, 2);
    int differing = 0, nonZero = 0;
    for (int i = 0; i < 5000; ++i) {
      const double u = -1.0 + (L.panelW + 2.0) * rng.uniformDouble(), v = -1.0 + (L.panelH + 2.0) * rng.uniformDouble();
      const double reach = i % 10 == 0 ? 50.0 : i % 3 == 0 ? 8.0 : 2.0;  // past kMaxBoxTiles too
      const double hu = i % 97 == 0 ? 0.0 : reach * rng.uniformDouble() * rng.uniformDouble();
      const double hv = reach * rng.uniformDouble() * rng.uniformDouble();
      const auto three = e.channelBoxAveragesPx(u - hu, v - hv, u + hu, v + hv);
      for (int c = 0; c < 3; ++c) {
        const float one = e.channelBoxAveragePx(c, u - hu, v - hv, u + hu, v + hv);
        differing += three[size_t(c)] != one;
        nonZero += one != 0.0f;
      }
    }
    EXPECT_EQ(differing, 0) << layout;
    EXPECT_GT(nonZero, 5000) << layout;  // the boxes mostly see the panel
  }
}

// An emitter given another's drive table (the budget's rungs: one EIA, other layouts) shares
// it and reads the same values as one that read the EIA itself; a table of another size is
// not taken.
TEST(PanelEmitter, SharedDriveTableReadsAsTheEia) {
  Display d = smallDisplay(4, 3, 6, 0.05, 0.3, 1.0, 1.2);
  const EiLayout L = computeLayout(d);
  const Image eia = patternEia(L);
  const PanelEmitter first(d.panel, L, eia, "pattern.exr", 1.2);
  d.panel.subpixels = diamondLayout(0.8);
  EmitterSettings shared;
  shared.drive = first.driveTable();
  const PanelEmitter reusing(d.panel, L, eia, "pattern.exr", 1.2, shared), reading(d.panel, L, eia, "pattern.exr", 1.2);
  EXPECT_EQ(reusing.driveTable().get(), first.driveTable().get());
  EXPECT_NE(reading.driveTable().get(), first.driveTable().get());
  EXPECT_EQ(*reading.driveTable(), *first.driveTable());
  Rng rng(13, 2);
  for (int i = 0; i < 500; ++i) {
    const double u = L.panelW * rng.uniformDouble(), v = L.panelH * rng.uniformDouble(), h = 3.0 * rng.uniformDouble();
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(reusing.channelBoxAveragePx(c, u - h, v - h, u + h, v + h),
                reading.channelBoxAveragePx(c, u - h, v - h, u + h, v + h));
  }
  EmitterSettings wrongSize;
  wrongSize.drive = std::make_shared<const std::vector<float>>(7, 1.0f);
  EXPECT_EQ(*PanelEmitter(d.panel, L, eia, "pattern.exr", 1.2, wrongSize).driveTable(), *first.driveTable());
}

// A copy outlives its original and reads as it did (the stripe path's rectangle is found by
// index in the copy's own subpixels).
TEST(PanelEmitter, ACopyReadsAsTheOriginalAfterItIsGone) {
  Display d = smallDisplay(4, 3, 6, 0.05, 0.3, 1.0, 1.2);
  const EiLayout L = computeLayout(d);
  const PanelEmitter kept(d.panel, L, patternEia(L), "pattern.exr", 1.2);
  auto original = std::make_unique<PanelEmitter>(d.panel, L, patternEia(L), "pattern.exr", 1.2);
  const PanelEmitter copy = *original;
  original.reset();
  Rng rng(17, 2);
  for (int i = 0; i < 300; ++i) {
    const double u = L.panelW * rng.uniformDouble(), v = L.panelH * rng.uniformDouble(), h = 2.0 * rng.uniformDouble();
    EXPECT_EQ(copy.channelBoxAveragesPx(u - h, v - h, u + h, v + h), kept.channelBoxAveragesPx(u - h, v - h, u + h, v + h));
  }
}

TEST(PanelEmitter, ChannelLookupMatchesLookupPx) {
  for (bool diamond : {false, true}) {
    Display d = smallDisplay(4, 3, 6, 0.05, 0.3, 1.0, 1.2);
    if (diamond) d.panel.subpixels = diamondLayout(0.8);
    const EiLayout L = computeLayout(d);
    PanelEmitter e(d.panel, L, patternEia(L), "pattern.exr", 1.2);
    Rng rng(5, 2);
    int mismatches = 0;
    for (int i = 0; i < 20000; ++i) {
      const double u = -1.0 + (L.panelW + 2.0) * rng.uniformDouble(), v = -1.0 + (L.panelH + 2.0) * rng.uniformDouble();
      const PanelEmission p = e.lookupPx(u, v);
      for (int c = 0; c < 3; ++c)
        if (e.channelDrivePx(c, u, v) != (p.channel == c ? p.weight : 0.0f)) ++mismatches;
    }
    EXPECT_EQ(mismatches, 0) << (diamond ? "diamond" : "stripe");
  }
}
