#pragma once
// A viewing camera described in optics/cameras/*.json (optics/cameras/README.md): sensor,
// lens, f-number, distance and focus, and which model to simulate it with.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "camera/camera_model.h"
#include "camera/lens_loader.h"
#include "camera/sensor.h"

namespace inim {

struct CameraDescription {
  std::string name, file;
  CameraSensor sensor;
  LensSystem lens;                // validated, with the design's stop
  std::string lensSource;         // the "lens" value: a name, a path or "(inline)"
  CameraModelKind model = CameraModelKind::RealLens;
  double fNumber = 0.0;           // 0: the design's stop
  double distanceMm = 350.0;      // entrance pupil to the display centre, default pose
  double focusDistanceMm = 0.0;   // 0: the distance of the pose (|lookAt - eye|)
  FocusMode focusMode = FocusMode::BestRms;
  bool fresnel = false;
  std::vector<std::string> assumptions;
};

// optics/cameras/alvium-1800-u-500c.json
std::string defaultCameraPath();
// A camera file by path, or by name under optics/cameras/.
CameraDescription loadCameraDescription(const std::string& pathOrName, const LensLoadOptions& lensOptions = {});
CameraDescription parseCameraDescription(const JsonObject& o, const LensLoadOptions& lensOptions = {});

// The default pose: the eye on the display normal at distanceMm, looking at the origin, y up.
ViewingPose defaultViewingPose(const CameraDescription& c);

// The real-lens settings a description gives (its f-number, focus mode, Fresnel), focused at
// `focusMm` from the entrance pupil.
RealLensSettings realLensSettings(const CameraDescription& c, double focusMm);

// Builds the camera model (the description's own, or `kind`). The pinhole and thin-lens
// stand-ins take the real lens's EFL and f-number and the same focus distance; the pinhole
// sits at the thin lens's image distance, so all three frame the scene alike.
std::unique_ptr<CameraModel> makeCameraModel(const CameraDescription& c, const ViewingPose& pose,
                                             std::optional<CameraModelKind> kind = std::nullopt);

}  // namespace inim
