// inim lens info FILE [--json] [--thickness-convention after|before] [--wavelength-nm W]:
// first-order properties of a camera lens (EFL, BFL, FFL, f-number, pupils, principal
// planes), found by real ray tracing of near-axis rays.
#include <cstdio>
#include <memory>
#include <string>

#include "camera/lens_analysis.h"
#include "camera/lens_loader.h"
#include "cli/commands.h"
#include "cli/options.h"

namespace inim::cli {

void addLensCommand(CLI::App& app) {
  CLI::App* lens = &app;
  lens->require_subcommand(1);
  struct Opts {
    std::string file;
    std::string convention;
    double wavelengthNm = kLensReferenceLambdaNm;
    bool json = false;
  };
  auto opts = std::make_shared<Opts>();
  auto* info = lens->add_subcommand(
      "info",
      "Print EFL, BFL, FFL, f-number, entrance and exit pupils and principal planes, found by real ray tracing");
  info->add_option("FILE", opts->file,
                   "Lens file (inim .json, Zemax .zmx or pbrt-v4 .dat) or a catalog name under optics/lenses/ (e.g. dgauss.50mm)")
      ->required();
  addSetting(info, "json", opts->json);
  addSetting(info, "thickness_convention", opts->convention);
  addSetting(info, "wavelength_nm", opts->wavelengthNm);
  info->callback([opts] {
    LensLoadOptions lo;
    if (opts->convention == "after") lo.thicknessConvention = ThicknessConvention::After;
    if (opts->convention == "before") lo.thicknessConvention = ThicknessConvention::Before;
    const LensSystem l = loadLens(opts->file, lo);
    const LensInfo li = analyzeLens(l, opts->wavelengthNm);
    if (opts->json) {
      Json j = lensInfoJson(li);
      j["thickness_convention_override"] = opts->convention.empty() ? Json(nullptr) : Json(opts->convention);
      std::printf("%s\n", j.dump(2).c_str());
    } else {
      std::printf("%s", lensInfoText(li).c_str());
    }
  });
}

}  // namespace inim::cli
