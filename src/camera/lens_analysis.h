#pragma once
// First-order properties of a lens found by real ray tracing: near-axis rays at two small
// heights (or angles), extrapolated to zero height (Richardson), so the results are the
// paraxial values without a separate paraxial (y-nu) trace. Focal lengths are in air.
#include <string>

#include "camera/lens_system.h"
#include "core/json_config.h"

namespace inim {

struct PupilInfo {
  double positionMm = 0.0;  // entrance: from the first vertex; exit: from the last vertex; +z toward the image
  double diameterMm = 0.0;
};

struct LensInfo {
  std::string name, file;
  double wavelengthNm = kLensReferenceLambdaNm;
  int surfaceCount = 0;
  int stopSurface = -1;
  double stopDiameterMm = 0.0;
  double eflMm = 0.0;           // effective focal length
  double bflMm = 0.0;           // last vertex -> rear focal point (F')
  double fflMm = 0.0;           // front focal point (F) -> first vertex (positive when F is in front)
  double fNumber = 0.0;         // EFL / entrance pupil diameter (object at infinity)
  PupilInfo entrancePupil;      // image of the stop seen from the object side
  PupilInfo exitPupil;          // image of the stop seen from the image side
  double frontPrincipalMm = 0.0;  // principal plane P from the first vertex (+z toward the image)
  double rearPrincipalMm = 0.0;   // principal plane P' from the last vertex
  double lengthMm = 0.0;        // first vertex -> last vertex
  double totalTrackMm = 0.0;    // first vertex -> rear focal point (length + BFL)
  bool dispersive = false;
  LensDesignInfo design;                // what the file says beyond its surfaces (Zemax files)
  std::vector<std::string> surfaceRows;  // one line per surface as read: radius, thickness, medium, ...
};

LensInfo analyzeLens(const LensSystem& lens, double lambdaNm = kLensReferenceLambdaNm);

// Human-readable report (one quantity per line) and JSON (keys efl_mm, bfl_mm, ffl_mm,
// f_number, entrance_pupil {position_mm, diameter_mm, measured_from}, exit_pupil {...},
// total_track_mm, ...). The CLI's `inim lens info FILE [--json]` prints these.
std::string lensInfoText(const LensInfo& info);
Json lensInfoJson(const LensInfo& info);
inline std::string lensInfoText(const LensSystem& lens, double lambdaNm = kLensReferenceLambdaNm) {
  return lensInfoText(analyzeLens(lens, lambdaNm));
}
inline Json lensInfoJson(const LensSystem& lens, double lambdaNm = kLensReferenceLambdaNm) {
  return lensInfoJson(analyzeLens(lens, lambdaNm));
}

// Where the paraxial image of an axial object point at lens z = objectZ (< 0: in front of
// the first vertex; -infinity: object at infinity) lies, as a distance behind the last vertex.
double paraxialImageDistance(const LensSystem& lens, double objectZ, double lambdaNm = kLensReferenceLambdaNm);

// A small height for near-axis rays: 1e-3 of the smallest clear semi-aperture.
double nearAxisHeight(const LensSystem& lens);

}  // namespace inim
