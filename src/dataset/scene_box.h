#pragma once
// A scene box and near/far planes for object-centric captures, from the camera poses alone.
//
// Heuristic (cameras circle an object and look at it):
// - centre: the least-squares point closest to every camera's optical axis;
// - half-size: mean camera distance to that centre x tan(half field of view), i.e. what a
//   camera at that distance sees around the centre, the same in all three axes;
// - near/far: min/max camera distance to the centre -/+ the box's half-diagonal (the
//   bounding sphere of the box), near kept >= 1% of the mean distance.
// When the axes are (near) parallel — a forward-facing capture — the centre is undefined;
// it falls back to the mean camera position moved along the mean view direction by the
// spread of the positions, and the estimate is only a rough guess there.
#include <vector>

#include "dataset/dataset.h"

namespace inim {

struct SceneBoxEstimate {
  Box3d box;
  double nearPlane = 0, farPlane = 0;
  bool axesConverge = true;  // false: the forward-facing fallback was used
};

SceneBoxEstimate estimateSceneBox(const std::vector<DatasetFrame>& frames);

// The least-squares point closest to the lines (origin[i], unit dir[i]). False if the lines
// are (near) parallel, when `point` is left unchanged.
bool closestPointToLines(const std::vector<glm::dvec3>& origins, const std::vector<glm::dvec3>& dirs,
                         glm::dvec3& point);

}  // namespace inim
