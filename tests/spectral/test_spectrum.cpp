// Spectral distributions: tabulated, piecewise linear, blackbody, Gaussian, CSV loading.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "core/output_file.h"
#include "spectral/spectrum.h"

namespace inim {
namespace {

std::string writeTemp(const std::string& name, const std::string& text) {
  auto p = std::filesystem::temp_directory_path() / (std::to_string(::getpid()) + "_" + name);
  std::ofstream(p) << text;
  return p.string();
}

TEST(Spectrum, ConstantAndScaled) {
  ConstantSpectrum c(0.25f);
  EXPECT_EQ(c(400.0f), 0.25f);
  EXPECT_EQ(c.maxValue(), 0.25f);
  ScaledSpectrum s(std::make_shared<ConstantSpectrum>(2.0f), 3.0f);
  EXPECT_EQ(s(500.0f), 6.0f);
  // Trapezoid integral of 1 over 360-830 nm is 470 nm exactly.
  EXPECT_NEAR(integrate(ConstantSpectrum(1.0f)), 470.0, 1e-9);
}

TEST(Spectrum, PiecewiseLinearInterpolatesAndIsZeroOutside) {
  PiecewiseLinearSpectrum s({400.0f, 500.0f, 600.0f}, {1.0f, 3.0f, 2.0f});
  EXPECT_FLOAT_EQ(s(400.0f), 1.0f);
  EXPECT_FLOAT_EQ(s(450.0f), 2.0f);
  EXPECT_FLOAT_EQ(s(500.0f), 3.0f);
  EXPECT_FLOAT_EQ(s(575.0f), 2.25f);
  EXPECT_FLOAT_EQ(s(600.0f), 2.0f);
  EXPECT_EQ(s(399.0f), 0.0f);
  EXPECT_EQ(s(601.0f), 0.0f);
  EXPECT_EQ(s.maxValue(), 3.0f);
  s.scale(2.0f);
  EXPECT_FLOAT_EQ(s(450.0f), 4.0f);
  // Integral of a triangle-ish table by the 1 nm trapezoid (exact for piecewise linear
  // with nodes on whole nm): 100*(1+3)/2 + 100*(3+2)/2 = 450.
  PiecewiseLinearSpectrum t({400.0f, 500.0f, 600.0f}, {1.0f, 3.0f, 2.0f});
  EXPECT_NEAR(integrate(t, 400.0f, 600.0f), 450.0, 1e-6);
  EXPECT_THROW(PiecewiseLinearSpectrum({500.0f, 400.0f}, {1.0f, 2.0f}), InputError);
}

// Planck: the normalised spectrum peaks at Wien's lambda_max = b / T (within 0.5 nm).
TEST(Spectrum, BlackbodyPeakFollowsWien) {
  for (float T : {3000.0f, 5000.0f, 6500.0f}) {
    BlackbodySpectrum bb(T);
    float best = 0.0f, bestL = 0.0f;
    for (float l = 300.0f; l <= 1200.0f; l += 0.05f)
      if (bb(l) > best) best = bb(l), bestL = l;
    const float wien = 2.897771955e6f / T;
    EXPECT_NEAR(bestL, wien, 0.5f) << T;
    EXPECT_NEAR(best, 1.0f, 1e-5f);
    EXPECT_NEAR(bb(wien), 1.0f, 1e-6f);
  }
}

// Hand-computed: 2hc^2 / (l^5 (exp(hc / (l k T)) - 1)) at 500 nm, 5000 K, CODATA 2018
// constants: hc/(lkT) = 5.75522..., B = 1.21072e13 W m^-2 sr^-1 m^-1 (rel. 1e-4).
TEST(Spectrum, PlanckValue) {
  EXPECT_NEAR(BlackbodySpectrum::planck(500.0, 5000.0) / 1.2107190590e13, 1.0, 1e-4);
  EXPECT_NEAR(BlackbodySpectrum::planck(600.0, 6500.0) / 3.9262368513e13, 1.0, 1e-4);
  EXPECT_EQ(BlackbodySpectrum::planck(500.0, 0.0), 0.0);
  EXPECT_THROW(BlackbodySpectrum(-10.0f), InputError);
}

// Gaussian: half the peak at mean +- FWHM/2 (to 1e-5).
TEST(Spectrum, GaussianFwhm) {
  GaussianSpectrum g(550.0f, 40.0f, 2.0f);
  EXPECT_FLOAT_EQ(g(550.0f), 2.0f);
  EXPECT_NEAR(g(530.0f), 1.0f, 1e-5f);
  EXPECT_NEAR(g(570.0f), 1.0f, 1e-5f);
  EXPECT_EQ(g.maxValue(), 2.0f);
  // Area of a Gaussian: scale * FWHM * sqrt(pi / (4 ln 2)).
  EXPECT_NEAR(integrate(g, 300.0f, 800.0f), 2.0 * 40.0 * std::sqrt(M_PI / (4.0 * std::log(2.0))), 1e-3);
}

TEST(Spectrum, LoadCsvColumnAndSource) {
  auto d65 = loadSpectrumCSV(dataPath("spectra/cie_d65.csv"), "relative_power");
  EXPECT_NEAR(d65->operator()(560.0f), 100.0f, 1e-3f);
  EXPECT_NE(d65->source().find("CIE"), std::string::npos);
  auto cols = csvColumns(dataPath("spectra/cie1931_2deg_cmf.csv"));
  ASSERT_EQ(cols.size(), 3u);
  EXPECT_EQ(cols[0], "x_bar");
  EXPECT_EQ(cols[2], "z_bar");
  auto k = loadSpectrumCSV(dataPath("spectra/metal_cu.csv"), "k");
  EXPECT_GT(k->operator()(550.0f), 2.0f);
}

// Bad input names the file and the column.
TEST(Spectrum, MissingColumnIsInputError) {
  std::string path = dataPath("spectra/cie_d65.csv");
  try {
    loadSpectrumCSV(path, "no_such_column");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find("cie_d65.csv"), std::string::npos) << msg;
    EXPECT_NE(msg.find("no_such_column"), std::string::npos) << msg;
    EXPECT_NE(msg.find("relative_power"), std::string::npos) << msg;  // lists known columns
  }
  EXPECT_THROW(loadSpectrumCSV("/nonexistent/file.csv", "n"), InputError);
  std::string bad = writeTemp("bad.csv", "# test\nwavelength_nm,n\n400,1.5\n500,abc\n");
  try {
    loadSpectrumCSV(bad, "n");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find("line 4"), std::string::npos) << msg;
    EXPECT_NE(msg.find("abc"), std::string::npos) << msg;
  }
  std::string unsorted = writeTemp("unsorted.csv", "wavelength_nm,n\n500,1.5\n400,1.6\n");
  EXPECT_THROW(loadSpectrumCSV(unsorted, "n"), InputError);
  std::filesystem::remove(bad);
  std::filesystem::remove(unsorted);
}

}  // namespace
}  // namespace inim
