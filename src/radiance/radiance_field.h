#pragma once
// A trained VoxelGrid as a Field. The model predicts sRGB-encoded colour (the NeRF
// convention: it was trained on encoded pixel values), so answers are linearised with the
// sRGB EOTF and declared as lin_rec709. Rays are in the field's own frame (the caller
// applies the placement transform); depth is the expected depth along d.
#include <memory>
#include <string>

#include "field/field.h"
#include "radiance/volume_renderer.h"
#include "radiance/voxel_grid.h"

namespace inim {

class RadianceField : public Field {
 public:
  explicit RadianceField(VoxelGrid grid, const MarchSettings& settings = {});
  RadianceField(const RadianceField&) = delete;  // the renderer refers to grid_
  RadianceField& operator=(const RadianceField&) = delete;
  static std::unique_ptr<RadianceField> load(const std::string& path);

  FieldEncoding encoding() const override { return FieldEncoding::RGB; }
  std::string colorSpace() const override { return "lin_rec709"; }
  // Deterministic (no randomness): `seed` and `lambda` are unused.
  void query(std::span<const FieldRay> rays, std::span<const SampledWavelengths> lambda,
             std::span<FieldSample> out, uint64_t seed) const override;
  void bounds(Point3& lo, Point3& hi) const override;

  const VoxelGrid& grid() const { return grid_; }

 private:
  VoxelGrid grid_;
  VolumeRenderer renderer_;  // refers to grid_: declared after it
};

}  // namespace inim
