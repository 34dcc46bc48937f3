#pragma once
// `inim view` and `inim reference` as a library. A camera at a pose in front of the display
// sees the display showing an EIA (runView) or the field itself at the EIA's placement
// (runReference); each writes linear camera RGB x exposure as an EXR and an sRGB PNG beside
// it, both or neither. Errors name settings (spp, width, distance_mm, gap_mm, ...) before any
// work.
//
//   ViewRunSettings s;
//   s.eiaPath = "eia.exr";  s.camera.out = "view.exr";  s.camera.width = 648;
//   ViewRunResult r = runView(s);
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "camera/camera_config.h"
#include "camera/camera_model.h"
#include "field/placement.h"
#include "display/layout_override.h"
#include "display_view/display_model.h"
#include "display_view/display_pose.h"
#include "display_view/reference_renderer.h"
#include "display_view/view_image.h"
#include "display_view/view_renderer.h"

namespace inim {

// The camera, its pose and the output files: what both runs share.
struct CameraRunSettings {
  std::string camera;                    // a name in optics/cameras or a file; "": the default camera
  std::optional<CameraModelKind> model;  // default: the description's
  std::optional<double> distanceMm;      // entrance pupil to display centre; default: the description's
  double rotHDeg = 0.0, rotVDeg = 0.0;   // the display's turn (display_view/display_pose.h)
  double focusMm = 0.0;                  // 0: the camera distance (the MLA plane)
  int width = 0, height = 0;             // 0: the sensor's (display_view/view_camera.h)
  std::string exposure = "auto";         // a factor, or auto (99th percentile -> 0.9)
  std::string out, png;                  // the EXR; the PNG ("": beside it)
};

// The camera as loaded and placed.
struct CameraSetup {
  CameraDescription desc;
  DisplayPose pose;
  std::unique_ptr<CameraModel> camera;
  Exposure exposure;
  std::string png;
};

// The view settings `inim view` renders with when told nothing: ViewSettings' defaults under
// the auto estimator policy (applyEstimatorPolicy below).
ViewSettings autoViewSettings();

struct ViewRunSettings {
  CameraRunSettings camera;
  std::string displayPath;        // "": the paper's prototype
  LayoutOverride layout;          // the layout the EIA was made for
  std::optional<double> gapMm;    // panel to MLA; default: the display's reconstruction gap
  std::string eiaPath;            // linear drive values (EXR), or an encoded PNG
  MlaKind mla = MlaKind::Real;
  EmitterSettings emitter;        // `encoded` follows the EIA's extension
  ViewSettings view = autoViewSettings();
};

struct ViewRunResult {
  CameraSetup camera;
  Display display;
  double gapMm = 0.0;
  bool coverGlass = false;
  int eiaWidth = 0, eiaHeight = 0;
  EiLayout layout;                    // the layout the EIA was made for
  std::shared_ptr<const Image> eia;   // its drive values as read
  double loadSeconds = 0.0;
  ViewResult render;
  std::vector<Image> carriedViews;  // of the panels CarriedPanels gave, rendered in the view's pass
  // The aperture tables the render made (ViewSettings::tableCache; the given cache, else one of
  // its own): later renders through the same camera reuse them.
  std::shared_ptr<QuadratureTableCache> tables;
  double exposureFactor = 1.0;
};

// Panels to see in the view's pass (renderViews: each another subpixel layout or drive of the
// view's panel), made from the loaded run and its display model; they must outlive the render.
using CarriedPanels = std::function<std::vector<const PanelEmitter*>(const ViewRunResult&, const DisplayModel&)>;

// `inim view`'s estimator policy on `view`: "auto" picks quadrature when the primaries are
// sampled (it integrates their spectra) and footprint otherwise; any other name is parsed
// (point, footprint, quadrature). Quadrature has no noise, so without an explicit spp it uses
// one stratum per pixel (RMSE ~1.3% of the mean against 16 at the sensor's resolution; inim
// bench).
void applyEstimatorPolicy(ViewSettings& view, const std::string& estimator, bool sppGiven);

// InputError (key eia) unless `path` names an existing EXR or PNG.
void checkEiaPath(const std::string& path);

// `loaded` (optional) is called when everything is loaded, before the render. The EIA path is
// checked (extension, existence) before any other work.
ViewRunResult runView(const ViewRunSettings& s, const std::function<void(const ViewRunResult&)>& loaded = {});
// The same without writing anything (exposureFactor stays 1): for runs that expose and write the
// view with other outputs (runs/view_reference.h).
// `carried` (optional): panels rendered with the view (their views in carriedViews).
ViewRunResult renderViewRun(const ViewRunSettings& s, const std::function<void(const ViewRunResult&)>& loaded = {},
                            const CarriedPanels& carried = {});
// The loaded display, EIA and camera as `inim view` prints them.
std::string loadedText(const ViewRunSettings& s, const ViewRunResult& r);
// The render's lines as `inim view` prints them: samples and time, rays, the estimator's counts.
std::string summaryText(const ViewRunResult& r, const ViewSettings& view, double totalSeconds);
// The warnings `inim view` gives, each a line, or "" when there is none: the display out of the
// camera's view; drive values outside [0, 1], which the panel shows clamped (EIAs filtered or
// resampled elsewhere overshoot a little, and clamping is what the panel does).
std::string outOfViewWarning(const ViewRunResult& r);
std::string driveClampedWarning(const ViewRunResult& r, const std::string& eiaPath);

struct ReferenceRunSettings {
  CameraRunSettings camera;
  std::string fieldPath;                // "": scenes/paper-fig7.json
  std::optional<Placement> placement;   // a run file's; absent: the field's own
  PlacementOverride placementOverride;  // given one by one, over that
  std::string displayPath;              // the display whose area should be in view; "": the prototype
  ReferenceSettings reference;
};

struct ReferenceRunResult {
  CameraSetup camera;
  std::string fieldPath;
  Placement placement;
  ViewResult render;
  double exposureFactor = 1.0;
  bool displayInView = true;
};

ReferenceRunResult runReference(const ReferenceRunSettings& s,
                                const std::function<void(const ReferenceRunResult&)>& loaded = {});

// The render's line as `inim reference` prints it: samples, times and rays.
std::string summaryText(const ReferenceRunResult& r, const ReferenceSettings& reference, double totalSeconds);

// The camera's two lines (model; image size, pitch and pose) as both commands print them.
std::string cameraText(const CameraSetup& cs);
// The scene and placement, then the camera (once loaded).
std::string loadedText(const ReferenceRunResult& r);
// A warning when the display is out of the camera's view; else "".
std::string displayOutOfViewWarning(const ReferenceRunResult& r);
// The exposure and the files written, as both commands print them.
std::string writtenText(const ReferenceRunResult& r, const std::string& out);
std::string writtenText(const ViewRunResult& r, const std::string& out);

}  // namespace inim
