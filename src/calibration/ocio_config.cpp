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

OCIO::ColorSpaceRcPtr lutColourSpace(const OcioColourSpaceSettings& space) {
  OCIO::FileTransformRcPtr file = OCIO::FileTransform::Create();
  file->setSrc(space.lutFile.c_str());
  file->setInterpolation(OCIO::INTERP_TETRAHEDRAL);
  OCIO::ColorSpaceRcPtr cs = OCIO::ColorSpace::Create();
  cs->setName(space.name.c_str());
  cs->setFamily("calibration");
  cs->setDescription(space.description.c_str());
  cs->setBitDepth(OCIO::BIT_DEPTH_F32);
  cs->setTransform(file, space.direction == LutDirection::FromReference ? OCIO::COLORSPACE_DIR_FROM_REFERENCE
                                                                        : OCIO::COLORSPACE_DIR_TO_REFERENCE);
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
