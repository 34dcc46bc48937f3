#include "display_view/estimators/channel_response.h"

#include <algorithm>

namespace inim {

namespace {

// A Spectrum view of one channel's full-drive radiance (for the exact non-dispersive integral).
class ChannelSpectrum final : public Spectrum {
 public:
  ChannelSpectrum(const PanelEmitter& panel, int channel) : panel_(panel), channel_(channel) {}
  float operator()(float l) const override { return panel_.channelSpectrum(channel_, l); }
  float maxValue() const override { return 0.0f; }

 private:
  const PanelEmitter& panel_;
  int channel_;
};

}  // namespace

void ChannelSampler::build(const std::vector<double>& binMass) {
  std::vector<double> mass = binMass;
  const size_t n = mass.size();
  double maxMass = 0.0;
  for (double m : mass) maxMass = std::max(maxMass, m);
  double total = 0.0;
  for (auto& m : mass) total += (m = std::max(m, 1e-6 * maxMass));
  cdf_.assign(n + 1, 0.0f);
  pdf_.assign(n, 0.0f);
  double cumulative = 0.0;
  for (size_t b = 0; b < n; ++b) {
    pdf_[b] = float(mass[b] / total);
    cumulative += mass[b] / total;
    cdf_[b + 1] = float(cumulative);
  }
  cdf_.back() = 1.0f;
}

float ChannelSampler::quantile(double u) const {
  float pdf;
  return sample(float(std::clamp(u, 0.0, double(0x1.fffffep-1f))), pdf);
}

float ChannelSampler::sample(float u, float& pdf) const {
  const int n = int(pdf_.size());
  int b = int(std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin()) - 1;
  b = std::clamp(b, 0, n - 1);
  const float w = cdf_[size_t(b) + 1] - cdf_[size_t(b)];
  const float f = w > 0.0f ? std::clamp((u - cdf_[size_t(b)]) / w, 0.0f, 0x1.fffffep-1f) : 0.5f;
  pdf = pdf_[size_t(b)];
  return kLambdaMin + float(b) + f;
}

ChannelResponse::ChannelResponse(const CameraSensor& sensor, const PanelEmitter& panel, bool dispersive,
                                 SpectralSampling sampling)
    : sensor_(sensor),
      panel_(panel),
      dispersive_(dispersive),
      primaries_(sampling == SpectralSampling::Primaries),
      raysPerSample_(!dispersive ? 1 : primaries_ ? kNumPrimaries : kNumWavelengths) {
  for (int c = 0; c < kNumPrimaries; ++c) {
    channelRgb_[size_t(c)] = sensor.cameraRgb(ChannelSpectrum(panel, c));
    samplers_.emplace_back([&](float l) { return panel.channelSpectrum(c, l); });
  }
}

bool ChannelResponse::slotWavelength(int slot, float uLambda, const SampledWavelengths& packet, float& lambda,
                                     float& pdf) const {
  if (primaries_) {
    lambda = samplers_[size_t(slot)].sample(uLambda, pdf);
  } else {
    lambda = packet[slot];
    pdf = packet.pdf()[slot];
  }
  return pdf > 0.0f;
}

void ChannelResponse::add(const std::array<float, kNumPrimaries>& emission, double weight, float lambda, float pdf,
                          int slot, float uLambda, Vec3d& rgb) const {
  for (int c = 0; c < kNumPrimaries; ++c) {
    if (emission[size_t(c)] == 0.0f) continue;
    if (!dispersive_) {
      const double kc = weight * emission[size_t(c)];
      if (primaries_) {
        rgb += kc * channelRgb_[size_t(c)];
      } else {
        const SampledWavelengths wl = SampledWavelengths::sampleVisible(uLambda);
        Vec3d sum(0.0);
        for (int i = 0; i < kNumWavelengths; ++i)
          if (wl.pdf()[i] > 0.0f)
            sum += sensor_.response(wl[i]) * (double(panel_.channelSpectrum(c, wl[i])) / wl.pdf()[i]);
        rgb += kc * sum / double(kNumWavelengths);
      }
    } else {
      if (primaries_ && c != slot) continue;
      const double kc = weight * emission[size_t(c)] * panel_.channelSpectrum(c, lambda) / pdf;
      rgb += sensor_.response(lambda) * (primaries_ ? kc : kc / double(kNumWavelengths));
    }
  }
}

}  // namespace inim
