#include "runs/triads_run.h"

#include <cmath>

#include "display/gap_range.h"
#include "core/error.h"
#include "core/format.h"
#include "core/image.h"
#include "core/output_file.h"
#include "core/file_kinds.h"
#include "core/progress.h"
#include "display/display.h"
#include "rays/pinhole_rays.h"
#include "synthesis/eia_synthesis.h"
#include "triads/sdf.h"

namespace inim {

TriadExportResult exportTriads(const TriadExportSettings& s) {
  requireFileKind(s.out, "out", {FileKind::Sdf, FileKind::Dat}, "a Zemax source file name (.sdf or .dat)");
  if (!(s.options.fluxScale > 0.0f) || !std::isfinite(s.options.fluxScale))
    throw InputError("", "flux_scale", std::to_string(s.options.fluxScale), "a number > 0");
  Display d = loadDisplay(displayPathOrDefault(s.displayPath));
  const EiLayout L = applyLayoutOverride(d, s.layout);
  TriadExportResult r;
  r.wavelengths = parseTriadWavelengths(d.panel, s.wavelengths);
  const std::vector<float> drive = driveFromEia(L, eiaArea(L, readImage(s.eiaPath), s.eiaPath));
  const RaySet rays = generatePinholeRays(L);
  TriadOptions to = s.options;
  to.description = "inim triads: " + d.name + ", " + r.wavelengths.source;
  OutputSet outputs;
  ProgressBar bar("triads", uint64_t(rays.size()) * 3);
  r.triads = writeTriadSdf(outputs.add(s.out), rays, drive, r.wavelengths, to, &bar);
  bar.finish();
  outputs.commit();
  r.displayRays = rays.size();
  return r;
}

TriadFormResult formTriads(const TriadFormSettings& s) {
  requireFileKind(s.out, "out", {FileKind::Exr}, "an OpenEXR file name (.exr)");
  if (!s.png.empty()) requireFileKind(s.png, "png", {FileKind::Png}, "a PNG file name (.png)");
  Display d = loadDisplay(displayPathOrDefault(s.displayPath));
  EiLayout L = applyLayoutOverride(d, s.layout);
  if (s.gapMm) {
    checkGapMm(*s.gapMm, "", "gap_mm");
    L = L.withGap(*s.gapMm);
  }
  TriadFormResult r;
  r.wavelengths = parseTriadWavelengths(d.panel, s.wavelengths);
  const EiaFormation formed = formEiaFromSdf(L, s.sdfPath, r.wavelengths);
  const Image eia = onPanel(L, formed.eia);
  OutputSet outputs;
  writeImage(eia, outputs.add(s.out));
  if (!s.png.empty()) writeImage(encodeForPanel(eia, d.panel.eotf), outputs.add(s.png));
  outputs.commit();
  r.width = eia.width, r.height = eia.height;
  r.binned = formed.binned, r.missed = formed.missed, r.unknownWavelength = formed.unknownWavelength;
  return r;
}

std::string exportText(const TriadExportSettings& s, const TriadExportResult& r, double seconds) {
  const TriadWavelengths& w = r.wavelengths;
  return formatText("wrote %llu triad rays (%llu display rays; %.6g/%.6g/%.6g nm, %s) to %s in %.2f s\n",
                    (unsigned long long)r.triads, (unsigned long long)r.displayRays, w.nm[0], w.nm[1], w.nm[2],
                    w.source.c_str(), s.out.c_str(), seconds);
}

std::string formText(const TriadFormSettings& s, const TriadFormResult& r, double seconds) {
  return formatText("formed %s (%d x %d) from %s: %llu rays binned, %llu missed the detector, %llu of unknown "
                    "wavelength, in %.2f s\n",
                    s.out.c_str(), r.width, r.height, s.sdfPath.c_str(), (unsigned long long)r.binned,
                    (unsigned long long)r.missed, (unsigned long long)r.unknownWavelength, seconds);
}

std::string formWarning(const TriadFormResult& r) {
  if (!r.unknownWavelength) return "";
  return formatText("inim: warning: %llu rays have none of the triad wavelengths %.6g/%.6g/%.6g nm (within 0.5 nm); "
                    "check --triad-wavelengths\n",
                    (unsigned long long)r.unknownWavelength, r.wavelengths.nm[0], r.wavelengths.nm[1],
                    r.wavelengths.nm[2]);
}

}  // namespace inim
