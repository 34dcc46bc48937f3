#pragma once
// Helpers the pipeline studies share (depth-sharpness, braiding, telecentric, nerf-pipeline): an
// EIA synthesised from an analytic scene placed at a depth (synthesis/), the scenes, a thin-lens
// viewing camera aimed along the display axis, and image measurements (luminance, where a
// camera pixel looks on a plane). Not part of the public interface.
#include <memory>

#include "camera/camera_model.h"
#include "core/image.h"
#include "core/json_config.h"
#include "display/display.h"
#include "display/ei_layout.h"

namespace inim::study_detail {

// The EIA (panel resolution, linear drive R, G, B) of the analytic scene `scene` (JSON, in mm)
// translated by (0, 0, zMm), exposure 1, no white balance, pinhole display rays of the layout.
Image synthesizeAt(const EiLayout& L, const Display& d, const Json& scene, double zMm, int spp);

// A scene with one diffuse rectangle w x h mm at the origin, its reflectance `reflectance`
// (a JSON spectrum or texture), lit by a distant point light on +z (radiance = reflectance).
Json litRectangleScene(double wMm, double hMm, const Json& reflectance, double rotateZDeg = 0.0);
// One emissive sphere (D65, luminance `scale`) of radius r at the origin.
Json emissiveSphereScene(double radiusMm, double scale);

// A thin-lens camera (focal length 12 mm, f/4: the 3 mm pupil of the paper's camera stand-in)
// with its entrance pupil at (0, 0, D), looking down -z, focused on the plane z = focusZ, with a
// W x H sensor whose pixels cover `sampleMm` on that plane. No natural vignetting.
std::unique_ptr<CameraModel> axialThinLens(double D, double focusZ, int W, int H, double sampleMm);
// Where the chief ray of pixel centre (x + 0.5, y + 0.5) meets the plane z = zMm.
glm::dvec2 pixelOnPlane(const CameraModel& cam, int x, int y, double zMm);

// Luminance-like weight of an RGB pixel (Rec.709 Y weights of the channels).
double lum(const Image& img, int x, int y);

}  // namespace inim::study_detail
