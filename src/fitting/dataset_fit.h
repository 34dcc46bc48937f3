#pragma once
// Between datasets (src/dataset) and radiance fields (src/radiance): the training rays of a
// dataset's frames, and the model's metadata (what it was trained on, in which units), which
// decides its default placement in front of a display.
#include <optional>
#include <string>
#include <vector>

#include "dataset/dataset.h"
#include "radiance/trainer.h"
#include "radiance/volume_renderer.h"
#include "field/placement.h"

namespace inim {

// One ray per pixel centre of the given frames, with the frame's pixel values (sRGB-encoded)
// and the dataset's near/far.
TrainingRays datasetRays(const Dataset& data, const std::vector<int>& frames);

// The JSON stored in a model: {"dataset": ..., "format": ..., "units": "mm" | "dataset",
// "scene": ...}. An inim capture is in mm (placement scale 1); any other dataset is in its
// own units, placed at the paper's 0.0075 field units per mm unless the user says otherwise.
std::string modelMetadata(const Dataset& data);

// The model's render of one frame (sRGB-encoded as the photos, clamped to [0, 1]).
Image renderFrame(const VolumeRenderer& renderer, const Dataset& data, const DatasetFrame& f);

// A model's render of dataset frames, scored against the photos (sRGB values, peak 1).
struct ViewScore {
  int frame = 0;
  std::string image;
  double psnr = 0, ssim = 0;
};
std::vector<ViewScore> evaluate(const VoxelGrid& grid, const Dataset& data, const std::vector<int>& frames,
                                std::vector<Image>* renders);
Placement defaultPlacementFor(const std::string& metadata);

}  // namespace inim
