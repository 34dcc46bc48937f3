// RadianceField: the Field adapter over VolumeRenderer.
#include "radiance/radiance_field.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <stdexcept>

#include "radiance/grid_io.h"
#include "spectral/color.h"

namespace inim {

RadianceField::RadianceField(VoxelGrid grid, const MarchSettings& settings)
    : grid_(std::move(grid)), renderer_(grid_, settings), previewRenderer_(grid_, previewMarch(settings)) {}

MarchSettings RadianceField::previewMarch(const MarchSettings& full) {
  MarchSettings m;
  m.stepVoxels = 1.0f;
  m.minTransmittance = 1e-2f;
  m.completeEnded = true;
  // A cell is empty when its opacity over one step is under the threshold; over a step k times
  // longer that opacity is 1 - (1 - a)^k. The preview then sees the haze the full query sees,
  // no more (a lower threshold made it both slower and further from the full query).
  m.occupancyAlpha = float(1.0 - std::pow(1.0 - double(full.occupancyAlpha), double(m.stepVoxels / full.stepVoxels)));
  m.colourMinWeight = 0.005f;
  m.colourSkipBudget = 0.1f;
  return m;
}

std::unique_ptr<RadianceField> RadianceField::load(const std::string& path) {
  return std::make_unique<RadianceField>(loadVoxelGrid(path));
}

void RadianceField::query(std::span<const FieldRay> rays, std::span<const SampledWavelengths>,
                          std::span<FieldSample> out, uint64_t) const {
  queryWith(renderer_, rays, out);
}

void RadianceField::queryPreview(std::span<const FieldRay> rays, std::span<const SampledWavelengths>,
                                 std::span<FieldSample> out, uint64_t) const {
  queryWith(previewRenderer_, rays, out);
}

void RadianceField::queryWith(const VolumeRenderer& renderer, std::span<const FieldRay> rays,
                              std::span<FieldSample> out) const {
  if (out.size() < rays.size()) throw std::invalid_argument("RadianceField: output too small");
  tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), 256),
                    [&](const tbb::blocked_range<size_t>& r) {
                      for (size_t i = r.begin(); i < r.end(); ++i) {
                        const FieldRay& fr = rays[i];
                        float tNear = fr.tNear, tFar = fr.tFar;
                        RadianceSample res;
                        if (!(tNear <= tFar)) {
                          res = backgroundResult(grid_);
                        } else {
                          res = renderer.render(RenderRay{fr.o, fr.d, tNear, tFar});
                        }
                        FieldSample& s = out[i];
                        s.rgb = Vec3(srgbDecode(res.rgb.x), srgbDecode(res.rgb.y),
                                     srgbDecode(res.rgb.z));
                        s.depth = res.depth;
                        s.opacity = res.opacity;
                      }
                    });
}

void RadianceField::bounds(Point3& lo, Point3& hi) const {
  lo = grid_.lo;
  hi = grid_.hi;
}

}  // namespace inim
