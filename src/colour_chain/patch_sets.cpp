#include "colour_chain/patch_sets.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/input_file.h"
#include "colour_chain/colour_chain.h"
#include "core/error.h"
#include "core/format.h"
#include "core/output_file.h"
#include "core/rng.h"
#include "spectral/cie.h"
#include "spectral/color.h"

namespace inim {

namespace {

// A reflectance table extended as constants beyond its range (the CIE's recommendation for
// reflectances measured over less than the visible range), times D65, at 1 nm over 360-830 nm,
// scaled so that a perfect white has Y = 1.
SpectrumPtr radianceUnderD65(const PiecewiseLinearSpectrum& reflectance) {
  const auto& l = reflectance.lambdas();
  const double whiteY = spectrumToXYZ(cie::D65()).y;
  std::vector<float> lambdas, values;
  for (int nm = int(kLambdaMin); nm <= int(kLambdaMax); ++nm) {
    const float c = std::clamp(float(nm), l.front(), l.back());
    lambdas.push_back(float(nm));
    values.push_back(float(double(reflectance(c)) * double(cie::D65()(float(nm))) / whiteY));
  }
  return std::make_shared<PiecewiseLinearSpectrum>(lambdas, values);
}

Vec3d exposedDrive(const PanelColor& panel, double exposure, const Vec3d& xyz) {
  return exposure * panel.driveFromXYZ(xyz);
}

}  // namespace

PatchSet colorCheckerPatches(const std::string& path) {
  const std::string file = path.empty() ? dataPath("spectra/colorchecker_babelcolor_avg.csv") : path;
  PatchSet set{"colorchecker", false, {}};
  for (const std::string& column : csvColumns(file)) {
    Patch p;
    p.name = column;
    p.radiance = radianceUnderD65(*loadSpectrumCSV(file, column));
    p.xyz = spectrumToXYZ(*p.radiance);
    set.patches.push_back(p);
  }
  if (set.patches.size() != 24)
    throw InputError(file, "columns", std::to_string(set.patches.size()) + " patches", "the 24 ColorChecker patches");
  return set;
}

PatchSet driveGrid(int levels) {
  if (levels < 2 || levels > 17)
    throw InputError("", "grid_levels", std::to_string(levels), "2 to 17 levels per channel");
  PatchSet set{"grid", true, {}};
  const double step = 1.0 / double(levels - 1);
  for (int b = 0; b < levels; ++b)
    for (int g = 0; g < levels; ++g)
      for (int r = 0; r < levels; ++r) {
        Patch p;
        p.drive = Vec3d(r, g, b) * step;
        p.name = "grid " + std::to_string(r) + "," + std::to_string(g) + "," + std::to_string(b);
        set.patches.push_back(p);
      }
  return set;
}

PatchSet holdOutInGamut(const PanelColor& panel, double exposure, int count, uint64_t seed,
                        const std::string& fieldSpace) {
  PatchSet set{"holdout_in", false, {}};
  Rng rng(seed, 0x4c4f4c44u);
  for (int tries = 0; int(set.patches.size()) < count && tries < 1000 * count; ++tries) {
    const Vec3d drive(rng.uniform(), rng.uniform(), rng.uniform());
    const Vec3d xyz = panel.driveToXYZ() * drive / exposure;
    if (glm::length(representableInField(xyz, fieldSpace) - xyz) > 1e-5 * (1.0 + glm::length(xyz))) continue;
    Patch p;
    p.name = "in " + std::to_string(set.patches.size());
    p.xyz = xyz;
    set.patches.push_back(p);
  }
  return set;
}

PatchSet holdOutOutOfGamut(const PanelColor& panel, double exposure, int count, uint64_t seed) {
  PatchSet set{"holdout_out", false, {}};
  const glm::dmat3 rec2020(rgbToXYZMatrix({0.708f, 0.292f}, {0.170f, 0.797f}, {0.131f, 0.046f}, {0.3127f, 0.3290f}));
  Rng rng(seed, 0x4f555447u);
  for (int tries = 0; int(set.patches.size()) < count && tries < 1000 * count; ++tries) {
    const Vec3d xyz = rec2020 * Vec3d(rng.uniform(), rng.uniform(), rng.uniform());
    const Vec3d d = exposedDrive(panel, exposure, xyz);
    if (std::min({d.x, d.y, d.z}) > -0.01 && std::max({d.x, d.y, d.z}) < 1.01) continue;
    Patch p;
    p.name = "out " + std::to_string(set.patches.size());
    p.xyz = xyz;
    set.patches.push_back(p);
  }
  return set;
}

PatchSet readPatchCsv(const std::string& path) {
  checkInputFile(path);
  std::ifstream in(path);
  if (!in) throw InputError(path, "file", "\"" + path + "\"", "a readable patch CSV");
  PatchSet set{path, false, {}};
  std::string line;
  bool header = false;
  for (int n = 1; std::getline(in, line); ++n) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, ',');) cells.push_back(trim(c));
    const std::string where = "line " + std::to_string(n);
    if (!header) {
      if (cells != std::vector<std::string>{"name", "X", "Y", "Z"})
        throw InputError(path, "columns (" + where + ")", "\"" + line + "\"", "the header name,X,Y,Z");
      header = true;
      continue;
    }
    if (cells.size() != 4) throw InputError(path, where, "\"" + line + "\"", "4 values: name,X,Y,Z");
    Patch p;
    p.name = cells[0];
    for (int c = 0; c < 3; ++c) {
      char* end = nullptr;
      const double v = std::strtod(cells[size_t(c) + 1].c_str(), &end);
      if (cells[size_t(c) + 1].empty() || *end != '\0' || !std::isfinite(v) || v < 0.0)
        throw InputError(path, where + " " + "XYZ"[c], "\"" + cells[size_t(c) + 1] + "\"",
                         "a finite number >= 0");
      p.xyz[c] = v;
    }
    set.patches.push_back(p);
  }
  if (set.patches.empty()) throw InputError(path, "rows", "none", "at least one patch after the header");
  return set;
}

}  // namespace inim
