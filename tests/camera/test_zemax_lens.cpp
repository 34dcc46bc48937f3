// Zemax .zmx lens files: vendor parts against their stated focal lengths, every encoding of one
// file giving one lens, units, the stop and aperture, and each refusal naming surface and keyword.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "camera/camera_config.h"
#include "camera/lens_analysis.h"
#include "camera/lens_loader.h"
#include "camera/zemax_lens.h"
#include "core/input_file.h"
#include "expect_input_error.h"

using namespace inim;

namespace {

std::string zmxPath(const std::string& name) { return std::string(INIM_SOURCE_DATA_DIR) + "/tests/data/zmx/" + name; }
std::string zmxBytes(const std::string& name) { return readInputFile(zmxPath(name)); }

// A small doublet written as OpticStudio writes files, in lens units of `unit`.
std::string doublet(const std::string& unit = "MM", const std::string& extraSurface = "") {
  return "VERS 190513 80 123\nMODE SEQ\nNAME test doublet\nUNIT " + unit +
         " X W X CM MR CPMM\nENPD 1.0E+1\nGCAT SCHOTT\nFTYP 0 0 1 3 0 0 0\n"
         "WAVM 1 0.4861 1\nWAVM 2 0.5876 1\nWAVM 3 0.6563 1\nWAVM 4 0.55 1\nPWAV 2\n"
         "SURF 0\n  TYPE STANDARD\n  CURV 0.0 0 0 0 0 \"\"\n  DISZ INFINITY\n"
         "SURF 1\n  STOP\n  TYPE STANDARD\n  CURV 0.0\n  DISZ 2\n  DIAM 6 1 0 0 1 \"\"\n"
         "SURF 2\n  TYPE STANDARD\n  CURV 0.02\n  DISZ 4\n  GLAS N-BK7 0 0 1.5168 64.17 0 0 0 0 0 0\n  DIAM 7 1 0 0 1 \"\"\n" +
         extraSurface +
         "SURF 3\n  TYPE STANDARD\n  CURV -0.03\n  DISZ 1.5\n  GLAS SF2 0 0 1.648 33.85\n  DIAM 7 1 0 0 1 \"\"\n"
         "SURF 4\n  TYPE STANDARD\n  CURV -0.004\n  DISZ 80\n  DIAM 7 1 0 0 1 \"\"\n"
         "SURF 5\n  TYPE STANDARD\n  CURV 0.0\n  DISZ 0\n  DIAM 5 0 0 0 1 \"\"\n";
}

std::string utf16(const std::string& ascii, bool littleEndian, bool bom) {
  std::string out;
  if (bom) out += littleEndian ? "\xFF\xFE" : "\xFE\xFF";
  for (char c : ascii) out += littleEndian ? std::string{c, '\0'} : std::string{'\0', c};
  return out;
}

std::string withLf(std::string s) {
  s.erase(std::remove(s.begin(), s.end(), '\r'), s.end());
  return s;
}

void expectSameLens(const LensSystem& a, const LensSystem& b) {
  ASSERT_EQ(a.surfaceCount(), b.surfaceCount());
  for (int i = 0; i < a.surfaceCount(); ++i) {
    const LensSurface &s = a.surfaces()[size_t(i)], &t = b.surfaces()[size_t(i)];
    EXPECT_EQ(s.radiusMm, t.radiusMm);
    EXPECT_EQ(s.thicknessMm, t.thicknessMm);
    EXPECT_EQ(s.apertureMm, t.apertureMm);
    EXPECT_EQ(s.conic, t.conic);
    EXPECT_EQ(s.asphere, t.asphere);
    EXPECT_EQ(s.mediumName, t.mediumName);
    EXPECT_EQ(s.isStop, t.isStop);
  }
}

std::string message(const InputError& e) { return e.what(); }

}  // namespace

// tests/data/zmx/README.md gives each file's source and the vendor's stated focal length.
TEST(ZemaxLens, VendorLensesMatchTheirStatedFocalLengths) {
  struct Part {
    const char* file;
    double statedEflMm, lambdaNm;
  };
  for (const Part& p : {Part{"LA1131-A.zmx", 50.0, 587.56}, Part{"AC254-050-A.zmx", 50.0, 587.56},
                        Part{"AL2520-A.zmx", 20.0, 780.0}, Part{"zmax_49360.zmx", 100.0, 587.56}}) {
    const LensSystem lens = loadLens(zmxPath(p.file));
    const double efl = analyzeLens(lens, p.lambdaNm).eflMm;
    EXPECT_NEAR(efl, p.statedEflMm, 0.005 * p.statedEflMm) << p.file;
  }
}

TEST(ZemaxLens, CatalogueGlassesAndAsphericTermsAreRead) {
  const LensSystem achromat = loadLens(zmxPath("AC254-050-A.zmx"));
  std::vector<std::string> media;
  for (const LensSurface& s : achromat.surfaces()) media.push_back(s.mediumName);
  EXPECT_NE(std::find(media.begin(), media.end(), "SCHOTT:N-BAF10"), media.end());
  EXPECT_NE(std::find(media.begin(), media.end(), "SCHOTT:SF10"), media.end());
  EXPECT_TRUE(achromat.isDispersive());
  EXPECT_EQ(achromat.design().wavelengthsNm.size(), 3u);  // FTYP: 3 of the 24 WAVM slots in use
  EXPECT_NEAR(achromat.design().primaryWavelengthNm, 587.6, 0.1);

  const LensSystem asphere = loadLens(zmxPath("AL2520-A.zmx"));
  int aspheres = 0;
  for (const LensSurface& s : asphere.surfaces()) aspheres += s.isAsphere() ? 1 : 0;
  EXPECT_EQ(aspheres, 1);
}

TEST(ZemaxLens, EveryEncodingOfOneFileGivesOneLens) {
  const std::string ascii = zmxBytes("LA1131-A.zmx");  // ASCII, CRLF
  const LensSystem ref = parseZmxLens(ascii, "LA1131-A.zmx");
  expectSameLens(ref, parseZmxLens(withLf(ascii), "lf.zmx"));
  expectSameLens(ref, parseZmxLens("\xEF\xBB\xBF" + ascii, "utf8-bom.zmx"));
  expectSameLens(ref, parseZmxLens(utf16(ascii, true, true), "utf16le-bom.zmx"));
  expectSameLens(ref, parseZmxLens(utf16(ascii, true, false), "utf16le.zmx"));
  expectSameLens(ref, parseZmxLens(utf16(withLf(ascii), false, true), "utf16be-lf.zmx"));
  // The vendor's own UTF-16 file loads as well (the Edmund part above), and Latin-1 bytes in a
  // NAME (AL2520-A's "Ø") do not matter.
  EXPECT_EQ(loadLens(zmxPath("ACL3026U.zmx")).surfaceCount(), 3);  // its dummy surface 1 dropped
}

TEST(ZemaxLens, UnitsScaleEveryLength) {
  const LensSystem mm = parseZmxLens(doublet("MM"), "mm.zmx");
  const LensSystem cm = parseZmxLens(doublet("CM"), "cm.zmx");
  const LensSystem in = parseZmxLens(doublet("IN"), "in.zmx");
  EXPECT_NEAR(analyzeLens(cm).eflMm, 10.0 * analyzeLens(mm).eflMm, 1e-9 * analyzeLens(cm).eflMm);
  EXPECT_NEAR(analyzeLens(in).eflMm, 25.4 * analyzeLens(mm).eflMm, 1e-9 * analyzeLens(in).eflMm);
  EXPECT_NEAR(cm.surfaces()[1].apertureMm, 140.0, 1e-12);
}

TEST(ZemaxLens, EvenAsphereTermsScaleWithTheUnit) {
  const std::string aspheric = "SURF 3\n  TYPE EVENASPH\n  CURV 0.01\n  DISZ 2\n  DIAM 7 1 0 0 1 \"\"\n  PARM 1 0\n  PARM 2 1e-6\n";
  auto renumbered = [&](const std::string& unit) {
    std::string t = doublet(unit, aspheric);
    // The inserted surface is SURF 3; shift the ones after it.
    for (int n : {5, 4, 3}) {
      const std::string from = "SURF " + std::to_string(n) + "\n  TYPE STANDARD\n  CURV " + (n == 3 ? "-0.03" : n == 4 ? "-0.004" : "0.0");
      const size_t at = t.find(from);
      if (at != std::string::npos) t.replace(at, 6, "SURF " + std::to_string(n + 1));
    }
    return t;
  };
  const LensSystem mm = parseZmxLens(renumbered("MM"), "a.zmx"), cm = parseZmxLens(renumbered("CM"), "b.zmx");
  ASSERT_TRUE(mm.surfaces()[2].isAsphere());
  EXPECT_DOUBLE_EQ(mm.surfaces()[2].asphere[1], 1e-6);
  // sag_mm(10 r) = 10 sag(r): the r^4 term scales by 10^-3.
  EXPECT_NEAR(cm.sag(2, 30.0), 10.0 * mm.sag(2, 3.0), 1e-12);
}

TEST(ZemaxLens, StopOnARefractingSurfaceBecomesAFlatStopInFrontOfIt) {
  const LensSystem lens = loadLens(zmxPath("LA1131-A.zmx"));  // STOP on the convex first surface
  EXPECT_EQ(lens.stopIndex(), 0);
  EXPECT_EQ(lens.surfaces()[0].radiusMm, 0.0);
  EXPECT_EQ(lens.surfaces()[0].thicknessMm, 0.0);  // the surface bows away from the object
  // ENPD 22.86 mm: the stop is the entrance pupil itself, not the 25.4 mm DIAM.
  EXPECT_NEAR(lens.stopDiameterMm(), 22.86, 1e-9);
  EXPECT_NEAR(analyzeLens(lens).entrancePupil.diameterMm, 22.86, 1e-6);
}

TEST(ZemaxLens, PlainCoordinateBreaksAndDummySurfacesKeepTheSpacing) {
  const std::string cb = "SURF 3\n  TYPE COORDBRK\n  DISZ 0\n  PARM 1 0\n  PARM 2 0\n  PARM 3 0\n";
  std::string t = doublet("MM");
  // Insert a zero coordinate break after surface 2: renumber 3.. upward.
  for (int n : {5, 4, 3}) {
    const size_t at = t.find("SURF " + std::to_string(n) + "\n");
    t.replace(at, 6, "SURF " + std::to_string(n + 1));
  }
  t.insert(t.find("SURF 4\n"), cb);
  const LensSystem a = parseZmxLens(doublet("MM"), "a.zmx"), b = parseZmxLens(t, "b.zmx");
  expectSameLens(a, b);
}

TEST(ZemaxLens, GlassMissingFromEveryCatalogueFallsBackToItsModelValuesWithAWarning) {
  const LensSystem lens = loadLens(zmxPath("ACL3026U.zmx"));  // GLAS B270 0 0 1.5 40
  ASSERT_FALSE(lens.design().warnings.empty());
  EXPECT_NE(lens.design().warnings[0].find("B270"), std::string::npos) << lens.design().warnings[0];
  EXPECT_NEAR(lens.indexAfter(1, 587.56), 1.5, 1e-6);
}

TEST(ZemaxLens, WhatInimCannotModelIsRefusedNamingSurfaceAndKeyword) {
  struct Case {
    std::string text, mustName;
  };
  const std::string base = doublet();
  auto with = [&](const std::string& from, const std::string& to) {
    std::string t = base;
    t.replace(t.find(from), from.size(), to);
    return t;
  };
  const std::vector<Case> cases = {
      {with("CURV 0.02\n", "CURV 0.02\n  TYPE TOROIDAL\n"), "SURF 2 (line 23), TYPE"},
      {with("GLAS SF2 0 0 1.648 33.85", "GLAS MIRROR"), "SURF 3 (line 29), GLAS"},
      {with("CURV -0.004\n", "CURV -0.004\n  SQAP 3 3 0\n"), "SURF 4 (line 35), SQAP"},
      {with("UNIT MM", "UNIT FURLONG"), "line 4: UNIT"},
      {with("MODE SEQ", "MODE NSC"), "line 2: MODE"},
      {with("CURV -0.03", "CURV -0.0x3"), "line 31: CURV"},
      {with("GLAS SF2 0 0 1.648 33.85", "GLAS NO-SUCH-GLASS 0 0 0 0"), "SURF 3 (line 29), GLAS (line 33)"},
      {with("DISZ 4\n", "DISZ INFINITY\n"), "SURF 2 (line 23), DISZ"},
      {base.substr(0, base.find("SURF 2")), "SURF"},  // truncated: no lens surface
      {with("CURV 0.02\n", "CURV 0.02\n  CONI 100\n"), "SURF 2 (line 23), DIAM"},  // conic ends inside the aperture
  };
  for (const Case& c : cases) {
    InputError e = expectInputError([&] { parseZmxLens(c.text, "bad.zmx"); });
    EXPECT_EQ(e.file(), "bad.zmx");
    EXPECT_NE(message(e).find(c.mustName), std::string::npos) << "wanted \"" << c.mustName << "\" in: " << message(e);
  }
  // A coordinate break that tilts.
  std::string tilt = base;
  tilt.replace(tilt.find("SURF 1\n  STOP\n  TYPE STANDARD"), 29, "SURF 1\n  STOP\n  TYPE COORDBRK\n  PARM 3 5");
  InputError e = expectInputError([&] { parseZmxLens(tilt, "tilt.zmx"); });
  EXPECT_NE(message(e).find("PARM 3"), std::string::npos) << message(e);
  // The paper's non-sequential model is not a lens.
  InputError nsc = expectInputError([] { loadLens(zmxPath("nsc/EIA_generation_NSC_NERF_SDF.zmx")); });
  EXPECT_NE(message(nsc).find("NSC"), std::string::npos) << message(nsc);
}

// The viewing camera takes a vendor file as its lens; what the file could only approximate is
// among the camera's assumptions.
TEST(ZemaxLens, TheCameraTakesAZemaxLens) {
  Json j = Json::parse(readInputFile(defaultCameraPath()));
  j["lens"] = zmxPath("ACL3026U.zmx");
  j.erase("f_number");
  const CameraDescription c = parseCameraDescription(JsonObject(j, "camera.json", ""));
  EXPECT_EQ(c.lens.name(), "Aspheric Condenser Lens, Uncoated, \xC3\x98" "30 mm, f=26.5 mm");  // "Ø" from UTF-16
  bool warned = false;
  for (const std::string& a : c.assumptions) warned = warned || a.find("GLAS B270") != std::string::npos;
  EXPECT_TRUE(warned);
}
