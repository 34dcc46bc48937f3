#pragma once
// The viewing camera's sensor: pixel grid and pitch, per-channel spectral sensitivity, and a
// camera RGB -> CIE XYZ matrix fitted by least squares against the CIE 1931 CMFs.
//
// Camera RGB is white balanced: each raw channel response is scaled so that D65 with
// luminance Y = 1 gives camera RGB (1, 1, 1). The 3x3 matrix M (XYZ = M rgb) is fitted on a
// training set of smooth reflectances under D65 (fitCameraRgbToXyz) with the constraint
// M (1,1,1) = XYZ(D65), so a D65 white maps exactly to Y = 1.
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "core/json_config.h"
#include "spectral/spectrum.h"

namespace inim {

struct SensorGeometry {
  int widthPx = 0, heightPx = 0;
  double pitchMm = 0.0;
  double widthMm() const { return widthPx * pitchMm; }
  double heightMm() const { return heightPx * pitchMm; }
  double halfDiagonalMm() const { return 0.5 * std::sqrt(widthMm() * widthMm() + heightMm() * heightMm()); }
};

struct ColorFit {
  glm::dmat3 cameraToXyz{1.0};  // white-balanced camera RGB -> XYZ (column-major glm)
  Vec3d whiteBalance{1.0};      // gains on the raw channel responses (D65 at Y = 1 -> (1,1,1))
  Vec3d whiteXyz{0.0};          // XYZ of D65 at Y = 1 (= cameraToXyz * (1,1,1))
  int trainingSpectra = 0;
  double meanDeltaE00 = 0.0;    // CIEDE2000 on the training set, reference white D65
  double maxDeltaE00 = 0.0;
  double rmsXyz = 0.0;          // RMS of the XYZ residuals (Y of the white = 1)
};

// The training set: 4 greys, Gaussian band-pass (centres 400-700 nm every 25 nm, FWHM 40
// and 100 nm) and band-stop (FWHM 80 nm) reflectances, and smooth long- and short-pass edges
// (425-675 nm every 25 nm): smooth spectra spanning hues and saturations, like a colour chart.
// Sampled at 1 nm over 360-830 nm.
std::vector<std::vector<double>> colorTrainingReflectances();

// Fits the white-balanced camera RGB -> XYZ matrix for sensitivities r, g, b (relative).
ColorFit fitCameraRgbToXyz(const Spectrum& r, const Spectrum& g, const Spectrum& b);

class CameraSensor {
 public:
  CameraSensor() = default;
  CameraSensor(std::string name, SensorGeometry geometry, SpectrumPtr r, SpectrumPtr g, SpectrumPtr b,
               std::string sensitivitySource = "");

  const std::string& name() const { return name_; }
  const SensorGeometry& geometry() const { return geometry_; }
  const std::string& sensitivitySource() const { return source_; }
  bool hasSensitivity() const { return r_ != nullptr; }

  // Channel sensitivities at a wavelength: as tabulated, and white balanced.
  Vec3d rawResponse(double lambdaNm) const;
  Vec3d response(double lambdaNm) const { return rawResponse(lambdaNm) * fit_.whiteBalance; }
  // White-balanced camera RGB of a spectral radiance (1 nm trapezoid over 360-830 nm);
  // D65 with Y = 1 gives (1, 1, 1).
  Vec3d cameraRgb(const Spectrum& radiance) const;
  Vec3d toXyz(const Vec3d& cameraRgb) const { return fit_.cameraToXyz * cameraRgb; }
  // XYZ -> white-balanced camera RGB, the inverse of toXyz: how a colour known only as XYZ (an
  // RGB field's, the observer's) becomes camera RGB.
  glm::dmat3 xyzToCameraRgb() const { return glm::inverse(fit_.cameraToXyz); }
  const ColorFit& colorFit() const { return fit_; }

 private:
  std::string name_, source_;
  SensorGeometry geometry_;
  SpectrumPtr r_, g_, b_;
  ColorFit fit_;
};

// A sensor description (an object of a camera file): width_px, height_px, pixel_pitch_mm,
// spectral_sensitivity (a CSV with columns wavelength_nm,r,g,b; relative to the camera file
// or to the data folder), optional name and channels (column names, default ["r","g","b"]).
CameraSensor parseSensor(const JsonObject& o);

}  // namespace inim
