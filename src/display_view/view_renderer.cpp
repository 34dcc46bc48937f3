#include "display_view/view_renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>
#include <string>

#include "core/error.h"
#include "core/format.h"
#include "core/parallel.h"
#include "core/progress.h"

namespace inim {

namespace {

constexpr int kTileSize = 16;

// Where the pixel position's central ray (lens centre, 550 nm) meets the plane z = 0; false
// when it is blocked or does not head down.
bool centralRayOnDisplayPlane(const CameraModel& camera, Vec2 pixel, bool requireAbove, Point3& p) {
  Ray r;
  if (!(camera.generateRay(pixel, Vec2(0.5f), 550.0f, r) > 0.0f) || !(r.d.z < 0.0f)) return false;
  if (requireAbove && !(r.o.z > 0.0f)) return false;
  p = r.o + (-r.o.z / r.d.z) * r.d;
  return true;
}

// True when no ray of the tile can reach the active area (see ViewSettings::cullTiles).
bool tileMissesDisplay(const CameraModel& camera, const Tile& t, const AreaMm& area, float frontZ) {
  const float xs[5] = {float(t.x0), float(t.x1), float(t.x0), float(t.x1), 0.5f * float(t.x0 + t.x1)};
  const float ys[5] = {float(t.y0), float(t.y0), float(t.y1), float(t.y1), 0.5f * float(t.y0 + t.y1)};
  const float lensSamples[3] = {0.02f, 0.5f, 0.98f};
  const float lambdas[3] = {550.0f, 450.0f, 650.0f};
  const int wavelengths = camera.isDispersive() ? 3 : 1;
  double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
  int valid = 0;
  for (int i = 0; i < 5; ++i)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        for (int l = 0; l < wavelengths; ++l) {
          Ray r;
          if (!(camera.generateRay(Vec2(xs[i], ys[i]), Vec2(lensSamples[a], lensSamples[b]), lambdas[l], r) > 0.0f))
            continue;
          if (!(r.d.z < 0.0f) || !(r.o.z > frontZ)) return false;  // grazing or behind: do not guess
          const double t0 = (double(frontZ) - r.o.z) / r.d.z;
          const double px = r.o.x + t0 * r.d.x, py = r.o.y + t0 * r.d.y;
          if (!std::isfinite(px) || !std::isfinite(py)) return false;
          lo[0] = std::min(lo[0], px);
          hi[0] = std::max(hi[0], px);
          lo[1] = std::min(lo[1], py);
          hi[1] = std::max(hi[1], py);
          ++valid;
        }
  if (valid == 0) return false;
  // The box of a tile's whole ray bundle is the probes' box up to the lens's tiny
  // nonlinearity, so the margin makes the test exact in practice (tests compare with and without).
  const double mx = 0.5 * (hi[0] - lo[0]) + 1.0, my = 0.5 * (hi[1] - lo[1]) + 1.0;
  return lo[0] - mx > area.x1 || hi[0] + mx < area.x0 || lo[1] - my > area.y1 || hi[1] + my < area.y0;
}

void validate(const ViewSettings& s) {
  if (s.spp < 1) throw InputError("", "spp", std::to_string(s.spp), "a whole number >= 1");
  if (!(s.backgroundY >= 0.0) || !std::isfinite(s.backgroundY))
    throw InputError("", "background_y", formatNumber(s.backgroundY), "a luminance >= 0");
}

}  // namespace

double displayCoverage(const CameraModel& camera, const AreaMm& area, int grid) {
  grid = std::max(1, grid);
  int hits = 0;
  for (int j = 0; j < grid; ++j)
    for (int i = 0; i < grid; ++i) {
      const Vec2 pix(float((i + 0.5) / grid * camera.width()), float((j + 0.5) / grid * camera.height()));
      Point3 p;
      if (centralRayOnDisplayPlane(camera, pix, true, p) && area.contains(p.x, p.y)) ++hits;
    }
  return double(hits) / double(grid * grid);
}

PixelMask displayMask(const CameraModel& camera, const AreaMm& area) {
  PixelMask m;
  m.width = camera.width();
  m.height = camera.height();
  m.on.assign(size_t(m.width) * m.height, 0);
  m.source = "display area";
  parallelForRange(m.height, [&](int64_t y0, int64_t y1) {
    for (int y = int(y0); y < int(y1); ++y)
      for (int x = 0; x < m.width; ++x) {
        Point3 p;
        if (!centralRayOnDisplayPlane(camera, Vec2(x + 0.5f, y + 0.5f), false, p)) continue;
        m.on[size_t(y) * m.width + x] = area.contains(p.x, p.y) ? 1 : 0;
      }
  }, nullptr, 8);
  return m;
}

namespace {

// One pass of the tile loop: the estimator's context panel into results[0], its companions into
// the others. The settings are validated by the caller, before the contexts are made.
std::vector<ViewResult> renderPass(const CameraModel& camera, const EstimatorContext& context,
                                   const std::vector<const EstimatorContext*>& companions,
                                   const ViewSettings& settings) {
  const auto start = std::chrono::steady_clock::now();
  const std::unique_ptr<PixelEstimator> estimator =
      companions.empty() ? makePanelEstimator(settings.panelEstimator, context)
                         : std::make_unique<QuadratureEstimator>(context, companions);
  const int W = camera.width(), H = camera.height();
  std::vector<Image> images(companions.size() + 1, Image(W, H, {"R", "G", "B"}));
  ViewStats stats;
  std::mutex statsMutex;
  const bool cull = settings.cullTiles && settings.backgroundY == 0.0;
  ProgressBar bar("view", uint64_t(W) * H, settings.progress && ProgressBar::stderrIsTerminal());
  parallelForTiles(W, H, [&](const Tile& tile) {
    if (cull && tileMissesDisplay(camera, tile, context.area, context.frontZ)) {
      std::lock_guard<std::mutex> lock(statsMutex);
      stats.culledPixels += uint64_t(tile.x1 - tile.x0) * uint64_t(tile.y1 - tile.y0);
      return;  // the images are already 0 there
    }
    const std::unique_ptr<TileEstimator> tileEstimator = estimator->beginTile();
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x) {
        const Vec3d rgb = tileEstimator->pixel(x, y) / double(settings.spp);
        for (int c = 0; c < 3; ++c) images[0].at(x, y, c) = float(rgb[c]);
        for (size_t k = 0; k < companions.size(); ++k) {
          const Vec3d other = tileEstimator->companionPixel(int(k)) / double(settings.spp);
          for (int c = 0; c < 3; ++c) images[k + 1].at(x, y, c) = float(other[c]);
        }
      }
    std::lock_guard<std::mutex> lock(statsMutex);
    tileEstimator->addStats(stats);
  }, &bar, kTileSize);
  bar.finish();

  estimator->addStats(stats);
  stats.raysPerSample = context.channels.raysPerSample();
  stats.dispersive = context.channels.dispersive();
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::vector<ViewResult> results;
  for (Image& image : images) results.push_back({std::move(image), stats});
  return results;
}

}  // namespace

ViewResult renderView(const CameraModel& camera, const CameraSensor& sensor, const MlaModel& mla,
                      const PanelEmitter& panel, const AreaMm& area, const ViewSettings& settings) {
  validate(settings);
  const EstimatorContext context(camera, sensor, mla, panel, area, settings);
  return std::move(renderPass(camera, context, {}, settings).front());
}

std::vector<ViewResult> renderViews(const CameraModel& camera, const CameraSensor& sensor, const MlaModel& mla,
                                    const std::vector<const PanelEmitter*>& panels, const AreaMm& area,
                                    const ViewSettings& settings) {
  std::vector<ViewResult> results(panels.size());
  if (panels.empty()) return results;
  validate(settings);
  std::vector<std::unique_ptr<EstimatorContext>> contexts;
  for (const PanelEmitter* p : panels)
    contexts.push_back(std::make_unique<EstimatorContext>(camera, sensor, mla, *p, area, settings));
  std::vector<const EstimatorContext*> carried;
  std::vector<size_t> carriedIndex;
  for (size_t k = 1; k < panels.size(); ++k)
    if (settings.panelEstimator == PanelEstimator::Quadrature &&
        QuadratureEstimator::canCarry(*contexts[0], *contexts[k]))
      carried.push_back(contexts[k].get()), carriedIndex.push_back(k);
  std::vector<ViewResult> pass = renderPass(camera, *contexts[0], carried, settings);
  results[0] = std::move(pass[0]);
  for (size_t i = 0; i < carried.size(); ++i) {
    results[carriedIndex[i]] = std::move(pass[i + 1]);
    results[carriedIndex[i]].carried = true;
  }
  for (size_t k = 1; k < panels.size(); ++k)
    if (std::find(carriedIndex.begin(), carriedIndex.end(), k) == carriedIndex.end())
      results[k] = renderPass(camera, *contexts[k], {}, settings).front();
  return results;
}

}  // namespace inim
