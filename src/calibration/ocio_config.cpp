#include "calibration/ocio_config.h"

#include <OpenColorIO/OpenColorIO.h>

#include <filesystem>
#include <sstream>

#include "calibration/lut_io.h"
#include "calibration/lut_text.h"
#include "core/error.h"
#include "core/output_file.h"
#include "spectral/color.h"

namespace OCIO = OCIO_NAMESPACE;

namespace inim {
namespace {

OCIO::ConfigRcPtr editableBaseConfig(const std::string& path) {
  try {
    return OCIO::Config::CreateFromFile(path.c_str())->createEditableCopy();
  } catch (const OCIO::Exception& e) {
    throw InputError(path, "", e.what(), "a valid OpenColorIO config");
  }
}

// Reference -> (matrix to the panel's drive) -> LUT -> (clamp to [0, 1]).
OCIO::TransformRcPtr fromReferenceTransform(const OcioColourSpaceSettings& space, OCIO::FileTransformRcPtr file) {
  OCIO::GroupTransformRcPtr group = OCIO::GroupTransform::Create();
  if (space.referenceToLutInput) {
    const std::array<double, 9>& m = *space.referenceToLutInput;
    const double m44[16] = {m[0], m[1], m[2], 0, m[3], m[4], m[5], 0, m[6], m[7], m[8], 0, 0, 0, 0, 1};
    OCIO::MatrixTransformRcPtr matrix = OCIO::MatrixTransform::Create();
    matrix->setMatrix(m44);
    group->appendTransform(matrix);
  }
  group->appendTransform(file);
  if (space.clampOutput) {
    OCIO::RangeTransformRcPtr clamp = OCIO::RangeTransform::Create();
    clamp->setMinInValue(0.0), clamp->setMinOutValue(0.0);
    clamp->setMaxInValue(1.0), clamp->setMaxOutValue(1.0);
    group->appendTransform(clamp);
  }
  return group;
}

OCIO::ColorSpaceRcPtr lutColourSpace(const OcioColourSpaceSettings& space) {
  OCIO::FileTransformRcPtr file = OCIO::FileTransform::Create();
  file->setSrc(space.lutFile.c_str());
  file->setInterpolation(OCIO::INTERP_TETRAHEDRAL);
  OCIO::ColorSpaceRcPtr cs = OCIO::ColorSpace::Create();
  cs->setName(space.name.c_str());
  cs->setFamily("calibration");
  cs->setDescription(space.description.c_str());
  cs->setBitDepth(OCIO::BIT_DEPTH_F32);
  if (space.direction == LutDirection::FromReference)
    cs->setTransform(fromReferenceTransform(space, file), OCIO::COLORSPACE_DIR_FROM_REFERENCE);
  else
    cs->setTransform(file, OCIO::COLORSPACE_DIR_TO_REFERENCE);
  return cs;
}

}  // namespace

void writeOcioConfig(const std::string& configPath, const OcioColourSpaceSettings& space,
                     const std::string& baseConfigPath) {
  const std::string base = baseConfigPath.empty() ? ColorSystem::instance().configPath() : baseConfigPath;
  if (space.lutFile.empty() || std::filesystem::path(space.lutFile).has_parent_path())
    throw InputError(configPath, "lut_file", space.lutFile, "a file name beside the config");
  OCIO::ConfigRcPtr config = editableBaseConfig(base);
  if (config->getColorSpace(space.name.c_str()))
    throw InputError(base, "colour_space", space.name, "a name the base config does not already use");
  config->addColorSpace(lutColourSpace(space));
  config->setSearchPath(".");  // relative to the config's own folder
  config->setDescription((std::string(config->getDescription()) + "; with " + space.name).c_str());
  std::ostringstream text;
  try {
    config->validate();
    config->serialize(text);
  } catch (const OCIO::Exception& e) {
    throw InputError(configPath, space.name, e.what(), "a colour space OpenColorIO accepts");
  }
  writeTextFile(configPath, text.str());
}

CalibrationFiles exportCalibration(OutputSet& outputs, const std::string& folder, const std::string& stem,
                                   const Lut3d& lut, OcioColourSpaceSettings space, LutFormat configFormat,
                                   const std::string& baseConfigPath) {
  namespace fs = std::filesystem;
  CalibrationFiles files{(fs::path(folder) / (stem + ".cube")).string(), (fs::path(folder) / (stem + ".clf")).string(),
                         (fs::path(folder) / (stem + ".ocio")).string()};
  space.lutFile = fs::path(configFormat == LutFormat::Cube ? files.cube : files.clf).filename().string();
  writeCube(outputs.add(files.cube), lut, stem);
  writeClf(outputs.add(files.clf), ClfProcess{std::nullopt, lut}, stem);
  writeOcioConfig(outputs.add(files.config), space, baseConfigPath);
  return files;
}

CalibrationFiles exportCalibration(const std::string& folder, const std::string& stem, const Lut3d& lut,
                                   OcioColourSpaceSettings space, LutFormat configFormat,
                                   const std::string& baseConfigPath) {
  OutputSet outputs;
  CalibrationFiles files = exportCalibration(outputs, folder, stem, lut, std::move(space), configFormat, baseConfigPath);
  outputs.commit();
  return files;
}

}  // namespace inim
