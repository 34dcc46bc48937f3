// Refractive index models and the material catalog (spectra/materials.json).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "spectral/dispersion.h"

namespace inim {
namespace {

constexpr float kLd = 587.56f, kLF = 486.13f, kLC = 656.27f;  // d, F, C lines, nm

const MaterialCatalog& cat() { return MaterialCatalog::standard(); }

// N-BK7: n_d = 1.5168 +- 1e-4 from the Schott Sellmeier formula and from the table
// (linear interpolation between 586 and 608 nm is good to 3e-6 here), V_d = 64.17 +- 0.1.
TEST(Dispersion, NBK7) {
  auto s = cat().dielectric("N-BK7");
  auto t = cat().dielectric("N-BK7-table");
  EXPECT_NEAR(s->n(kLd), 1.5168f, 1e-4f);
  EXPECT_NEAR(t->n(kLd), 1.5168f, 1e-4f);
  std::cout << "[ info ] N-BK7 n_d Sellmeier " << s->n(kLd) << ", table " << t->n(kLd) << "\n";
  double Vd = (s->n(kLd) - 1.0) / (s->n(kLF) - s->n(kLC));
  EXPECT_NEAR(Vd, 64.17, 0.1);
  EXPECT_TRUE(s->isDispersive());
  // Table and formula agree over the visible (same catalogue data) to 1e-4.
  for (float l = 400.0f; l <= 800.0f; l += 7.0f) EXPECT_NEAR(s->n(l), t->n(l), 1e-4f) << l;
}

// Sultanova et al. 2009: PMMA n_d = 1.4906, polycarbonate 1.5848 (+- 5e-4).
TEST(Dispersion, Polymers) {
  EXPECT_NEAR(cat().dielectric("PMMA")->n(kLd), 1.4906f, 5e-4f);
  EXPECT_NEAR(cat().dielectric("polycarbonate")->n(kLd), 1.5848f, 5e-4f);
}

// Tabulated catalogue glasses at n_d (Schott/Ohara catalogue n_d values, +- 1e-3).
TEST(Dispersion, TabulatedGlasses) {
  EXPECT_NEAR(cat().dielectric("SF11")->n(kLd), 1.78472f, 1e-3f);
  EXPECT_NEAR(cat().dielectric("BAF10")->n(kLd), 1.67003f, 1e-3f);
  EXPECT_NEAR(cat().dielectric("LASF9")->n(kLd), 1.85025f, 1e-3f);
  // Normal dispersion: n decreases with wavelength.
  for (const auto& name : {"SF11", "BAF10", "LASF9", "N-BK7-table"}) {
    auto ior = cat().dielectric(name);
    EXPECT_GT(ior->n(450.0f), ior->n(650.0f)) << name;
  }
}

// Cauchy through n_d with the Abbe number: reproduces n_d and n_F - n_C = (n_d - 1)/V_d.
TEST(Dispersion, CauchyFromAbbe) {
  CauchyIor c = CauchyIor::fromAbbe(1.5168, 64.17);
  EXPECT_NEAR(c.n(kLd), 1.5168f, 1e-6f);
  EXPECT_NEAR(c.n(kLF) - c.n(kLC), 0.5168 / 64.17, 1e-6);
  auto e = cat().dielectric("abbe-example");
  EXPECT_NEAR(e->n(kLd), 1.5168f, 1e-6f);
  EXPECT_THROW(CauchyIor::fromAbbe(1.5, 0.0), InputError);
  // Plain Cauchy: n = A + B / l^2 (um): 1.5 + 0.004 / 0.25 = 1.516 at 500 nm.
  EXPECT_NEAR(CauchyIor(1.5, 0.004).n(500.0f), 1.516f, 1e-6f);
  EXPECT_NEAR(CauchyIor(1.5, 0.0, 0.0016).n(500.0f), 1.5256f, 1e-6f);
}

TEST(Dispersion, ConstantAndClampedTable) {
  ConstantIor c(1.33f);
  EXPECT_EQ(c.n(400.0f), 1.33f);
  EXPECT_FALSE(c.isDispersive());
  TabulatedIor t(std::make_shared<PiecewiseLinearSpectrum>(std::vector<float>{400, 600},
                                                           std::vector<float>{1.6f, 1.5f}));
  EXPECT_FLOAT_EQ(t.n(300.0f), 1.6f);
  EXPECT_FLOAT_EQ(t.n(900.0f), 1.5f);
  EXPECT_FLOAT_EQ(t.n(500.0f), 1.55f);
  EXPECT_FALSE(cat().dielectric("air")->isDispersive());
}

// Conductors: n and k tables; copper at 550 nm is about n = 0.9, k = 2.6.
TEST(Dispersion, Conductors) {
  for (const char* m : {"Cu", "Ag", "Al", "Au", "CuZn"}) {
    ASSERT_TRUE(cat().hasConductor(m)) << m;
    const auto& c = cat().conductor(m);
    EXPECT_GT((*c.k)(550.0f), 1.0f) << m;
    EXPECT_GT((*c.eta)(550.0f), 0.0f) << m;
  }
  const auto& cu = cat().conductor("Cu");
  EXPECT_NEAR((*cu.eta)(550.0f), 0.9f, 0.2f);
  EXPECT_NEAR((*cu.k)(550.0f), 2.6f, 0.2f);
  EXPECT_EQ(cat().conductorNames().size(), 5u);
}

TEST(Dispersion, UnknownMaterialIsInputError) {
  try {
    cat().dielectric("unobtainium");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find("materials.json"), std::string::npos) << msg;
    EXPECT_NE(msg.find("unobtainium"), std::string::npos) << msg;
    EXPECT_NE(msg.find("N-BK7"), std::string::npos) << msg;  // lists known names
  }
  EXPECT_THROW(cat().conductor("N-BK7"), InputError);
}

// A misspelt key in a catalog entry is an error naming the file and the key.
TEST(Dispersion, BadCatalogIsInputError) {
  auto p = std::filesystem::temp_directory_path() / (std::to_string(::getpid()) + "_mat.json");
  std::ofstream(p) << R"({"materials": {"G": {"type": "cauchy", "A": 1.5, "Bee": 0.004}}})";
  try {
    MaterialCatalog c(p.string());
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find(p.filename().string()), std::string::npos) << msg;
    EXPECT_NE(msg.find("materials.G"), std::string::npos) << msg;
  }
  std::ofstream(p) << R"({"materials": {"G": {"type": "glassy", "n": 1.5}}})";
  EXPECT_THROW(MaterialCatalog(p.string()), InputError);
  std::ofstream(p) << R"({"materials": {"G": {"type": "table", "file": "nope.csv"}}})";
  EXPECT_THROW(MaterialCatalog(p.string()), InputError);
  std::filesystem::remove(p);
}

}  // namespace
}  // namespace inim
