#pragma once
// Triads: every display ray becomes three monochromatic rays, one per panel primary, each
// carrying its drive value as flux (docs/design.md). Exported as a Zemax
// spectral source file (as the paper's code did: origin at the pinhole, direction negated
// so it points back at the panel, order R, G, B per display ray), and turned back into an
// EIA by straight propagation to a detector at the panel plane z = -g.
#include <array>
#include <string>
#include <vector>

#include "core/image.h"
#include "display/panel.h"
#include "rays/ray_set.h"
#include "triads/sdf.h"

namespace inim {

class ProgressBar;

struct TriadWavelengths {
  std::array<double, 3> nm{};  // R, G, B
  std::string source;
};
// "panel": the peaks of the panel's primaries (default); "paper": 656/566/471 nm (the paper's
// code); "zemax-sequential": 620/525/460 nm (the paper's sequential model). InputError for
// another name.
TriadWavelengths triadWavelengths(const Panel& panel, const std::string& choice = "panel");
TriadWavelengths paperTriadWavelengths();
// Triad wavelengths from "panel", "paper", "zemax-sequential" or "R,G,B" in nm (each in
// 360-830 nm, at least 2 nm apart so EIA formation can tell them apart). InputError naming
// `key` otherwise.
TriadWavelengths parseTriadWavelengths(const Panel& panel, const std::string& text,
                                       const std::string& key = "triad_wavelengths");

struct TriadOptions {
  float fluxScale = 1.0f;      // flux = drive value x fluxScale
  bool skipZeroFlux = false;   // leave out triad rays with flux 0 (the paper wrote them all)
  std::string description = "inim display triads";
  bool raySetFluxIsSum = false;  // header ray-set flux: 1 (paper) or the sum of ray fluxes
};

// The three triad rays of display ray `r` (drive = 3 values R, G, B).
void makeTriad(const Ray& displayRay, const float* drive, const TriadWavelengths& w, float fluxScale,
               SdfRay out[3]);
// All triads in memory (3 N rays: display ray order, then R, G, B).
std::vector<SdfRay> expandTriads(const RaySet& rays, const std::vector<float>& drive,
                                 const TriadWavelengths& w, const TriadOptions& options = {});
// Streams the triads to an SDF file in chunks (expanded in parallel, written in order).
// Returns the number of triad rays written.
uint64_t writeTriadSdf(const std::string& path, const RaySet& rays, const std::vector<float>& drive,
                       const TriadWavelengths& w, const TriadOptions& options = {},
                       ProgressBar* progress = nullptr);

// EIA formation: each triad ray is propagated in a straight line to the detector plane
// z = -L.gapMm (the panel), its flux binned into the EIA pixel it lands on, in the channel of
// its wavelength (the nearest triad wavelength within 0.5 nm).
struct EiaFormation {
  Image eia;                // L.eiaW x L.eiaH, channels R, G, B: summed flux
  uint64_t binned = 0;      // rays that landed on the EIA
  uint64_t missed = 0;      // rays off the detector or not heading toward it
  uint64_t unknownWavelength = 0;
};
EiaFormation formEia(const EiLayout& L, const std::vector<SdfRay>& triads, const TriadWavelengths& w);
EiaFormation formEiaFromSdf(const EiLayout& L, const std::string& sdfPath, const TriadWavelengths& w,
                            ProgressBar* progress = nullptr);

}  // namespace inim
