#pragma once
// Reads the JSON scene format (scenes/README.md documents every key): materials by name,
// objects (sphere, box, rectangle, disk, cylinder, OBJ mesh) with transforms, lights (rect
// area, point, spot, environment) and the integrator. Strict: unknown or misspelt keys,
// non-positive sizes, unknown material names and missing files are InputErrors naming the
// file, the key path, the bad value and what was expected.
#include <string>
#include <vector>

#include "core/json_config.h"
#include "scene/integrator.h"
#include "scene/lights.h"
#include "scene/materials.h"
#include "scene/shapes.h"

namespace inim {

// One entry of "objects" (a shape and its material), for tools and tests.
struct SceneObject {
  int id = -1;
  std::string name;
  std::string type;      // sphere, box, rectangle, disk, cylinder, mesh
  std::string material;  // material name
  uint32_t shape = 0;    // index into SceneDescription::shapes (== Embree geometry ID)
};

struct SceneDescription {
  std::string file;
  std::vector<Shape> shapes;        // finalized
  std::vector<Material> materials;
  std::vector<Light> lights;        // area lights refer to shapes by index
  std::vector<SceneObject> objects;
  IntegratorSettings integrator;
  size_t droppedTriangles = 0;      // degenerate triangles skipped in meshes
};

SceneDescription loadSceneDescription(const std::string& path);
// `file` names the scene in messages and anchors relative paths.
SceneDescription parseSceneDescription(const Json& j, const std::string& file);

// Parses a spectrum value (number, [r,g,b], illuminant name or {"type": ...} object) at
// obj[key]. `role` decides what RGB means: "reflectance" (bounded albedo), "emission"
// (illuminant), "transmittance" (bounded), "generic".
SpectrumPtr parseSpectrum(const JsonObject& obj, const std::string& key, const std::string& role);

}  // namespace inim
