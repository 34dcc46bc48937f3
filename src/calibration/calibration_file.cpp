#include "calibration/calibration_file.h"

#include <filesystem>
#include <fstream>

#include "core/error.h"
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
  const std::string ext = lowerExtension(path);
  const std::string quoted = "\"" + path + "\"";
  if (ext != ".cube" && ext != ".clf")
    throw InputError(path, key, quoted, "a 3D LUT calibration file (.cube or .clf)");
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec) || !std::ifstream(path, std::ios::binary))
    throw InputError(path, key, quoted, "a readable calibration file (.cube or .clf)");
  if (ext == ".cube") return std::make_shared<const Lut3d>(readCube(path));
  return std::make_shared<const ClfModel>(readClf(path));
}

std::string describeCalibration(const std::string& path, const ColourModel& model) {
  auto lutText = [](const Lut3d& lut) {
    return "3D LUT, " + std::to_string(lut.size()) + " nodes per axis, tetrahedral";
  };
  if (const auto* lut = dynamic_cast<const Lut3d*>(&model)) return path + " (" + lutText(*lut) + ")";
  if (const auto* clf = dynamic_cast<const ClfModel*>(&model))
    return path + " (CLF: " + (clf->process().matrix ? "3x3 matrix, then " : "") + lutText(clf->process().lut) + ")";
  return path + " (" + model.name() + ")";
}

}  // namespace inim
