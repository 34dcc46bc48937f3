#pragma once
// The camera's response to the panel's three primaries, shared by the panel estimators: how a
// ray's emission per channel at a wavelength becomes linear, white-balanced camera RGB, and
// which wavelength each ray of a dispersive sample carries (docs/view-estimators.md).
//
//   Nothing dispersive: one ray per sample carries every wavelength; the channel it reads
//     contributes that primary's exact spectral integral (Primaries) or the visible packet's
//     estimate of it (Visible).
//   Something dispersive: one ray per slot (per primary, or per wavelength of the visible
//     packet), each at its own wavelength, weighted by spectrum / pdf.
#include <array>
#include <vector>

#include "camera/sensor.h"
#include "core/geometry.h"
#include "display/panel.h"
#include "spectral/sampled.h"
#include "display_view/panel_emitter.h"
#include "display_view/view_settings.h"

namespace inim {

// Importance sampling of one primary's spectrum: a piecewise-constant pdf on 1 nm bins over
// 360-830 nm (bin mass = Simpson estimate of the spectrum over the bin, plus a floor of 1e-6
// of the largest, so the pdf is positive wherever the spectrum can be).
class ChannelSampler {
 public:
  template <class F>
  explicit ChannelSampler(F spectrum);
  // The wavelength at cumulative mass u.
  float quantile(double u) const;
  float sample(float u, float& pdf) const;

 private:
  void build(const std::vector<double>& binMass);
  std::vector<float> cdf_, pdf_;
};

class ChannelResponse {
 public:
  // `dispersive`: something on the ray's path depends on the wavelength (or one ray per
  // wavelength is asked for), so each slot gets its own ray.
  ChannelResponse(const CameraSensor& sensor, const PanelEmitter& panel, bool dispersive, SpectralSampling sampling);

  bool dispersive() const { return dispersive_; }
  bool primaries() const { return primaries_; }
  int raysPerSample() const { return raysPerSample_; }
  // Channel c's full-drive spectrum integrated against the camera's response (camera RGB).
  const Vec3d& channelRgb(int c) const { return channelRgb_[size_t(c)]; }
  const ChannelSampler& sampler(int c) const { return samplers_[size_t(c)]; }
  const CameraSensor& sensor() const { return sensor_; }
  const PanelEmitter& panel() const { return panel_; }

  // The wavelength of slot `slot` of a dispersive sample and its pdf: primary `slot`'s
  // importance sample at `uLambda`, or the packet's slot-th wavelength; false when it cannot
  // carry light.
  bool slotWavelength(int slot, float uLambda, const SampledWavelengths& packet, float& lambda, float& pdf) const;
  // Adds a ray's emission (per channel, times `weight` = camera weight x throughput) at
  // `lambda` (pdf) of slot `slot` to `rgb`: the one place emission becomes camera RGB.
  void add(const std::array<float, kNumPrimaries>& emission, double weight, float lambda, float pdf, int slot,
           float uLambda, Vec3d& rgb) const;

 private:
  const CameraSensor& sensor_;
  const PanelEmitter& panel_;
  bool dispersive_, primaries_;
  int raysPerSample_;
  std::array<Vec3d, kNumPrimaries> channelRgb_;
  std::vector<ChannelSampler> samplers_;
};

template <class F>
ChannelSampler::ChannelSampler(F spectrum) {
  const int n = int(kLambdaMax - kLambdaMin);
  std::vector<double> mass(size_t(n), 0.0);
  for (int b = 0; b < n; ++b) {
    const double a = kLambdaMin + b;
    mass[size_t(b)] = std::max(0.0, (double(spectrum(float(a))) + 4.0 * spectrum(float(a + 0.5)) +
                                     double(spectrum(float(a + 1.0)))) / 6.0);
  }
  build(mass);
}

}  // namespace inim
