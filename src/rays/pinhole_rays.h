#pragma once
// Pinhole display rays: for every pixel of every EI, the chief ray from the pixel centre
// (z = -g) through its pinhole (lenslet centre, z = 0). The ray starts at the pinhole and
// points toward the viewer (+z). This is the paper's ray-generation model.
#include <optional>
#include <vector>

#include "core/geometry.h"
#include "core/image.h"
#include "rays/ray_set.h"

namespace inim {

class ProgressBar;

struct RayD {
  Point3d o;  // at the pinhole, z = 0
  Vec3d d;    // unit, d.z > 0
};

// One ray in double precision (what the text export writes).
RayD pinholeRay(const EiLayout& L, const RayAddress& a);
inline RayD pinholeRay(const EiLayout& L, int64_t index) { return pinholeRay(L, rayAddress(L, index)); }
// The centre of a ray's pixel on the panel plane, z = -g.
Point3d pixelCentre(const EiLayout& L, const RayAddress& a);

// All rays of the layout, in ray order, computed in parallel (TBB) in double and stored as
// float. Deterministic: independent of the thread count.
RaySet generatePinholeRays(const EiLayout& L, ProgressBar* progress = nullptr);

// The pixel of EI (k, l) whose pinhole chief ray passes through `point` (display frame, mm):
// the pixel that holds q = c - g (p - c) / p_z (c the pinhole, on z = 0). For p_z > 0 (a real
// point, in front of the MLA) the display ray itself passes through p; for p_z < 0 (virtual,
// behind the MLA) its backward extension does. nullopt when q falls outside the EI (the EI
// does not see the point) or p_z == 0.
std::optional<RayAddress> predictPixelForPoint(const EiLayout& L, int k, int l, const Point3d& point);

// Per-ray drive values (3 floats a ray: R, G, B, in ray order) from an EIA image with at least
// 3 channels (the first three are taken as R, G, B), and back. Pixels outside every EI are 0.
std::vector<float> driveFromEia(const EiLayout& L, const Image& eia);
Image eiaFromDrive(const EiLayout& L, const std::vector<float>& drive);

}  // namespace inim
