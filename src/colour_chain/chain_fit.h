#pragma once
// Corrections fitted to the simulated chain (docs/colour-calibration.md).
//
// Panel side: a map from the drive `inim eia` would put on the panel (the nominal drive, after
// the gamut mapping) to the drive that makes the chain show that colour's target. At a pose
// the nominal drive of a measured XYZ is F(x) = gains * native(shown(x) / whiteY), so the
// correction is F's inverse:
//   matrix_3x3, root_polynomial_2  fitted by least squares to the drive grid's pairs
//                                  (F(x_i) -> x_i), pooled over the poses it is for;
//   lut3d                          F inverted node by node (invertToLut) on the continuous
//                                  chain (8-bit steps would make its Jacobian zero), with F the
//                                  mean over the poses.
// Camera side: camera RGB -> XYZ fitted to the grid's pairs (camera RGB, observer XYZ).
#include <memory>
#include <string>
#include <vector>

#include "calibration/colour_model.h"
#include "calibration/lut3d.h"
#include "colour_chain/colour_chain.h"

namespace inim {

enum class CorrectionKind { Matrix, RootPolynomial, Lut };
const char* correctionName(CorrectionKind k);  // "matrix_3x3", "root_polynomial_2", "lut3d"
std::vector<CorrectionKind> allCorrectionKinds();

// The nominal drive whose target is `xyz` at a pose (F above, without the chain).
Vec3d nominalDriveOf(const PoseChain& chain, const FieldToDrive& uncalibrated, const Vec3d& xyz);

// A panel-side correction for `poses` (one pose: a correction per angle; all: one for all).
std::shared_ptr<const ColourModel> fitPanelCorrection(CorrectionKind kind, const std::vector<const PoseChain*>& poses,
                                                      const FieldToDrive& uncalibrated, const PatchSet& grid,
                                                      int lutSize = Lut3d::kDefaultSize);

// A camera RGB -> XYZ correction (Matrix or RootPolynomial) from the grid shown at `poses`.
std::shared_ptr<const ColourModel> fitCameraCorrection(CorrectionKind kind, const std::vector<const PoseChain*>& poses,
                                                       const PatchSet& grid);

}  // namespace inim
