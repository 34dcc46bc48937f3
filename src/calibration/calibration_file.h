#pragma once
// A calibration file as `inim eia --calibration` and `inim fig11 --calibration` apply it: a
// drive -> drive correction read from a 3D LUT file, chosen by the file's extension
// (case-insensitive):
//   .cube  Iridas/Resolve 3D LUT (readCube)                 -> Lut3d
//   .clf   Common LUT Format: optional Matrix, then LUT3D  -> ClfModel
// Both readers refuse what they do not write (lut_io.h): malformed lines or elements, a wrong
// number of entries, non-finite entries, a domain other than [0,1], fewer than 2 nodes per
// axis, CLF nodes other than Matrix and LUT3D (so no Range or IndexMap can remap the domain).
//
//   std::shared_ptr<const ColourModel> c = loadCalibration("panel.cube");
//   synthesis.correction = c;  // applied after the gamut mapping (synthesis/panel_color.h)
#include <memory>
#include <string>

#include "calibration/lut_io.h"

namespace inim {

// A CLF process list (matrix, then LUT) as a colour model.
class ClfModel : public ColourModel {
 public:
  explicit ClfModel(ClfProcess process) : process_(std::move(process)) {}
  Vec3d apply(const Vec3d& source) const override { return process_.apply(source); }
  std::string name() const override { return process_.matrix ? "clf_matrix_lut3d" : "clf_lut3d"; }
  std::string describe() const override {
    return std::string("CLF: ") + (process_.matrix ? "3x3 matrix, then " : "") + process_.lut.describe();
  }
  // The matrix (rows, when present) and the LUT's parameters.
  nlohmann::json parameters() const override;
  const ClfProcess& process() const { return process_; }

 private:
  ClfProcess process_;
};

// The correction in `path`. InputError naming the file, `key` and the path as the value for
// another extension or a file that cannot be read; the readers' InputErrors (naming the file
// and the line or element) for bad contents.
std::shared_ptr<const ColourModel> loadCalibration(const std::string& path, const std::string& key = "calibration");

// One line for reports: "<path> (3D LUT, 33 nodes per axis, tetrahedral)" and the like.
std::string describeCalibration(const std::string& path, const ColourModel& model);

}  // namespace inim
