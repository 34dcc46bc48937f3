#pragma once
// The binary model file of a VoxelGrid (little-endian):
//   char[8]  magic "INIMRFG\0"
//   uint32   format version (kVoxelGridVersion)
//   uint32   header bytes that follow (so later versions can append fields)
//   header:  float lo[3], hi[3]; int32 res[3]; int32 shDegree; uint32 activation;
//            float background[3]; float densityScale; uint64 payload checksum (FNV-1a);
//            uint32 metadata bytes, then the metadata (UTF-8 JSON: what the model was trained on)
//   payload: float density[vertices]; float color[vertices * 3 * shCount(shDegree)]
// A foreign, corrupt, truncated or newer file is an InputError naming the path.
#include <string>

#include "radiance/voxel_grid.h"

namespace inim {

constexpr uint32_t kVoxelGridVersion = 1;

// Writes to a temporary beside `path` and renames it into place.
void saveVoxelGrid(const VoxelGrid& grid, const std::string& path);
VoxelGrid loadVoxelGrid(const std::string& path);

}  // namespace inim
