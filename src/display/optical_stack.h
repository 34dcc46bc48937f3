#pragma once
// A display's optics as a stack of layers from the panel outward (optics/README.md, "Optical
// stacks"): lens arrays (a lattice of lenslets, each with a back and a front surface), plates,
// aperture arrays, barrier walls and air gaps, optionally curved as a whole.
//
// Frame: z along the stack's axis, 0 at the panel's emitting plane, + toward the viewer; the
// layers follow one another without overlap, each from its back plane to its front plane.
// Surfaces follow the optical-design convention: light runs from the panel to the viewer, a
// radius > 0 has its centre of curvature on the viewer's side of the vertex, 0 is a plane. A
// lens array's vertices lie on its layer's back and front planes; a surface may bulge out of
// its layer only into a neighbouring air gap (or barrier layer) deep enough to hold it.
#include <optional>
#include <string>
#include <vector>

#include "core/json_config.h"
#include "display/curved_frame.h"
#include "display/mla.h"

namespace inim {

// An even asphere: z(r) = c r^2 / (1 + sqrt(1 - (1 + k) c^2 r^2)) + sum_i a_i r^(2 i + 4),
// c = 1 / R; a plane when R = 0 and no terms.
struct StackSurface {
  double radiusMm = 0.0;            // signed; 0: flat
  double conic = 0.0;
  std::vector<double> asphereMm;    // a_4, a_6, ...: coefficients of r^4, r^6, ... (mm^(1-2i-4))
  double curvature() const { return radiusMm == 0.0 ? 0.0 : 1.0 / radiusMm; }
  bool isPlane() const;
  // Sag at radius r from the vertex; nullopt where the conic is undefined (no real surface).
  std::optional<double> sag(double r) const;
};

struct StackLayer {
  enum class Kind { Gap, Plate, LensArray, Apertures, Barriers };
  Kind kind = Kind::Gap;
  std::string keyPath;              // "stack.layers[2]", for messages
  double thicknessMm = 0.0;         // back plane to front plane (a barrier layer: its height)
  std::string material;             // plate and lens array: a dielectric; empty: air
  // Lattice of lens arrays, aperture arrays and barriers.
  Mla::Lattice lattice = Mla::Lattice::Square;
  double pitchMm = 0.0;
  // The lattice's shift from where the display's EI layout centres its lenslets (each EI
  // behind its lenslet).
  double offsetXMm = 0.0, offsetYMm = 0.0;
  std::optional<int> cols, rows;    // lenslets (holes, cells); unbounded when not given
  // Lens arrays.
  StackSurface back, front;
  Mla::Aperture aperture = Mla::Aperture::Square;
  double apertureMm = 0.0;          // clear aperture: square side, circle diameter, hex flat to flat
  // Aperture arrays: one hole per lattice cell in an opaque sheet.
  Mla::Aperture hole = Mla::Aperture::Circle;
  double holeMm = 0.0;
  // Barriers: opaque walls along the cell borders, thicknessMm high and wallMm wide.
  double wallMm = 0.0;
  double reflectance = 0.0;         // of the walls (0: absorbing)

  // Largest distance from a lenslet's axis to its clear aperture's edge.
  double apertureRadiusMm() const;
};

struct StackCurvature {
  enum class Shape { Cylinder, Sphere };
  Shape shape = Shape::Sphere;
  double radiusMm = 0.0;            // > 0: centre of curvature on the viewer's side
};

struct OpticalStack {
  std::string file;
  std::vector<StackLayer> layers;   // from the panel outward
  std::optional<StackCurvature> curvature;  // lenslet centres on a cylinder (axis y) or sphere
  std::optional<double> panelRadiusMm;      // a curved panel (same shape as the array)
  double panelWidthMm = 0.0, panelHeightMm = 0.0;  // the panel's active area (parseOpticalStack's)

  double totalThicknessMm() const;
  // z of layer i's back plane.
  double layerBackZ(size_t i) const;
  int lensArrayCount() const;
  // The frame the layers are flat in (curved_frame.h): bent around the curvature's centre, the
  // reference shell through the back plane of the first layer that is not an air gap; flat
  // without curvature.
  CurvedFrame arrayFrame() const;
  // The panel's: a shell of panel_radius_mm through the panel's vertex (z = 0), of the array's
  // shape; flat without panel_radius_mm.
  CurvedFrame panelFrame() const;
  bool curved() const { return curvature.has_value() || panelRadiusMm.has_value(); }
};

const char* layerKindName(StackLayer::Kind k);

// Where the axis of the lenslet at lattice point (x, y) (a curved stack's: the line from the
// centre of curvature through it) meets the panel, in the panel's coordinates (a flat panel's
// x, y; a curved one's arc coordinates); a flat stack's axes meet it at (x, y).
void axisFootOnPanel(const OpticalStack& s, double x, double y, double& px, double& py);

// Reads "stack": {"layers": [...], "curvature": {...}, "panel_radius_mm": R} and validates it
// against a panel of the given active size (mm): layers that overlap, surfaces undefined or
// crossing inside their aperture, a curvature radius below half the array, a lattice that does
// not cover the panel; InputError naming the file, the key path and the value.
OpticalStack parseOpticalStack(const JsonObject& stack, double panelWidthMm, double panelHeightMm);

// The stack a display of today describes: an air gap, then its MLA as one lens array (a flat
// face and the lenslet cap, on the side the MLA's orientation gives), placed so that the lenslets'
// panel-side principal plane lies at gapMm from the panel, as the display's gaps are measured.
// The MLA's focal length decides R when the file gives no radius (R = (n_d - 1) f).
OpticalStack stackFromMla(const Mla& mla, double gapMm);

// The other way: the MLA (and the panel-to-H gap, mm) a stack is, when it is what the ray
// tracer of today models: air gaps, then one lens array with a flat face and one convex
// spherical or conic cap, nothing in front of it, flat, on the layout's lenslet centres.
// nullopt otherwise, with `why` saying what is beyond that.
struct StackAsMla {
  Mla mla;
  double gapMm = 0.0;
};
std::optional<StackAsMla> mlaFromStack(const OpticalStack& stack, std::string& why);

// For a stack the MLA of today does not describe: the MLA that stands in for it where the EI
// layout and the pinhole model need one (the first lens array's lattice, pitch and aperture,
// the stack's effective focal length at n_d, its material), and the gap from the panel to the
// stack's front principal plane H (reduced to air). The stack's own tracer refracts through
// every layer; this MLA only places the EIs.
StackAsMla equivalentMla(const OpticalStack& stack);

}  // namespace inim
