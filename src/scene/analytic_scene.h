#pragma once
// An analytic scene: a JSON scene file (scenes/README.md) ray traced with Embree. It is
// the exact ground truth among fields: spectral radiance at the sample's 4 wavelengths,
// exact depth to the first surface, opacity 1 on a hit (0 where only the environment is
// seen).
//
//   auto scene = AnalyticScene::load("scenes/paper-fig7.json");
//   scene->query(rays, lambdas, out, seed);          // Field interface, thread-safe
//   RTCScene s = scene->embreeScene();               // for bare rtcIntersect1 benchmarks
//   Hit h; bool hit = scene->intersect(ray, h);      // one plain closest-hit query
//
// Dispersion: when a sample refracts through a dispersive dielectric, only its hero
// wavelength (index 0) goes on. Because the caller's wavelengths are const, the returned L
// then carries 4x the hero radiance in L[0] and zeros in L[1..3], which is the pbrt-v4
// estimator (pdf[0]/4, pdf[1..3] = 0) expressed with the caller's unchanged pdfs.
#include <memory>
#include <optional>
#include <string>

#include "field/field.h"
#include "scene/integrator.h"
#include "scene/lights.h"
#include "scene/scene_geometry.h"
#include "scene/scene_loader.h"

namespace inim {

class AnalyticScene final : public Field {
 public:
  // Loads a scene file; `integrator`, when given, overrides the file's "integrator".
  static std::unique_ptr<AnalyticScene> load(
      const std::string& path, const std::optional<IntegratorSettings>& integrator = std::nullopt);
  // From parsed JSON; `file` names it in messages and anchors relative paths.
  static std::unique_ptr<AnalyticScene> fromJson(
      const Json& j, const std::string& file,
      const std::optional<IntegratorSettings>& integrator = std::nullopt);
  explicit AnalyticScene(SceneDescription description);
  // The integrator and lights refer to members: neither copyable nor movable.
  AnalyticScene(const AnalyticScene&) = delete;
  AnalyticScene& operator=(const AnalyticScene&) = delete;

  FieldEncoding encoding() const override { return FieldEncoding::Spectral; }
  void query(std::span<const FieldRay> rays, std::span<const SampledWavelengths> lambda,
             std::span<FieldSample> out, uint64_t seed) const override;
  // Bounds of the objects (not of rect lights); a zero box at the origin when there are none.
  void bounds(Point3& lo, Point3& hi) const override;

  // One ray, as query() computes it (L with the dispersion convention above).
  FieldSample queryOne(const FieldRay& ray, const SampledWavelengths& lambda, uint64_t seed) const;

  // Closest hit along ray in (tMin, tMax) with full surface data; false on a miss.
  bool intersect(const Ray& ray, Hit& hit) const { return geometry_->intersect(ray, &hit); }
  RTCScene embreeScene() const { return geometry_->embreeScene(); }
  const SceneGeometry& geometry() const { return *geometry_; }

  // Not thread-safe with concurrent queries: set before rendering.
  void setIntegratorSettings(const IntegratorSettings& s);
  const IntegratorSettings& integratorSettings() const { return integrator_->settings(); }

  const std::string& file() const { return file_; }
  const std::vector<SceneObject>& objects() const { return objects_; }
  const SceneObject* objectById(int id) const;
  const std::vector<Material>& materials() const { return materials_; }
  const LightSet& lights() const { return lights_; }
  size_t droppedTriangles() const { return dropped_; }

 private:
  std::string file_;
  std::unique_ptr<SceneGeometry> geometry_;
  std::vector<Material> materials_;
  std::vector<SceneObject> objects_;
  LightSet lights_;
  std::unique_ptr<Integrator> integrator_;
  size_t dropped_ = 0;
};

}  // namespace inim
