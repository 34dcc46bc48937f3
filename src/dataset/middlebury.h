#pragma once
// Middlebury multi-view stereo camera files (Seitz et al. 2006), `*_par.txt`:
//   line 1: number of images
//   then per image: name k11 k12 k13 k21 k22 k23 k31 k32 k33 r11 .. r33 t1 t2 t3
// A world point X projects to pixels by K [R | t] X: world-to-camera in OpenCV axes (camera
// looks down +z, y down). We convert to camera-to-world in OpenGL axes:
//   C2W = [R^T | -R^T t] * diag(1, -1, -1, 1)
// and move the principal point by +0.5 px, because K uses OpenCV's integer pixel centres
// (pixel (0,0) is centred at (0,0)) and inim puts them at half-integers.
#include <string>

#include "dataset/manifest.h"

namespace inim {

DatasetManifest readMiddleburyPar(const std::string& path);

// The OpenCV world-to-camera (R, t) -> OpenGL camera-to-world conversion above.
glm::dmat4 openCvWorldToCameraToGl(const glm::dmat3& R, const glm::dvec3& t);

}  // namespace inim
