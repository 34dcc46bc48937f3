#include "core/file_kinds.h"

#include "core/error.h"
#include "core/format.h"

namespace inim {

const std::vector<FileKindInfo>& fileKinds() {
  static const std::vector<FileKindInfo> kinds = {
      {FileKind::Json, "JSON", {".json"}, "scenes, displays, panels, MLAs, cameras, lenses, run files, reports"},
      {FileKind::Inimrf, "inim radiance field", {".inimrf"}, "a trained radiance-field model"},
      {FileKind::Ply, "PLY Gaussian splats", {".ply"}, "Gaussian splats: INRIA or compressed PLY"},
      {FileKind::Splat, "splat file", {".splat"}, "Gaussian splats, 32 bytes each"},
      {FileKind::Exr, "OpenEXR image", {".exr"}, "linear images: EIAs, views, references, ray tables"},
      {FileKind::Png, "PNG image", {".png"}, "encoded images: EIAs for the panel, previews, figures"},
      {FileKind::Hdr, "Radiance HDR image", {".hdr"}, "linear texture images"},
      {FileKind::Tiff, "TIFF image", {".tif", ".tiff"}, "linear texture images"},
      {FileKind::Pfm, "portable float map", {".pfm"}, "linear images to compare"},
      {FileKind::Npy, "NumPy array", {".npy"}, "ray tables and the colours an external field fills in"},
      {FileKind::Txt, "Zemax ray text", {".txt"}, "display rays as Zemax reads them"},
      {FileKind::Irays, "inim binary rays", {".irays"}, "display rays, compact"},
      {FileKind::Sdf, "Zemax source file", {".sdf"}, "RGB-wavelength triads as a spectral source"},
      {FileKind::Dat, "lens prescription or Zemax source file", {".dat"},
       "a pbrt-style lens prescription; written by inim triads, a Zemax source file"},
      {FileKind::Cube, "3D LUT (.cube)", {".cube"}, "colour corrections"},
      {FileKind::Clf, "Common LUT Format", {".clf"}, "colour corrections: matrix, then 3D LUT"},
      {FileKind::Zmx, "Zemax lens file", {".zmx"},
       "sequential lens prescriptions as lens vendors publish them; the NSC model inim eia writes"},
      {FileKind::Agf, "Zemax glass catalogue", {".agf"}, "glass makers' dispersion data (spectra/glass/)"},
  };
  return kinds;
}

const FileKindInfo& fileKindInfo(FileKind k) { return fileKinds()[size_t(k)]; }

std::optional<FileKind> fileKindOf(const std::string& path) {
  const std::string ext = lowerExtension(path);
  for (const FileKindInfo& info : fileKinds())
    for (const char* e : info.extensions)
      if (ext == e) return info.kind;
  return std::nullopt;
}

FileKind requireFileKind(const std::string& path, const std::string& key, std::initializer_list<FileKind> kinds,
                         const std::string& expected, const std::string& file) {
  const std::optional<FileKind> k = fileKindOf(path);
  for (FileKind want : kinds)
    if (k == want) return want;
  throw InputError(file, key, "\"" + path + "\"", expected);
}

}  // namespace inim
