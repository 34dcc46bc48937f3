#pragma once
// Fig. 11's error against depth (Fig11Settings::depthError): where in depth the reconstruction
// departs from the reference. The reference is rendered with its depth channels
// (ReferenceSettings::depth); they are taken off before it is exposed and written, so the
// reference images stay R, G, B. Per pose the error is binned by scene depth
// (analysis/depth_error.h) over the pixels that see the display; at the end one figure has a
// curve per pose with the MLA plane (z = 0), the reference image plane L of the
// reconstruction (through the cover glass when the display has one) and its depth-of-field
// band (|z| <= DisplayInfo's depth range: lateral sampling max(P, P |z| / g) <= 2P) marked.
//
// Outputs, in the run's OutputSet: depth_error_<pose>.csv, reference_<pose>_depth.exr (A, Z, dZ),
// depth_error.png; metrics.json gains "depth_error" per pose.
//
//   ReferenceDepth d = takeDepthChannels(ref.image);        // before exposing
//   depth.addPose(name, label, {refLin, recLin, refSrgb, recSrgb}, d, mask, deltaE, metrics[name]);
//   depth.writeFigure(display);                              // after the last pose
#include <filesystem>
#include <string>
#include <vector>

#include "analysis/depth_error.h"
#include "core/image.h"
#include "core/json_config.h"
#include "core/output_file.h"
#include "core/pixel_mask.h"
#include "display/display.h"

namespace inim {

// The reference's Z, A and dZ channels.
struct ReferenceDepth : DepthMap {
  bool present = false;
  int width = 0, height = 0;
};

// Moves the A, Z and dZ channels out of `reference` (which keeps its other channels, in order).
// Nothing is present when the image has no Z channel.
ReferenceDepth takeDepthChannels(Image& reference);

// One pose's images as fig11 compares them: linear camera RGB exposed alike, and their sRGB.
struct Fig11PoseImages {
  const Image& refLinear;
  const Image& recLinear;
  const Image& refSrgb;
  const Image& recSrgb;
};

// The marks of the figure from a display: L and the depth range of its reconstruction.
DepthMarks depthMarksFor(const Display& display);

class Fig11DepthError {
 public:
  Fig11DepthError(OutputSet& outputs, std::filesystem::path dir) : outputs_(outputs), dir_(std::move(dir)) {}

  // Bins the pose's error (default binning; `deltaE`: the CIEDE2000 map of the sRGB images, as
  // compareImages gives it), writes its CSV and depth EXR, sets poseMetrics["depth_error"] and
  // returns the bins. Nothing (empty) when `depth` is not present.
  std::vector<DepthBin> addPose(const std::string& name, const std::string& label, const Fig11PoseImages& img,
                                const ReferenceDepth& depth, const PixelMask& mask, const std::vector<float>& deltaE,
                                Json& poseMetrics);
  // depth_error.png, a curve per pose added; nothing when none was.
  void writeFigure(const Display& display);

  const std::vector<DepthErrorCurve>& curves() const { return curves_; }

 private:
  std::string out(const std::string& name) { return outputs_.add((dir_ / name).string()); }

  OutputSet& outputs_;
  std::filesystem::path dir_;
  std::vector<DepthErrorCurve> curves_;
};

}  // namespace inim
