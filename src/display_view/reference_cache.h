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
// $XDG_CACHE_HOME/inim, else ~/.cache/inim), or the folder a run names (ReferenceSettings::cacheDir,
// a sweep's); INIM_REFERENCE_CACHE=0 turns the default one off. Entries are written to temporaries
// tagged by host and process and renamed, so concurrent runs, on one machine or on the nodes of
// a cluster sharing a file system, never read half an entry. The image's SHA-256 is stored with it
// and checked on every read: a damaged or mismatched entry is rendered again.
#include <optional>
#include <string>
#include <utility>

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

// The right to render one entry, held by one run at a time (a KEY.lock file naming its host and
// process, removed when the claim ends), so that concurrent runs, a sweep's points or its array
// tasks on a shared file system, wait for an entry instead of rendering it too.
class ReferenceClaim {
 public:
  ReferenceClaim() = default;
  explicit ReferenceClaim(std::string lockPath) : lock_(std::move(lockPath)) {}
  ReferenceClaim(ReferenceClaim&& o) noexcept : lock_(std::exchange(o.lock_, {})) {}
  ReferenceClaim& operator=(ReferenceClaim&& o) noexcept;
  ~ReferenceClaim();
  bool held() const { return !lock_.empty(); }

 private:
  std::string lock_;
};
// The entry when it is cached, waiting while another live run holds its claim; else none, with
// the claim taken (`claim`). A claim of a process gone (on this host), or older than
// `staleSeconds`, is taken over. Throws Interrupted (core/interrupt.h) while it waits.
std::optional<ViewResult> loadOrClaimReference(const std::string& dir, const std::string& key, ReferenceClaim& claim,
                                               double staleSeconds = 3600.0);
// Failures to write are not errors: the run goes on without the entry.
void storeCachedReference(const std::string& dir, const std::string& key, const ViewResult& r);

}  // namespace inim
