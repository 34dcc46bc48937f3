#include "calibration/calibration_file.h"

#include <filesystem>
#include <fstream>

#include "core/input_file.h"
#include "core/error.h"
#include "core/file_kinds.h"
#include "core/format.h"

namespace inim {

nlohmann::json ClfModel::parameters() const {
  nlohmann::json p = {{"model", name()}, {"lut3d", process_.lut.parameters()}};
  if (process_.matrix) {
    const glm::dmat3& m = *process_.matrix;  // glm: column-major
    nlohmann::json rows = nlohmann::json::array();
    for (int row = 0; row < 3; ++row) rows.push_back({m[0][row], m[1][row], m[2][row]});
    p["matrix_rows"] = rows;
  }
  return p;
}

std::shared_ptr<const ColourModel> loadCalibration(const std::string& path, const std::string& key) {
  const std::string quoted = "\"" + path + "\"";
  const FileKind kind =
      requireFileKind(path, key, {FileKind::Cube, FileKind::Clf}, "a 3D LUT calibration file (.cube or .clf)", path);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec) || !std::ifstream(path, std::ios::binary))
    throw InputError(path, key, quoted, "a readable calibration file (.cube or .clf)");
  checkInputFile(path);
  if (kind == FileKind::Cube) return std::make_shared<const Lut3d>(readCube(path));
  return std::make_shared<const ClfModel>(readClf(path));
}

std::string describeCalibration(const std::string& path, const ColourModel& model) {
  return path + " (" + model.describe() + ")";
}

}  // namespace inim
