#pragma once
// A test scene for the comparisons' references: a grey square at z = 5 mm (scene mm) lit
// head-on by a distant point light, and the default camera's sensor.
#include <memory>
#include <string>

#include "camera/camera_config.h"
#include "core/json_config.h"
#include "scene/analytic_scene.h"

namespace fixtures {

inline std::unique_ptr<inim::AnalyticScene> greyPlaneAt5mm(int sizeMm) {
  const std::string size = std::to_string(sizeMm);
  return inim::AnalyticScene::fromJson(inim::Json::parse(R"({
    "units": "mm",
    "integrator": {"type": "direct"},
    "materials": {"grey": {"type": "diffuse", "reflectance": 0.5}},
    "objects": [{"id": 1, "name": "plane z=5", "type": "rectangle", "size_mm": [)" + size + ", " + size + R"(],
                 "translate_mm": [0, 0, 5], "material": "grey"}],
    "lights": [{"name": "distant", "type": "point", "position_mm": [0, 0, 1000000], "spectrum": 1.0,
                "scale": 3.14159265358979e12}]
  })"), "plane-test-scene.json");
}

inline const inim::CameraSensor& defaultSensor() {
  static const inim::CameraDescription c = inim::loadCameraDescription("alvium-1800-u-500c");
  return c.sensor;
}

}  // namespace fixtures
