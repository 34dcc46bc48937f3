#pragma once
// What the panel emits: the spectral radiance leaving a point of the panel's emitting plane
// (display frame, z = -g) in a direction, at a wavelength, for an EIA of drive values.
//
//   PanelEmitter e(display.panel, layout, readImage("eia.exr"), "eia.exr");
//   PanelEmission em = e.emit(arrival, lambdaNm);          // from an MlaModel arrival
//   float L = em.weight * e.channelSpectrum(em.channel, lambdaNm);
//
// Model (docs/design.md):
//  - Pixels. EIA pixel (c, r) is panel pixel (panelCol0 + c, panelRow0 + r); its centre is at
//    x = (c + 0.5 - eiaW/2) p, y = (eiaH/2 - r - 0.5) p (ei_layout.h). Points off the panel
//    emit nothing.
//  - Subpixels. The panel's SubpixelLayout repeats every tileW x tileH pixels from panel pixel
//    (0, 0). A point inside a subpixel polygon emits that subpixel's primary; the black matrix
//    (everything outside the polygons) emits nothing. A polygon belongs to the pixel of the tile
//    that holds its area centroid, and takes that pixel's drive value of its channel.
//  - Drive values. The EIA holds LINEAR drive values in [0, 1] (what `inim eia` writes in its
//    EXR: the panel's EOTF has already been applied to the encoded values), so radiance is
//    proportional to the drive value; values are clamped to [0, 1] (a panel cannot emit more
//    than full drive or less than black). An 8-bit image (PNG) holds ENCODED values: pass
//    `encoded = true` and the panel's EOTF decodes them first.
//  - Spectrum and scale. A subpixel of channel c at drive d emits
//        L(lambda) = d * K_c * L0 * primary_c(lambda) * a(theta) * T(theta)/T(0)
//    with K_c = tile area / emitting area of channel c (the area normalisation: full drive on
//    every subpixel averages, over a tile, to L0 * sum_c primary_c, the panel white, whatever the
//    fill factor), and L0 chosen so that the panel white has CIE luminance Y (spectrumToXYZ
//    normalisation, integral of y_bar = 1) = the panel's peak_luminance_cd_m2 (absolute units:
//    radiance is then in "cd/m^2 per unit Y", and camera RGB of a D65 grey of luminance Y is
//    (Y, Y, Y)), or Y = 1 with `absolute = false`.
//  - Angular profile a(theta), theta the emission angle from the normal (inside the cover glass
//    when there is one): "lambertian" = constant radiance (a = 1); "uniform" = uniform radiant
//    intensity (a = 1/cos theta, capped at cos theta = 0.05), times cos^n theta with
//    `cosExponent` = n (0 by default). a(0) = 1: peak luminance is the on-axis value.
//  - Cover glass (when the panel has one and `coverGlass` is on): a flat plate of thickness t and
//    index n(lambda) from spectra/materials.json on the emitting plane (z from -g to -g + t).
//    The arriving ray (traced through air to z = -g by the MLA model) is refracted at the plate's
//    top, z = -g + t, and reaches the emitter at the laterally offset point; the exterior
//    radiance is scaled by the unpolarised Fresnel transmittance relative to normal incidence,
//    T(theta)/T(0), so the peak luminance stays the on-axis value seen through the glass.
//    A dispersive glass makes the emitter wavelength dependent (isDispersive()).
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "core/geometry.h"
#include "core/image.h"
#include "display/ei_layout.h"
#include "display/panel.h"
#include "mla_optics/mla_model.h"
#include "spectral/dispersion.h"
#include "spectral/spectrum.h"

namespace inim {

using Vec2d = glm::dvec2;  // (the same alias as camera/lens_system.h)

struct EmitterSettings {
  bool absolute = true;      // L0 from the peak luminance (cd/m^2); false: panel white Y = 1
  double cosExponent = 0.0;  // extra cos^n theta on the panel's angular profile
  bool coverGlass = true;    // model the panel's cover glass when it has one
  bool encoded = false;      // the drive image holds EOTF-encoded values (decode them first)
  // The driveTable() of an emitter made from the same image and panel (the error budget's
  // rungs, which differ in the layout or the optics only): shared instead of read again.
  std::shared_ptr<const std::vector<float>> drive;
};

// The emitting subpixel at a point and the wavelength-independent part of its radiance:
// L(lambda) = weight * channelSpectrum(channel, lambda). channel = -1: nothing emits there.
struct PanelEmission {
  int channel = -1;
  float weight = 0.0f;
};

class PanelEmitter {
 public:
  // `drive`: the EIA (channels R, G, B, found by name, else the first three) at the panel's
  // resolution, or at the EIA area's size (then placed where the layout puts it). `file` names
  // the image in errors. InputError (naming the file, the key "resolution" and both sizes) for
  // any other size; InputError for fewer than 3 channels, non-finite values, or an unknown
  // cover-glass material. `gapMm`: where the emitting plane sits (z = -gapMm), normally the
  // display's reconstruction gap.
  PanelEmitter(const Panel& panel, const EiLayout& layout, const Image& drive, const std::string& file,
               double gapMm, const EmitterSettings& settings = {});

  // The subpixel under a point of the emitting plane (display frame x, y in mm), with its
  // drive value as weight (no angular or glass factor).
  PanelEmission lookup(double x, double y) const;
  // The same in continuous panel pixel coordinates (u right, v down).
  PanelEmission lookupPx(double u, double v) const;
  Vec2d toPanelPx(double x, double y) const { return {x / pitch_ + uOff_, vOff_ - y / pitch_}; }
  // Emission toward the viewer for a ray that reached the emitting plane at `a.p` travelling
  // along `a.d` (d.z < 0), at a wavelength (used for the cover glass only).
  PanelEmission emit(const Point3& p, const Vec3& d, float lambdaNm) const;
  PanelEmission emit(const PanelArrival& a, float lambdaNm) const { return emit(a.p, a.d, lambdaNm); }
  // Full spectral radiance along -d at p (0 on the black matrix and off the panel).
  float radiance(const Point3& p, const Vec3& d, float lambdaNm) const;

  // The two halves of emit(), for estimators that filter over an area of the panel:
  // where a ray that reached the emitting plane at `p` along `d` meets the emitter (after the
  // cover glass, when there is one), in continuous panel pixel coordinates (u right, v down),
  // and the factor emit() applies to the drive value there (angular profile x relative glass
  // transmittance). False when nothing can emit toward the ray (d.z >= 0).
  // emit(p, d, l) == lookupPx(uv) with its weight times `factor`.
  bool emissionPointPx(const Point3& p, const Vec3& d, float lambdaNm, Vec2d& uv, float& factor) const;
  // Average over the axis-aligned box [u0, u1] x [v0, v1] (panel pixel coordinates) of the
  // emission per channel: (1 / box area) x sum over the subpixels of channel c of
  // (area of subpixel n box) x its drive value. Exact: rectangles by their overlap, other
  // polygons by clipping them to the box (Sutherland-Hodgman; exact area for any simple
  // polygon). The black matrix and the area off the panel count as 0. A box of zero area is a
  // point lookup (the channel of lookupPx gets its weight, the others 0).
  std::array<float, kNumPrimaries> boxAveragePx(double u0, double v0, double u1, double v1) const;
  // The same for one channel only (its own subpixels: the Quadrature estimator's lookup).
  float channelBoxAveragePx(int c, double u0, double v0, double u1, double v1) const;
  // channelBoxAveragePx of every channel over one box, equal to three calls bit for bit; a
  // stripe layout's channels share the box's tiles and rows, and their columns where their
  // rectangles coincide (the Quadrature estimator's lookup when nothing is dispersive).
  std::array<float, kNumPrimaries> channelBoxAveragesPx(double u0, double v0, double u1, double v1) const;
  // The drive value of channel c at a point (panel pixel coordinates): lookupPx(u, v).weight
  // when lookupPx(u, v).channel == c, else 0 (up to points exactly on a rectangle's edge).
  // Tests only channel c's subpixels, axis-aligned rectangles by their bounds: the cheap
  // lookup of the Quadrature estimator where it has no lenslet map (quadrature_estimator.h).
  float channelDrivePx(int c, double u, double v) const;

  // Radiance spectrum of a channel's subpixel at full drive on axis: K_c L0 primary_c(lambda).
  float channelSpectrum(int channel, float lambdaNm) const;
  // L0 primary_c(lambda): a channel's contribution to the tile-averaged panel white.
  float averageChannelSpectrum(int channel, float lambdaNm) const;
  // XYZ (spectrumToXYZ normalisation) of the panel white: the tile average at full drive.
  Vec3d whiteXyz() const;
  double areaFactor(int channel) const { return areaFactor_[size_t(channel)]; }  // K_c
  double luminanceScale() const { return l0_; }                                     // L0
  bool isDispersive() const { return glassIor_ != nullptr && glassIor_->isDispersive(); }
  bool hasCoverGlass() const { return glassIor_ != nullptr; }
  double gapMm() const { return gap_; }
  // Panel extent in the display frame (mm), for framing and warnings.
  double panelMinX() const { return -uOff_ * pitch_; }
  double panelMaxX() const { return (panelW_ - uOff_) * pitch_; }
  double panelMinY() const { return (vOff_ - panelH_) * pitch_; }
  double panelMaxY() const { return vOff_ * pitch_; }
  const Panel& panel() const { return panel_; }
  // True when `o` emits as this one does wherever their subpixels coincide: the same panel
  // placement, emitting plane, cover glass, angular profile and primaries (L0 primary_c on a
  // 1 nm grid); they may differ in the subpixel layout and the drive values only. Such panels
  // can be seen through one pass of the same optics (renderViews).
  bool emitsLike(const PanelEmitter& o) const;
  // The drive values (panelW x panelH x RGB), for EmitterSettings::drive.
  std::shared_ptr<const std::vector<float>> driveTable() const { return driveTable_; }

 private:
  struct Poly {
    int channel = 0;
    int pixU = 0, pixV = 0;  // pixel of the tile that owns it
    float u0, v0, u1, v1;    // bounding box, tile coordinates (pixels)
    std::vector<std::array<float, 2>> pts;
    bool rect = false;       // an axis-aligned rectangle (its bounding box)
  };
  // The constructor's steps (panel_emitter.cpp).
  void readDrive(const EiLayout& L, const Image& img, const std::string& file);
  static Poly makePoly(const Subpixel& sp, int tileW, int tileH);
  void placeSubpixels();
  void readPrimariesAndGlass();
  double polyBoxArea(const Poly& p, double u0, double v0, double u1, double v1) const;
  static constexpr int kMaxBoxTiles = 40;  // per side, for channelBoxAveragePx's stripe path
  struct SideOverlaps {
    int n = 0;
    double length[kMaxBoxTiles];
    int index[kMaxBoxTiles];  // pixel column or row
  };
  static bool sideOverlaps(double b0, double b1, int t0, int t1, int w, float r0, float r1, int pix, int limit,
                           SideOverlaps& out);
  // A box clipped to the panel and the tiles it touches; false when it misses the panel.
  struct BoxTiles {
    double cu0, cv0, cu1, cv1;
    int tu0, tu1, tv0, tv1;
  };
  bool boxTiles(double u0, double v0, double u1, double v1, BoxTiles& b) const;
  // Channel c's rectangle overlaps with a box's columns and rows (the stripe layouts: one
  // rectangle of each channel per tile); false when the channel has another shape or the box
  // spans more than kMaxBoxTiles tiles.
  bool channelColumns(int c, const BoxTiles& b, SideOverlaps& cols) const;
  bool channelRows(int c, const BoxTiles& b, SideOverlaps& rows) const;
  // Sum over the overlaps of (column length x row length x channel c's drive).
  double overlapSum(int c, const SideOverlaps& cols, const SideOverlaps& rows) const;
  double boxSumByPolygons(int c, const BoxTiles& b) const;
  // Channel c's one rectangle per tile, or null (an index, so that copies stay valid).
  const Poly* channelRect(int c) const {
    return channelRect_[size_t(c)] < 0 ? nullptr : &polys_[size_t(channelRect_[size_t(c)])];
  }
  float angular(float cosTheta) const;

  Panel panel_;
  EmitterSettings settings_;
  int panelW_ = 0, panelH_ = 0, tileW_ = 1, tileH_ = 1;
  double pitch_ = 0.0, uOff_ = 0.0, vOff_ = 0.0, gap_ = 0.0;
  std::shared_ptr<const std::vector<float>> driveTable_;  // panelW x panelH x 3, clamped to [0, 1]
  const float* drive_ = nullptr;                          // its values
  std::vector<Poly> polys_;
  std::array<std::vector<int>, kNumPrimaries> channelPolys_;  // indices into polys_ per channel
  std::array<int, kNumPrimaries> channelRect_{-1, -1, -1};     // index of the channel's one rectangle, if so
  std::array<SpectrumPtr, kNumPrimaries> primary_;
  std::array<double, kNumPrimaries> areaFactor_{};
  double l0_ = 1.0;
  bool uniformIntensity_ = false;
  IorPtr glassIor_;
  double glassT_ = 0.0;
};

}  // namespace inim
