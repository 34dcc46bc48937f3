#pragma once
// A small Wavefront OBJ reader: v, vt, vn and f (polygons fan-triangulated; v, v/vt, v//vn,
// v/vt/vn; negative indices). Groups, smoothing groups, materials and lines are ignored.
#include <string>
#include <vector>

#include "core/geometry.h"

namespace inim {

struct ObjMesh {
  std::vector<Vec3> P, N;  // N empty unless every face corner has a normal
  std::vector<Vec2> UV;    // UV empty unless every face corner has a texture coordinate
  std::vector<uint32_t> indices;
};

// Throws InputError naming `path`, the line and the bad text.
ObjMesh loadObj(const std::string& path);
ObjMesh parseObj(const std::string& text, const std::string& nameForMessages);

}  // namespace inim
