#pragma once
// The panel-side colour correction of `inim calibrate` applied to an EIA already made: every EI
// pixel's drive values through the correction, clamped to [0, 1], exactly as `inim eia
// --calibration` applies it when it makes the EIA (synthesis/panel_color.h FieldToDrive: the
// correction is the last step on each EI pixel's drive), so correcting an uncalibrated EIA gives
// the calibrated one without synthesising it again. Pixels outside every EI are left as they are.
//
//   Image calibrated = correctedEia(layout, eia, *loadCalibration("panel.cube"));
#include "calibration/colour_model.h"
#include "core/image.h"
#include "display/ei_layout.h"

namespace inim {

// `eia`: panel-sized or EIA-sized (as the panel emitter takes it), drive values in R, G, B (by
// channel name, else the first three).
Image correctedEia(const EiLayout& L, const Image& eia, const ColourModel& correction);

}  // namespace inim
