// The paper's Zemax model written out: its structure against the paper's own NSC demo
// (lrio-copl/NERF-ZEMAX, tests/data/zmx/nsc/; source in tests/data/zmx/README.md), whose
// detector and ray count are the default display's.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <sstream>

#include "core/input_file.h"
#include "core/text_encoding.h"
#include "display/display.h"
#include "fixtures.h"
#include "triads/triads.h"
#include "triads/zemax_nsc_model.h"

using namespace inim;
using namespace fixtures;

namespace {

// An NSC file's structure: top-level keywords in order, and each object's type, comment,
// position line and numbered parameters.
struct NscObject {
  std::string type, comment;
  std::vector<std::string> position;  // NSOP's fields
  std::map<int, double> parameters;   // NSOD k value
  std::set<std::string> keywords;
};
struct NscFile {
  std::vector<std::string> topLevel;
  std::set<std::string> surfaceKeywords;
  std::vector<NscObject> objects;
  std::string mode, containerType;
};

NscFile readNsc(const std::string& bytes) {
  NscFile f;
  std::istringstream in(utf8FromBytes(bytes, "nsc.zmx"));
  std::string line;
  bool inSurface1 = false;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream w(line);
    std::string key;
    if (!(w >> key)) continue;
    if (line[0] != ' ') {
      f.topLevel.push_back(key);
      if (key == "MODE") w >> f.mode;
      if (key == "SURF") {
        int n = 0;
        w >> n;
        inSurface1 = n == 1;
      }
      continue;
    }
    f.surfaceKeywords.insert(key);
    if (inSurface1 && key == "TYPE") w >> f.containerType;
    if (key == "NSOH") {
      NscObject o;
      int a = 0, b = 0;
      w >> o.type >> a >> b;
      std::getline(w, o.comment);
      if (!o.comment.empty() && o.comment[0] == ' ') o.comment.erase(0, 1);
      f.objects.push_back(o);
    } else if (!f.objects.empty() && key.rfind("NS", 0) == 0 || (!f.objects.empty() && key == "NOID")) {
      NscObject& o = f.objects.back();
      o.keywords.insert(key);
      if (key == "NSOP")
        for (std::string v; w >> v;) o.position.push_back(v);
      if (key == "NSOD") {
        int k = 0;
        double v = 0.0;
        w >> k >> v;
        o.parameters[k] = v;
      }
    }
  }
  return f;
}

const std::string kPaperDemo = std::string(INIM_SOURCE_DATA_DIR) + "/tests/data/zmx/nsc/EIA_generation_NSC_NERF_SDF.zmx";

NscFile demo() { return readNsc(readInputFile(kPaperDemo)); }

ZemaxNscModel defaultDisplayModel() {
  const Display d = loadDisplay(defaultDisplayPath());
  const EiLayout L = computeLayout(d);
  return zemaxNscModelFor(L, "/some/folder/default.sdf", uint64_t(L.numRays()) * 3, paperTriadWavelengths().nm, d.name);
}

}  // namespace

TEST(ZemaxNscModel, HasThePaperDemosObjectsAndNumbersForTheDefaultDisplay) {
  const NscFile paper = demo(), ours = readNsc(utf16leWithBom(zemaxNscModelText(defaultDisplayModel())));
  EXPECT_EQ(ours.mode, "NSC");
  EXPECT_EQ(ours.mode, paper.mode);
  EXPECT_EQ(ours.containerType, paper.containerType);  // NONSEQCO
  ASSERT_EQ(ours.objects.size(), 2u);
  ASSERT_EQ(paper.objects.size(), 2u);
  for (size_t i = 0; i < 2; ++i) EXPECT_EQ(ours.objects[i].type, paper.objects[i].type);  // NSC_SFIL, NSC_DETC
  const NscObject &src = ours.objects[0], &det = ours.objects[1];
  const NscObject &paperSrc = paper.objects[0], &paperDet = paper.objects[1];
  EXPECT_EQ(src.comment, "default.sdf");  // the SDF by its file name, where OpticStudio looks for it
  // The default display is the paper's: 153 x 65 lenslets of 25 x 25 pixels, three triads each.
  EXPECT_EQ(src.parameters.at(2), paperSrc.parameters.at(2));  // analysis rays 18,646,875
  EXPECT_EQ(src.parameters.at(2), 18646875.0);
  for (int k : {1, 2, 3, 4}) EXPECT_DOUBLE_EQ(det.parameters.at(k), paperDet.parameters.at(k)) << "detector NSOD " << k;
  EXPECT_EQ(det.parameters.at(6), paperDet.parameters.at(6));  // colour mode
  // At the display's gap, as the demo (rays leave z = 0 toward the panel): the default display
  // generates at the paper's g = f = 3.3 mm; the demo's detector sits at the 3 mm of the paper's
  // ray-generation macro.
  ASSERT_GE(det.position.size(), 7u);
  EXPECT_DOUBLE_EQ(std::stod(det.position[2]), -computeLayout(loadDisplay(defaultDisplayPath())).gapMm);
  EXPECT_DOUBLE_EQ(std::stod(paperDet.position[2]), -3.0);
  EXPECT_EQ(det.position[6], paperDet.position[6]);  // ABSORB
  // Every keyword we write is one the paper's OpticStudio file uses.
  for (const NscObject* o : {&src, &det})
    for (const std::string& k : o->keywords)
      EXPECT_TRUE(paper.objects[0].keywords.count(k) || paper.objects[1].keywords.count(k)) << k;
  const std::set<std::string> paperTop(paper.topLevel.begin(), paper.topLevel.end());
  for (const std::string& k : ours.topLevel)
    if (k != "NOTE") EXPECT_TRUE(paperTop.count(k)) << k;  // NOTE: the vendors' lens files use it
}

TEST(ZemaxNscModel, IsUtf16WithCrlfAsOpticStudioWritesIt) {
  const std::string bytes = utf16leWithBom(zemaxNscModelText(defaultDisplayModel()));
  const std::string paper = readInputFile(kPaperDemo);
  EXPECT_EQ(bytes.substr(0, 2), paper.substr(0, 2));  // FF FE
  EXPECT_NE(bytes.find(std::string("\r\0\n\0", 4)), std::string::npos);
  EXPECT_EQ(utf8FromBytes(bytes, "x").find("\n"), utf8FromBytes(bytes, "x").find("\r\n") + 1);
}

TEST(ZemaxNscModel, DetectorFollowsTheDisplaysGapAndEia) {
  EiLayout L = computeLayout(paperDisplay({.cols = 5, .rows = 3, .gapMm = 3.3}));
  const ZemaxNscModel m = zemaxNscModelFor(L, "x.sdf", 4500, {625.0, 530.0, 460.0}, "small");
  EXPECT_DOUBLE_EQ(m.detectorZMm, -3.3);
  EXPECT_EQ(m.detectorPixelsX, L.eiaW);
  EXPECT_DOUBLE_EQ(2.0 * m.detectorHalfWidthMm, L.eiaW * L.pixelMm);
  EXPECT_EQ(m.analysisRays, 4500u);
  EXPECT_DOUBLE_EQ(m.wavelengthsUm[0], 0.625);
}
