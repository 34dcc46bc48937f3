#pragma once
// Colour to the panel (docs/design.md): field radiance -> CIE XYZ -> the panel's
// native linear RGB -> exposure / white scaling -> gamut mapping -> linear drive values.
//
// The native RGB is defined by the panel's primaries: the matrix M whose columns are the XYZ
// of each primary's emission spectrum at drive value 1 (including its "scale"), normalised so
// that drive (1, 1, 1), the panel white at peak luminance, has Y = 1. Field luminance is
// relative: a field luminance Y = 1 / exposure drives the panel white (Y = 1). Spectral fields
// give XYZ directly (CIE 1931, the normalisation of spectrumToXYZ); RGB fields go through
// OpenColorIO from their declared colour space to cie_xyz_d65 first.
//
// Optional white scaling ("d65"): per-channel gains that make a D65 white drive (1, 1, 1), as a
// display that treats its input as sRGB-white-referenced does (the paper fed NeRF RGB straight
// to the panel). The default ("none") is colorimetric: D65 is shown as D65 if the panel can.
//
// Out of gamut: any channel < 0 or > 1 (beyond a 1e-6 rounding allowance) after exposure.
// Mapping: `clip` clamps each channel to [0, 1] (keeps hue poorly, simple); `desaturate` moves
// the colour toward the grey of equal panel luminance until it fits, keeping luminance (and
// clamps the grey itself to [0, 1] when the luminance is outside it).
#include <algorithm>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "calibration/colour_model.h"
#include "core/geometry.h"
#include "display/panel.h"
#include "spectral/spectrum.h"

namespace inim {

enum class GamutMapping { Clip, Desaturate };
const char* gamutName(GamutMapping g);
GamutMapping parseGamut(const std::string& s, const std::string& key = "gamut");

class PanelColor {
 public:
  PanelColor() = default;
  explicit PanelColor(const Panel& panel);

  // Columns: XYZ of R, G, B at drive 1, normalised so drive (1,1,1) has Y = 1.
  const glm::dmat3& driveToXYZ() const { return driveToXYZ_; }
  const glm::dmat3& xyzToDrive() const { return xyzToDrive_; }
  Vec3d whiteXYZ() const { return driveToXYZ_ * Vec3d(1.0); }
  // Luminance of each primary at drive 1 (sums to 1): Y = dot(weights, drive).
  Vec3d luminanceWeights() const { return {driveToXYZ_[0].y, driveToXYZ_[1].y, driveToXYZ_[2].y}; }
  // Chromaticities (x, y) of the primaries and the white, for reports.
  Vec2 primaryXY(int c) const;
  Vec2 whiteXY() const;
  double peakLuminanceCdM2() const { return peak_; }

  Vec3d driveFromXYZ(const Vec3d& xyz) const { return xyzToDrive_ * xyz; }
  // Exact (integrated, no sampling) drive of an emission spectrum.
  Vec3d driveFromSpectrum(const Spectrum& s) const;
  // Gains that make D65 (Y = 1) drive (1, 1, 1).
  Vec3d d65WhiteGains() const;

 private:
  glm::dmat3 driveToXYZ_{1.0}, xyzToDrive_{1.0};
  double peak_ = 0.0;
};

// Converts linear RGB triples of an OCIO colour space to XYZ (cie_xyz_d65), in place.
void rgbToXYZInPlace(std::span<Vec3> rgb, const std::string& colorSpace);

struct GamutStats {
  uint64_t pixels = 0;       // drive triples checked
  uint64_t outOfGamut = 0;   // any channel < 0 or > 1 before mapping
  uint64_t negative = 0;     // ... of which some channel < 0 (outside the primaries' triangle)
  uint64_t overRange = 0;    // ... of which some channel > 1 (brighter than the panel can show)
  double maxChannel = 0.0;   // before mapping
  double minChannel = 0.0;
  GamutStats& operator+=(const GamutStats& o);
};

constexpr float kGamutTolerance = 1e-6f;

// Maps one drive triple into [0, 1]^3; returns true if it was out of gamut.
bool mapToGamut(Vec3& drive, const Vec3& luminanceWeights, GamutMapping mapping);
// Same, accumulating statistics.
inline void mapToGamut(Vec3& drive, const Vec3& w, GamutMapping m, GamutStats& st) {
  ++st.pixels;
  float lo = std::min(drive.x, std::min(drive.y, drive.z)), hi = maxComponent(drive);
  st.maxChannel = std::max(st.maxChannel, double(hi));
  st.minChannel = std::min(st.minChannel, double(lo));
  if (mapToGamut(drive, w, m)) {
    ++st.outOfGamut;
    if (lo < -kGamutTolerance) ++st.negative;
    if (hi > 1.0f + kGamutTolerance) ++st.overRange;
  }
}

// The colour path of `inim eia` from a field colour (XYZ) to the drive values on the panel, in
// one place so that `inim calibrate` drives its patches exactly as an EIA is made:
// native drive (xyzToDrive, in float as the synthesis computes it) -> exposure x white gains ->
// gamut mapping -> the optional panel-side correction (a calibration LUT or model, drive ->
// drive), whose output is clamped to [0, 1] since a panel cannot go beyond full drive.
struct DriveSettings {
  double exposure = 1.0;
  bool whiteBalanceD65 = false;
  GamutMapping gamut = GamutMapping::Clip;
  std::shared_ptr<const ColourModel> correction;  // null: uncalibrated
};

class FieldToDrive {
 public:
  FieldToDrive(const PanelColor& color, const DriveSettings& settings);
  // Native linear drive of an XYZ (field luminance units), before exposure.
  Vec3 native(const Vec3& xyz) const { return xyzToDrive_ * xyz; }
  // Exposure, white gains, gamut mapping (counted in `stats`) and correction of a native drive.
  Vec3 fromNative(const Vec3& nativeDrive, GamutStats& stats) const;
  Vec3 fromXyz(const Vec3& xyz, GamutStats& stats) const { return fromNative(native(xyz), stats); }
  Vec3 fromXyz(const Vec3& xyz) const;
  const Vec3& gains() const { return gains_; }
  const DriveSettings& settings() const { return settings_; }

 private:
  DriveSettings settings_;
  glm::mat3 xyzToDrive_;
  Vec3 gains_, lumWeights_;
};

}  // namespace inim
