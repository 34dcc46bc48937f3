#pragma once
// `inim capture` as a library: a posed dataset of an analytic scene (transforms.json + PNGs),
// framed by default on the part of the scene the display can show. Errors name settings
// (elevation_deg, target) before any rendering.
#include <string>

#include "capture/capture.h"
#include "field/field.h"

namespace inim {

struct CaptureRunSettings {
  std::string scenePath;               // "": scenes/paper-fig7.json
  std::string displayPath;             // frames the default target; "": the paper's prototype
  std::string elevationDeg = "50,90";  // min,max above the display plane
  std::string target;                  // x0,y0,z0,x1,y1,z1 in mm; "": captureTargetForDisplay
  CaptureSettings capture;             // its elevations, target and scene file are set from the above
  std::string outDir;
};

struct CaptureRunResult {
  std::string scenePath;
  CaptureResult capture;
};

// What a capture frames by default: the scene's bounds within the display's lenslet area in x
// and y and within the default VCP (+-kDefaultVcpMm) in z, so that a backdrop does not dwarf
// what the display can show. InputError naming the scene's `bounds` when nothing is left.
Box3d captureTargetForDisplay(const Field& scene, const std::string& scenePath, const std::string& displayPath);

CaptureRunResult runCapture(const CaptureRunSettings& s);
// What was captured and where transforms.json is.
std::string captureText(const CaptureRunSettings& s, const CaptureRunResult& r);

}  // namespace inim
