#pragma once
// The view simulation's MLA for a display given as an optical stack that today's MLA does not
// describe (Display::stackTraced): StackTracer in the display frame, the panel at z = -gap,
// the lattices placed on the EI layout's lenslet centres. Lenslet indices are the layout's
// lenslet nearest the point where the ray last refracted at a lens surface.
#include <memory>

#include "display/display.h"
#include "display/ei_layout.h"
#include "mla_optics/mla_model.h"
#include "mla_optics/stack_tracer.h"

namespace inim {

// The display's optical stack (today's MLA as one: stackFromMla) with its first air gap changed
// so that the panel lies `gapMm` below the display frame's z = 0 (the reconstruction gap's
// plane); InputError when there is no first air gap to change or it would vanish.
OpticalStack displayStackAtGap(const Display& display, double gapMm);

class StackMla final : public MlaModel {
 public:
  // `gapMm`: the panel's distance below the display frame's z = 0 (the display's reconstruction
  // gap, or another: the stack's first air gap grows or shrinks by the difference; InputError
  // when there is no first air gap to change or it would vanish).
  StackMla(const Display& display, const EiLayout& layout, double gapMm, FresnelMode fresnel = FresnelMode::Stochastic);

  using MlaModel::traceToPanel;
  bool traceToPanel(const Ray& ray, float lambdaNm, FresnelMode mode, Rng* rng, PanelArrival& out) const override;
  FresnelMode fresnelMode() const override { return fresnel_; }
  bool isDispersive() const override { return dispersive_; }
  float frontZ() const override { return frontZ_; }

 private:
  void lensletAt(double x, double y, int& k, int& l) const;

  std::unique_ptr<StackTracer> tracer_;
  CurvedFrame panelFrame_;
  FresnelMode fresnel_;
  double gapMm_ = 0.0;
  float frontZ_ = 0.0f;
  bool dispersive_ = false;
  const EiLayout* layout_ = nullptr;
  double pitchMm_ = 1.0;
};

// The ideal display of a curved stack (the error budget's ideal rung): each lenslet an ideal
// thin lens of the stack's focal length f at its principal point on the shell of the display
// frame's z = 0 (the reconstruction gap), across its own axis, as IdealLensletMla is across z:
// a ray from the viewer meets the shell in lenslet (k, l)'s cell, its slopes in the lenslet's
// axes turn by its offset from the axis over f, and it goes on straight to the panel as built
// (flat, or curved). No refraction, dispersion, crosstalk or Fresnel.
class CurvedIdealMla final : public MlaModel {
 public:
  CurvedIdealMla(const Display& display, const EiLayout& layout, double focalLengthMm, double gapMm);
  using MlaModel::traceToPanel;
  bool traceToPanel(const Ray& ray, float lambdaNm, FresnelMode mode, Rng* rng, PanelArrival& out) const override;
  bool isDispersive() const override { return false; }
  float frontZ() const override { return frontZ_; }

 private:
  CurvedFrame array_, panel_;
  const EiLayout* layout_ = nullptr;
  double f_ = 0.0, gapMm_ = 0.0;
  float frontZ_ = 0.0f;
};

// Where a ray leaving a stack back through its panel lands, in the panel's coordinates (a curved
// panel's arc coordinates and its own axes), the panel at the display frame's z = -gap.
void panelArrivalAt(const CurvedFrame& panel, const Point3d& p, const Vec3d& d, double gapMm, PanelArrival& out);

}  // namespace inim
