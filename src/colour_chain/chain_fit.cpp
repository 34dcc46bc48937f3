#include "colour_chain/chain_fit.h"

#include "calibration/colour_models.h"
#include "core/error.h"

namespace inim {

const char* correctionName(CorrectionKind k) {
  switch (k) {
    case CorrectionKind::Matrix: return "matrix_3x3";
    case CorrectionKind::RootPolynomial: return "root_polynomial_2";
    case CorrectionKind::Lut: return "lut3d";
  }
  return "?";
}

std::vector<CorrectionKind> allCorrectionKinds() {
  return {CorrectionKind::Matrix, CorrectionKind::RootPolynomial, CorrectionKind::Lut};
}

Vec3d nominalDriveOf(const PoseChain& chain, const FieldToDrive& uncalibrated, const Vec3d& xyz) {
  return Vec3d(uncalibrated.native(Vec3(xyz / chain.whiteY())) * uncalibrated.gains());
}

namespace {

template <class Model>
std::shared_ptr<const ColourModel> fitPairs(const ColourPairs& pairs) {
  return std::make_shared<Model>(Model::fit(pairs));
}

std::shared_ptr<const ColourModel> fitByKind(CorrectionKind kind, const ColourPairs& pairs) {
  if (kind == CorrectionKind::Matrix) return fitPairs<MatrixModel>(pairs);
  if (kind == CorrectionKind::RootPolynomial) return fitPairs<RootPolynomialModel>(pairs);
  throw std::logic_error("fitByKind: a LUT is not fitted to pairs");
}

}  // namespace

std::shared_ptr<const ColourModel> fitPanelCorrection(CorrectionKind kind, const std::vector<const PoseChain*>& poses,
                                                      const FieldToDrive& uncal, const PatchSet& grid, int lutSize) {
  if (kind == CorrectionKind::Lut) {
    auto forward = [&](const Vec3d& x) {
      Vec3d sum(0.0);
      for (const PoseChain* p : poses) sum += nominalDriveOf(*p, uncal, p->linearXyz(x));
      return sum / double(poses.size());
    };
    InversionSettings is;
    is.size = lutSize;
    // The continuous chain is defined beyond full drive: let the table continue the inverse
    // there, so the cells at the gamut's boundary interpolate exactly (FieldToDrive clamps).
    is.lowerBound = -1.0, is.upperBound = 2.0;
    return std::make_shared<Lut3d>(invertToLut(forward, is).lut);
  }
  ColourPairs pairs;
  for (const PoseChain* p : poses)
    for (const Patch& patch : grid.patches) {
      pairs.sources.push_back(nominalDriveOf(*p, uncal, p->shownXyz(patch.drive)));
      pairs.targets.push_back(patch.drive);
    }
  return fitByKind(kind, pairs);
}

std::shared_ptr<const ColourModel> fitCameraCorrection(CorrectionKind kind, const std::vector<const PoseChain*>& poses,
                                                       const PatchSet& grid) {
  ColourPairs pairs;
  for (const PoseChain* p : poses)
    for (const Patch& patch : grid.patches) {
      pairs.sources.push_back(p->cameraRgb(patch.drive));
      pairs.targets.push_back(p->shownXyz(patch.drive));
    }
  return fitByKind(kind, pairs);
}

}  // namespace inim
