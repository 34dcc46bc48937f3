#include "field_render/renderer.h"

#include <algorithm>
#include <cmath>

#include "field_render/field_renderer.h"
#include "spectral/cie.h"
#include "spectral/color.h"

namespace inim {

namespace {

// R, G, B (linear Rec.709 for spectral fields, the field's colour space for RGB ones), A, Z.
class Rec709Film final : public Film {
 public:
  std::vector<std::string> channels() const override { return {"R", "G", "B", "A", "Z"}; }

  void resolvePixel(const PixelRays& p, float* pixel) const override {
    Vec3 acc(0.0f);
    float alpha = 0.0f, depthSum = 0.0f;
    int depthCount = 0;
    for (size_t i = 0; i < p.answers.size(); ++i) {
      const FieldSample& fs = p.answers[i];
      const float w = p.weights[i];
      const Vec3 c = p.spectral ? toRec709_ * xyz(fs, p.wavelengths[i], p.heroOnly) : fs.rgb;
      if (isFinite(c)) acc += w * c;
      alpha += w * fs.opacity;
      if (std::isfinite(fs.depth)) {
        depthSum += fs.depth;
        ++depthCount;
      }
    }
    acc /= float(p.spp);
    pixel[0] = acc.x;
    pixel[1] = acc.y;
    pixel[2] = acc.z;
    pixel[3] = alpha / float(p.spp);
    pixel[4] = depthCount ? depthSum / float(depthCount) : 0.0f;
  }

 private:
  // XYZ of one answer; a hero-only ray estimates from its hero wavelength alone, i.e. as a
  // packet whose other wavelengths the field terminated (L[0] = 4x the hero).
  static Vec3 xyz(const FieldSample& fs, const SampledWavelengths& wl, bool heroOnly) {
    if (!heroOnly || fs.secondaryTerminated) return sampledToXYZ(fs.L, wl);
    SampledSpectrum hero(0.0f);
    hero[0] = fs.L[0] * float(kNumWavelengths);
    return sampledToXYZ(hero, wl);
  }

  const Mat3 toRec709_ = ColorSystem::xyzToRec709();
};

}  // namespace

RenderResult renderField(const Field& field, const CameraModel& camera, const RenderSettings& s) {
  FieldRenderSettings fs;
  fs.spp = std::max(1, s.spp);
  fs.seed = s.seed;
  fs.raysPerBatch = s.raysPerBatch;
  fs.progress = s.progress;
  fs.progressLabel = "render";
  FieldRender r = renderThroughCamera(field, camera, IndependentPixelSampler(s.seed), Rec709Film(), fs);
  if (field.encoding() != FieldEncoding::Spectral && field.colorSpace() != "lin_rec709")
    ColorSystem::instance().convertImage(r.image, field.colorSpace(), "lin_rec709");
  RenderResult res;
  res.image = std::move(r.image);
  res.seconds = r.stats.seconds;
  res.raysTraced = r.stats.cameraRays;
  return res;
}

Image encodeSRGB(const Image& lin) {
  Image rgb(lin.width, lin.height, {"R", "G", "B"});
  for (int y = 0; y < lin.height; ++y)
    for (int x = 0; x < lin.width; ++x)
      for (int c = 0; c < 3; ++c) rgb.at(x, y, c) = std::max(0.0f, lin.at(x, y, c));
  ColorSystem::instance().convertImage(rgb, "lin_rec709", "srgb");
  return rgb;
}

}  // namespace inim
