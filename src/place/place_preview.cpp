#include "place/place_preview.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>

#include "core/parallel.h"
#include "core/rng.h"
#include "spectral/cie.h"
#include "spectral/color.h"
#include "synthesis/orthoscopic.h"

namespace inim {

namespace {

using Query = OrthoscopicQuery::Query;

// Every ray of a preview: pixel (i % W, i / W), one query per sample.
struct PreviewRays {
  int width = 0, height = 0, spp = 1;
  std::vector<Query> queries;  // [W * H * spp], pixel-major
  std::vector<SampledWavelengths> lambdas;  // spectral fields: the wavelengths of each query
};

// Spectral fields: the samples of one ray stratify the visible range.
void sampleWavelengths(PreviewRays& pr, uint64_t seed) {
  pr.lambdas.resize(pr.queries.size());
  for (size_t i = 0; i < pr.queries.size(); ++i) {
    const float u = (float(i % size_t(pr.spp)) + Rng::forSample(seed, pr.queries[i].ray.id, 0).uniform()) / float(pr.spp);
    pr.lambdas[i] = SampledWavelengths::sampleVisible(u);
  }
}

Vec3d centralDirection(const EiLayout& L, int k, int l) {
  const Vec3d d = Point3d(L.pinholeXAt(k, l), L.pinholeYAt(k, l), 0.0) -
                  Point3d(L.eiCentreXAt(k, l), L.eiCentreYAt(k, l), -L.gapMm);
  return d / std::sqrt(glm::dot(d, d));
}

// Levels 0 and 1: n x n queries per lenslet, parallel to its central ray, over its cell.
PreviewRays lensletRays(const EiLayout& L, const OrthoscopicQuery& oq, int n, int spp) {
  PreviewRays pr{L.eiCols * n, L.eiRows * n, spp, {}, {}};
  pr.queries.resize(size_t(pr.width) * pr.height * spp);
  const double px = L.lensPitchMm / n, py = L.lensRowPitchMm() / n;
  for (int l = 0; l < L.eiRows; ++l)
    for (int k = 0; k < L.eiCols; ++k) {
      const Vec3d d = centralDirection(L, k, l);
      for (int b = 0; b < n; ++b)
        for (int a = 0; a < n; ++a) {
          const int x = k * n + a, y = l * n + b;
          const Point3d o(L.pinholeXAt(k, l) + (a + 0.5 - 0.5 * n) * px,
                          L.pinholeYAt(k, l) - (b + 0.5 - 0.5 * n) * py, 0.0);
          const uint64_t id = uint64_t(y) * pr.width + x;
          for (int s = 0; s < spp; ++s) pr.queries[id * spp + s] = oq.make(o, d, id, uint32_t(s));
        }
    }
  return pr;
}

// Level 2: a pinhole camera at (0, 0, D) looking down -z, framing the display area with a margin.
struct CameraFrame {
  double D = 350.0, tanX = 0.1, tanY = 0.1;
  int width = 0, height = 0;
  // Pixel coordinates of the display-frame point p (on the image plane's projection).
  glm::dvec2 project(const Point3d& p) const {
    const double u = p.x / (D - p.z), v = p.y / (D - p.z);
    return {(u / tanX + 1.0) * 0.5 * width, (1.0 - v / tanY) * 0.5 * height};
  }
};

CameraFrame cameraFrame(const EiLayout& L, const PreviewRequest& r) {
  const AreaMm a = L.activeArea();
  CameraFrame c;
  c.D = r.viewingDistanceMm;
  const double halfW = 0.5 * (a.x1 - a.x0) * 1.15, halfH = 0.5 * (a.y1 - a.y0) * 1.15;
  c.width = std::clamp(r.cameraWidth, 16, 4096);
  c.height = std::clamp(int(std::lround(c.width * halfH / halfW)), 8, 4096);
  c.tanX = halfW / c.D;
  c.tanY = halfH / c.D;
  return c;
}

PreviewRays cameraRays(const CameraFrame& c, const Transform& toField, int spp, uint64_t seed) {
  PreviewRays pr{c.width, c.height, spp, {}, {}};
  pr.queries.resize(size_t(c.width) * c.height * spp);
  const Point3d eye(0.0, 0.0, c.D);
  for (int y = 0; y < c.height; ++y)
    for (int x = 0; x < c.width; ++x) {
      const uint64_t id = uint64_t(y) * c.width + x;
      for (int s = 0; s < spp; ++s) {
        Rng rng = Rng::forSample(seed ^ 0x9e3779b97f4a7c15ull, id, uint64_t(s));
        const double u = ((x + rng.uniform()) / c.width * 2.0 - 1.0) * c.tanX;
        const double v = (1.0 - (y + rng.uniform()) / c.height * 2.0) * c.tanY;
        Vec3d d(u, v, -1.0);
        d /= std::sqrt(glm::dot(d, d));
        Query q;
        Vec3d df = toField.vector(d);
        const double len = std::sqrt(glm::dot(df, df));
        q.ray.o = Point3(toField.point(eye));
        q.ray.d = Vec3(df / len);
        q.ray.id = id;
        q.ray.sample = uint32_t(s);
        q.displayPerField = 1.0 / len;
        q.vcpPoint = eye;
        q.displayDir = d;
        pr.queries[id * spp + s] = q;
      }
    }
  return pr;
}

// The field's answers to every query, in chunks; a cancelled render stops at its next chunk.
std::vector<FieldSample> queryField(const Field& field, const PreviewRays& pr, uint64_t seed, bool preview,
                                    const std::function<bool()>& cancelled) {
  const size_t n = pr.queries.size();
  const bool spectral = field.encoding() == FieldEncoding::Spectral;
  std::vector<FieldRay> rays(n);
  for (size_t i = 0; i < n; ++i) rays[i] = pr.queries[i].ray;
  std::vector<FieldSample> out(n);
  std::atomic<bool> stop{false};
  parallelForRange(int64_t(n), [&](int64_t a, int64_t b) {
    if (stop.load(std::memory_order_relaxed) || (cancelled && cancelled())) {
      stop = true;
      return;
    }
    const size_t m = size_t(b - a);
    const auto r = std::span<const FieldRay>(rays).subspan(size_t(a), m);
    const auto l = spectral ? std::span<const SampledWavelengths>(pr.lambdas).subspan(size_t(a), m)
                            : std::span<const SampledWavelengths>();
    const auto o = std::span(out).subspan(size_t(a), m);
    preview ? field.queryPreview(r, l, o, seed) : field.query(r, l, o, seed);
  }, nullptr, 512);
  if (stop || (cancelled && cancelled())) throw PreviewCancelled{};
  return out;
}

// Linear Rec.709 of the field's answers (spectral through the CIE observer, RGB through its
// colour space), and each pixel's first-hit display z (NaN: no hit).
struct PixelAnswers {
  std::vector<Vec3> rgb;
  std::vector<double> hitZ;
};

Mat3 rgbToRec709(const Field& field) {
  if (field.encoding() == FieldEncoding::Spectral || field.colorSpace() == "lin_rec709") return Mat3(1.0f);
  const ColorSystem& cs = ColorSystem::instance();
  Mat3 m;
  for (int c = 0; c < 3; ++c) {
    Vec3 e(0.0f);
    e[c] = 1.0f;
    m[c] = cs.convert(e, field.colorSpace(), "lin_rec709");
  }
  return m;
}

PixelAnswers resolvePixels(const Field& field, const PreviewRays& pr, const std::vector<FieldSample>& out) {
  const bool spectral = field.encoding() == FieldEncoding::Spectral;
  const Mat3 toRec709 = spectral ? ColorSystem::xyzToRec709() : rgbToRec709(field);
  const size_t pixels = size_t(pr.width) * pr.height;
  PixelAnswers pa{std::vector<Vec3>(pixels, Vec3(0.0f)), std::vector<double>(pixels, std::nan(""))};
  for (size_t p = 0; p < pixels; ++p) {
    double zSum = 0.0;
    int hits = 0;
    for (int s = 0; s < pr.spp; ++s) {
      const size_t i = p * pr.spp + s;
      const FieldSample& fs = out[i];
      Vec3 c = fs.rgb;
      if (spectral) c = sampledToXYZ(fs.L, pr.lambdas[i]);
      c = toRec709 * c;
      if (std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z)) pa.rgb[p] += c / float(pr.spp);
      if (fs.opacity >= 0.5f && std::isfinite(fs.depth) && pr.queries[i].ray.tFar >= 0.0f) {
        zSum += OrthoscopicQuery::hitZ(pr.queries[i], fs.depth);
        ++hits;
      }
    }
    if (2 * hits >= pr.spp && hits > 0) pa.hitZ[p] = zSum / hits;
  }
  return pa;
}

// Auto exposure: the 99th percentile of the brightest channel over the hits -> 0.9.
double autoExposure(const PixelAnswers& pa) {
  std::vector<float> v;
  for (size_t p = 0; p < pa.rgb.size(); ++p)
    if (std::isfinite(pa.hitZ[p])) v.push_back(std::max({pa.rgb[p].x, pa.rgb[p].y, pa.rgb[p].z}));
  if (v.empty()) return 1.0;
  const size_t k = std::min(v.size() - 1, size_t(0.99 * double(v.size())));
  std::nth_element(v.begin(), v.begin() + long(k), v.end());
  return v[k] > 0.0f ? 0.9 / v[k] : 1.0;
}

constexpr Vec3 kMissGrey{0.16f, 0.16f, 0.16f};

// Display-encoded colour of one pixel; only on-plane hits are the exact red (1, 0, 0).
Vec3 paint(const Vec3& linear, double z, double exposure, double tol, bool tintVirtual, PreviewCounts& n) {
  if (!std::isfinite(z)) {
    ++n.missed;
    return kMissGrey;
  }
  if (std::abs(z) <= tol) {
    ++n.onPlane;
    return Vec3(1.0f, 0.0f, 0.0f);
  }
  Vec3 c;
  for (int i = 0; i < 3; ++i) c[i] = srgbEncode(std::clamp(float(linear[i] * exposure), 0.0f, 1.0f));
  if (z > 0.0) {
    ++n.real;
  } else {
    ++n.virtualHits;
    if (tintVirtual) c = 0.55f * c + Vec3(0.02f, 0.07f, 0.22f);  // cooler and darker
  }
  if (c.x * 255.0f >= 254.5f && c.y * 255.0f < 0.5f && c.z * 255.0f < 0.5f) c.y = 1.0f / 255.0f;
  return c;
}

// The display's active area outlined in the camera view (level 2).
void outlineDisplay(Image& img, const CameraFrame& c, const EiLayout& L) {
  const AreaMm a = L.activeArea();
  const glm::dvec2 p0 = c.project(Point3d(a.x0, a.y1, 0.0)), p1 = c.project(Point3d(a.x1, a.y0, 0.0));
  const int x0 = int(std::floor(p0.x)), x1 = int(std::floor(p1.x)), y0 = int(std::floor(p0.y)),
            y1 = int(std::floor(p1.y));
  auto set = [&](int x, int y) {
    if (x < 0 || y < 0 || x >= img.width || y >= img.height) return;
    img.at(x, y, 0) = 1.0f, img.at(x, y, 1) = 0.85f, img.at(x, y, 2) = 0.1f;
  };
  for (int x = x0; x <= x1; ++x) set(x, y0), set(x, y1);
  for (int y = y0; y <= y1; ++y) set(x0, y), set(x1, y);
}

}  // namespace

PreviewFrame renderPlacePreview(const EiLayout& L, const Field& field, const Transform& fieldToDisplay,
                                double vcpMm, const PreviewRequest& r, const std::function<bool()>& cancelled) {
  const bool spectral = field.encoding() == FieldEncoding::Spectral;
  PreviewRays pr;
  CameraFrame cam;
  if (r.level == 2) {
    cam = cameraFrame(L, r);
    pr = cameraRays(cam, fieldToDisplay.inverse(), std::max(1, r.cameraSpp), r.seed);
  } else {
    const OrthoscopicQuery oq(fieldToDisplay, vcpMm);
    pr = lensletRays(L, oq, r.level == 0 ? 1 : std::clamp(r.raysPerSide, 1, 16),
                     spectral && r.level != 0 ? std::max(1, r.wavelengthSamples) : 1);
  }
  if (spectral) sampleWavelengths(pr, r.seed);
  // Level 0 must keep up with a drag: the field's cheaper answers (levels 1 and 2 refine).
  const std::vector<FieldSample> out = queryField(field, pr, r.seed, r.level == 0, cancelled);
  const PixelAnswers pa = resolvePixels(field, pr, out);
  PreviewFrame f;
  if (r.level == 0) {
    f.lensletHits.resize(size_t(pr.width) * pr.height);
    for (size_t p = 0; p < f.lensletHits.size(); ++p) {
      const FieldSample& s = out[p * size_t(pr.spp)];
      f.lensletHits[p] = {s.depth, s.opacity};
    }
  }
  f.exposure = r.exposure ? *r.exposure : autoExposure(pa);
  f.image = Image(pr.width, pr.height, {"R", "G", "B"});
  for (int y = 0; y < pr.height; ++y)
    for (int x = 0; x < pr.width; ++x) {
      const size_t p = size_t(y) * pr.width + x;
      const Vec3 c = paint(pa.rgb[p], pa.hitZ[p], f.exposure, r.onPlaneToleranceMm, r.level != 2, f.counts);
      for (int i = 0; i < 3; ++i) f.image.at(x, y, i) = c[i];
    }
  if (r.level == 2) outlineDisplay(f.image, cam, L);
  return f;
}

std::string encodePng(const Image& rgb) {
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput proxy(bytes);
  auto out = OIIO::ImageOutput::create("png", &proxy);
  if (!out) throw std::runtime_error("PNG encoder unavailable");
  OIIO::ImageSpec spec(rgb.width, rgb.height, 3, OIIO::TypeDesc::UINT8);
  std::vector<unsigned char> px(size_t(rgb.width) * rgb.height * 3);
  for (size_t i = 0; i < px.size(); ++i)
    px[i] = (unsigned char)std::lround(std::clamp(rgb.data[i / 3 * size_t(rgb.numChannels()) + i % 3], 0.0f, 1.0f) * 255.0f);
  if (!out->open("preview.png", spec) || !out->write_image(OIIO::TypeDesc::UINT8, px.data()) || !out->close())
    throw std::runtime_error("PNG encoding failed: " + out->geterror());
  return std::string(bytes.begin(), bytes.end());
}

}  // namespace inim
