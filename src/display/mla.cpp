#include "core/format.h"
#include "display/mla.h"

#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "display/panel.h"
#include "spectral/dispersion.h"

namespace inim {

const char* latticeName(Mla::Lattice l) { return l == Mla::Lattice::Square ? "square" : "hex"; }
const char* apertureName(Mla::Aperture a) {
  switch (a) {
    case Mla::Aperture::Square: return "square";
    case Mla::Aperture::Circle: return "circle";
    case Mla::Aperture::Hex: return "hex";
  }
  return "?";
}
const char* orientationName(Mla::Orientation o) {
  return o == Mla::Orientation::CurvedTowardViewer ? "curved-toward-viewer" : "curved-toward-panel";
}

LensletFocus lensletFocus(const Mla& m) {
  LensletFocus r;
  if (m.radiusMm) {
    IorPtr ior = MaterialCatalog::standard().dielectric(m.material);
    double n = ior->n(float(kLambdaDNm));
    r.indexD = n;
    if (!(n > 1.0))
      throw InputError(m.file, "material", "\"" + m.material + "\" (n_d = " + formatNumber(n) + ")",
                       "a lens material with n_d > 1");
    r.focalFromRadiusMm = *m.radiusMm / (n - 1.0);
  }
  if (m.focalLengthMm) {
    r.focalLengthMm = *m.focalLengthMm;
    r.source = "focal_length_mm";
    if (r.focalFromRadiusMm) {
      double rel = std::abs(*r.focalFromRadiusMm - *m.focalLengthMm) / *m.focalLengthMm;
      if (rel > 0.02)
        throw InputError(m.file, "focal_length_mm", formatNumber(*m.focalLengthMm),
                         "agreement within 2 % with radius_of_curvature_mm / (n_d - 1) = " +
                             formatNumber(*m.radiusMm) + " / (" + formatNumber(*r.indexD) + " - 1) = " +
                             formatNumber(*r.focalFromRadiusMm) + " mm (" + m.material + ")");
    }
  } else {
    r.focalLengthMm = *r.focalFromRadiusMm;
    r.source = "radius_of_curvature_mm / (n_d - 1)";
  }
  return r;
}

Mla parseMla(const JsonObject& o) {
  Mla m;
  m.file = o.file();
  m.name = o.string("name");
  m.lattice = o.choice("lattice", {"square", "hex"}, "square") == "square" ? Mla::Lattice::Square
                                                                          : Mla::Lattice::Hex;
  m.pitchMm = o.positive("pitch_mm");
  if (o.has("radius_of_curvature_mm")) m.radiusMm = o.positive("radius_of_curvature_mm");
  if (o.has("focal_length_mm")) m.focalLengthMm = o.positive("focal_length_mm");
  if (!m.radiusMm && !m.focalLengthMm)
    o.fail("focal_length_mm", "(missing)", "focal_length_mm, radius_of_curvature_mm, or both");
  m.conic = o.number("conic", 0.0);
  std::string ap = o.choice("aperture", {"square", "circle", "hex"},
                            m.lattice == Mla::Lattice::Square ? "square" : "hex");
  m.aperture = ap == "square" ? Mla::Aperture::Square
               : ap == "circle" ? Mla::Aperture::Circle
                                : Mla::Aperture::Hex;
  m.apertureMm = o.positive("aperture_mm", m.pitchMm);
  if (m.apertureMm > m.pitchMm * (1.0 + 1e-9))
    o.fail("aperture_mm", formatNumber(m.apertureMm), "an aperture <= pitch_mm (" + formatNumber(m.pitchMm) + ")");
  m.substrateThicknessMm = o.positive("substrate_thickness_mm");
  m.material = o.string("material");
  m.orientation = o.choice("orientation", {"curved-toward-viewer", "curved-toward-panel"},
                           "curved-toward-viewer") == "curved-toward-viewer"
                      ? Mla::Orientation::CurvedTowardViewer
                      : Mla::Orientation::CurvedTowardPanel;
  if (m.radiusMm) {
    // The cap must exist over the aperture: the half-diagonal (square) or radius must be < R.
    double half = m.aperture == Mla::Aperture::Square  ? m.apertureMm * std::sqrt(0.5)
                  : m.aperture == Mla::Aperture::Hex   ? m.apertureMm / std::sqrt(3.0)
                                                       : 0.5 * m.apertureMm;
    if ((1.0 + m.conic) * half * half >= *m.radiusMm * *m.radiusMm)
      o.fail("radius_of_curvature_mm", formatNumber(*m.radiusMm),
             "a radius whose cap covers the aperture (aperture half-diagonal " + formatNumber(half) + " mm)");
  }
  m.assumptions = readAssumptions(o);
  o.rejectUnknown();
  return m;
}

Mla loadMla(const std::string& path) {
  Json j = readJsonFile(path);
  return parseMla(JsonObject(j, path, ""));
}

}  // namespace inim
