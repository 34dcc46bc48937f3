#pragma once
// The reference rendered once (docs/speed-and-error.md): a reference view carries no display, so the
// poses of fig11, the budget's noise floor, `inim view --reference`, `inim reference` and every
// design of a sweep that shares the scene, camera and pose share it. Content-addressed: the key
// is the SHA-256 of everything the image depends on,
//   the program itself (a rebuild changes every key),
//   the field's files (ReferenceSettings::fieldKey, fieldContentKey),
//   the placement, the camera's behaviour (its rays on a grid of pixels and lens samples, its
//   size, kind and dispersion) and the sensor's response on a 1 nm grid,
//   the render settings (spp, seed, camera dispersion, depth, the full-sample map),
// so a cached image is found only for the same inputs, and it is the same image, bit for bit
// (float EXR), with the same ray counts.
//
// Where: references/ in inim's cache folder (core/content_hash.h: $INIM_CACHE_DIR, else
// $XDG_CACHE_HOME/inim, else ~/.cache/inim); INIM_REFERENCE_CACHE=0 turns it off. Entries are written to a temporary and renamed, so
// concurrent runs never read half an entry; a damaged entry is rendered again.
#include <optional>
#include <string>

#include "camera/camera_model.h"
#include "camera/sensor.h"
#include "core/transform.h"
#include "display_view/reference_renderer.h"

namespace inim {

// The cache folder ("": caching is off).
std::string referenceCacheDir();

// The hash of a field file's bytes and, for a JSON file, of every file its string values name
// (relative to it or to the data folder: a scene's meshes, textures, spectra).
std::string fieldContentKey(const std::string& path);

std::string referenceCacheKey(const std::string& fieldKey, const Transform& fieldToDisplay, const CameraModel& camera,
                              const CameraSensor& sensor, const ReferenceSettings& s);

std::optional<ViewResult> loadCachedReference(const std::string& dir, const std::string& key);
// Failures to write are not errors: the run goes on without the entry.
void storeCachedReference(const std::string& dir, const std::string& key, const ViewResult& r);

}  // namespace inim
