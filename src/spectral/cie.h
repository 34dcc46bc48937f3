#pragma once
// CIE 1931 2-degree colour matching functions and standard illuminants, loaded from
// spectra/*.csv (CIE data), and spectrum -> XYZ.
#include "core/geometry.h"
#include "spectral/spectrum.h"

namespace inim {

namespace cie {
const PiecewiseLinearSpectrum& X();
const PiecewiseLinearSpectrum& Y();
const PiecewiseLinearSpectrum& Z();
const PiecewiseLinearSpectrum& D65();  // relative power, as tabulated (560 nm ~ 100)
const PiecewiseLinearSpectrum& A();
// Integral of y_bar over 360-830 nm (1 nm trapezoid); ~106.857.
double yIntegral();
}  // namespace cie

// XYZ of D65 scaled to Y = 1: the white of the field and of CIELAB in colour comparisons.
Vec3d d65WhiteXyz();

// XYZ of an emission spectrum, normalised so that Y = integral(s * y_bar) / yIntegral().
Vec3d spectrumToXYZ(const Spectrum& s);
// XYZ of a reflectance under an illuminant, normalised so that a perfect white has Y = 1.
Vec3d reflectanceToXYZ(const Spectrum& r, const Spectrum& illuminant);
// Monte Carlo estimate of XYZ from radiance sampled at `lambda` (divides by the pdfs).
Vec3 sampledToXYZ(const SampledSpectrum& L, const SampledWavelengths& lambda);

}  // namespace inim
