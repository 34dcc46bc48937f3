#pragma once
// inim's compact binary ray file (.irays), for fast exact round trips. Little-endian:
//   char[8]  magic "INIMRAYS"
//   uint32   version (1)
//   uint32   header size in bytes (48)
//   uint64   ray count N
//   int32 x4 EI columns, EI rows, EI width px, EI height px (0 = not from a layout)
//   float32  gap in mm (0 = unknown)
//   uint32   reserved (0)
// then six float32 arrays of N values each: ox, oy, oz, dx, dy, dz (file size 48 + 24 N).
#include <cstdint>
#include <string>

#include "rays/ray_set.h"

namespace inim {

constexpr uint32_t kRayBinaryVersion = 1;
constexpr uint32_t kRayBinaryHeaderSize = 48;

struct RayBinaryInfo {
  int32_t eiCols = 0, eiRows = 0, eiW = 0, eiH = 0;
  float gapMm = 0.0f;
  static RayBinaryInfo fromLayout(const EiLayout& L) {
    return {L.eiCols, L.eiRows, L.eiW, L.eiH, float(L.gapMm)};
  }
};

// Throws InputError naming the path when it cannot be written.
void writeRayBinary(const std::string& path, const RaySet& rays, const RayBinaryInfo& info = {});
// Validates magic, version, header size and file size; InputError naming the file otherwise.
RaySet readRayBinary(const std::string& path, RayBinaryInfo* info = nullptr);

}  // namespace inim
