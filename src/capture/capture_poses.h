#pragma once
// Camera placement for a synthetic capture: a golden-spiral (Fibonacci) cap of directions
// around the display's +z axis, and the camera-to-world pose of a camera looking at a point.
//
// Frame: the scene's own (= the display frame for analytic scenes): x right, y up, z toward
// the viewer, mm. The cap's pole is +z: the cameras stand where the display's viewers stand.
#include <vector>

#include <glm/glm.hpp>

namespace inim {

// n unit directions spread evenly (equal area, golden-angle azimuths) over the cap of
// elevations [minElevationDeg, maxElevationDeg] above the xy plane, toward +z (elevation 90 is
// the +z axis). Direction i has cos(polar) stratified at (i + 0.5)/n, so the set is
// deterministic and the same n always gives the same views.
std::vector<glm::dvec3> capDirections(int n, double minElevationDeg, double maxElevationDeg);

// Camera-to-world (OpenGL axes: looks down -z, +y up) of a camera at `eye` looking at
// `target` with `up` (replaced by -z of the world when nearly parallel to the view, which
// only happens for elevations near 0 at azimuth 90 degrees). The same axes as FovCameraModel
// (camera/fov_camera.h).
glm::dmat4 lookAtCameraToWorld(const glm::dvec3& eye, const glm::dvec3& target,
                               glm::dvec3 up = {0.0, 1.0, 0.0});

}  // namespace inim
