#include "dataset/transforms_json.h"

#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/json_config.h"

namespace inim {

namespace {

// Global or per-frame camera keys: the frame's value wins.
struct CameraKeys {
  const JsonObject& global;
  const JsonObject& frame;
  bool has(const std::string& k) const { return frame.has(k) || global.has(k); }
  const JsonObject& owner(const std::string& k) const { return frame.has(k) ? frame : global; }
  double number(const std::string& k, double fallback) const {
    return has(k) ? owner(k).number(k) : fallback;
  }
  double positive(const std::string& k) const { return owner(k).positive(k); }
  // Image sizes: instant-ngp's colmap2nerf.py writes them as floats (1080.0), which are whole.
  int imageSize(const std::string& k) const { return owner(k).integer(k, 1, std::numeric_limits<int>::max()); }
};

// Camera keys, global or per frame, as instant-ngp (scripts/colmap2nerf.py) and Nerfstudio
// (process_data/colmap_utils.py) write them. camera_angle_y, fovx and fovy restate what the
// focal lengths or camera_angle_x already say and are not read.
const char* const kCameraKeys[] = {"camera_model", "fl_x", "fl_y", "cx", "cy", "w", "h",
                                   "k1", "k2", "k3", "k4", "p1", "p2", "is_fisheye",
                                   "camera_angle_x", "camera_angle_y", "fovx", "fovy"};
// Keys those tools write that do not bear on the poses and images read here: Nerfstudio's
// "applied_transform" (already applied to the poses) and "ply_file_path" (its sparse points);
// inim capture's "inim_capture" (read by the fitting stage).
const char* const kIgnoredTopKeys[] = {"applied_transform", "ply_file_path", "inim_capture"};
// Per frame: instant-ngp's "sharpness"; Nerfstudio's "colmap_im_id", "mask_path" and
// "depth_file_path" (masks and depths are not used); the Blender set's "rotation".
const char* const kIgnoredFrameKeys[] = {"sharpness", "colmap_im_id", "mask_path", "depth_file_path", "rotation"};

// Marks `keys` as known, so that rejectUnknown() refuses only what no tool writes (a
// misspelling such as fl_z).
template <size_t N>
void acceptKeys(const JsonObject& o, const char* const (&keys)[N]) {
  for (const char* k : keys) o.has(k);
}

glm::dmat4 readMatrix(const JsonObject& frame) {
  const std::string key = "transform_matrix";
  const Json& m = frame.raw(key);
  auto bad = [&](const std::string& what) { frame.fail(key, jsonValueText(m), what); };
  if (!m.is_array() || (m.size() != 4 && m.size() != 3)) bad("a 4x4 (or 3x4) array of rows");
  glm::dmat4 r(1.0);
  for (size_t row = 0; row < m.size(); ++row) {
    if (!m[row].is_array() || m[row].size() != 4) bad("a 4x4 (or 3x4) array of rows");
    for (size_t col = 0; col < 4; ++col) {
      const Json& v = m[row][col];
      if (!v.is_number()) bad("numbers");
      double x = v.get<double>();
      // JSON has no NaN or Infinity, and readJsonFile refuses literals beyond a double.
      if (!std::isfinite(x)) bad("finite numbers (non-finite pose)");
      r[int(col)][int(row)] = x;  // glm is column-major
    }
  }
  if (m.size() == 4 && (r[0][3] != 0.0 || r[1][3] != 0.0 || r[2][3] != 0.0 || r[3][3] != 1.0))
    bad("a rigid transform with last row 0 0 0 1");
  // The rotation part must be a rotation (up to a uniform scale some exporters leave in).
  glm::dmat3 R(r);
  double det = glm::determinant(R);
  if (!(det > 1e-12)) bad("a camera-to-world matrix with a proper (det > 0) rotation");
  return r;
}

void checkModel(const JsonObject& o) {
  std::string model = o.string("camera_model");
  if (model != "OPENCV" && model != "PINHOLE")
    o.fail("camera_model", model, "OPENCV or PINHOLE (fisheye and equirectangular models are not supported)");
}

}  // namespace

DatasetManifest readTransformsJson(const std::string& path) {
  const Json root = readJsonFile(path);
  if (!root.is_object()) throw InputError(path, "", jsonValueText(root), "a JSON object");
  JsonObject g(root, path, "");
  DatasetManifest man;
  man.file = path;

  bool ngp = g.has("aabb_scale") || g.has("scale") || g.has("offset");
  if (g.has("camera_model")) {
    man.format = "nerfstudio";
    checkModel(g);
  } else if (ngp) {
    man.format = "instant-ngp";
  } else if (g.has("camera_angle_x") && !g.has("fl_x")) {
    man.format = "blender";
  } else {
    man.format = "nerfstudio";
  }

  if (ngp) {
    double aabb = g.has("aabb_scale") ? g.positive("aabb_scale") : 1.0;
    double scale = g.has("scale") ? g.positive("scale") : 0.33;
    glm::dvec3 off = g.has("offset") ? g.vec3("offset") : glm::dvec3(0.5);
    // ngp = cycle(world * scale + offset), cycle(x,y,z) = (y,z,x) (instant-ngp's
    // nerf_matrix_to_ngp). The ngp box is a cube, the same on every axis, so the cycle drops out.
    Box3d b;
    b.lo = (glm::dvec3(0.5 - 0.5 * aabb) - off) / scale;
    b.hi = (glm::dvec3(0.5 + 0.5 * aabb) - off) / scale;
    man.ngpBox = b;
  }

  if (!g.has("frames")) g.fail("frames", "missing", "an array of frames");
  if (!g.raw("frames").is_array()) g.fail("frames", jsonValueText(g.raw("frames")), "an array of frames");
  std::vector<JsonObject> frames = g.objects("frames");
  for (size_t i = 0; i < frames.size(); ++i) {
    const JsonObject& f = frames[i];
    CameraKeys c{g, f};
    if (f.has("camera_model")) checkModel(f);
    if (c.has("is_fisheye") && c.owner("is_fisheye").boolean("is_fisheye", false))
      c.owner("is_fisheye").fail("is_fisheye", "true", "a pinhole camera (fisheye is not supported)");
    FrameSpec s;
    s.key = f.keyPath("file_path");
    if (!f.has("file_path")) f.fail("file_path", "missing", "the frame's image path");
    s.filePath = f.string("file_path");
    if (!f.has("transform_matrix")) f.fail("transform_matrix", "missing", "a 4x4 camera-to-world matrix");
    s.cameraToWorld = readMatrix(f);

    Intrinsics& k = s.intrinsics;
    if (c.has("w")) k.width = c.imageSize("w");
    if (c.has("h")) k.height = c.imageSize("h");
    if (c.has("fl_x")) {
      k.fx = c.positive("fl_x");
      k.fy = c.has("fl_y") ? c.positive("fl_y") : k.fx;
    } else if (c.has("camera_angle_x")) {
      s.angleX = c.positive("camera_angle_x");
      if (s.angleX >= M_PI) c.owner("camera_angle_x").fail("camera_angle_x", std::to_string(s.angleX),
                                                          "an angle in (0, pi) radians");
      if (c.has("camera_angle_y")) s.angleY = c.positive("camera_angle_y");
      if (s.angleY >= M_PI) c.owner("camera_angle_y").fail("camera_angle_y", std::to_string(s.angleY),
                                                          "an angle in (0, pi) radians");
    } else {
      throw InputError(path, f.keyPath("fl_x"), "missing",
                       "intrinsics: fl_x (and fl_y, cx, cy) or camera_angle_x, globally or per frame");
    }
    k.cx = c.has("cx") ? c.number("cx", 0) : std::numeric_limits<double>::quiet_NaN();
    k.cy = c.has("cy") ? c.number("cy", 0) : std::numeric_limits<double>::quiet_NaN();
    bool pinhole = c.has("camera_model") && c.owner("camera_model").string("camera_model") == "PINHOLE";
    if (!pinhole) {
      k.k1 = c.number("k1", 0);
      k.k2 = c.number("k2", 0);
      k.p1 = c.number("p1", 0);
      k.p2 = c.number("p2", 0);
      for (const char* extra : {"k3", "k4"})
        if (c.has(extra) && c.number(extra, 0) != 0.0)
          c.owner(extra).fail(extra, jsonValueText(c.owner(extra).raw(extra)),
                              "0: only the OPENCV model (k1 k2 p1 p2) is supported");
    }
    for (const char* key : {"cx", "cy", "k1", "k2", "p1", "p2"})
      if (c.has(key) && !std::isfinite(c.number(key, 0)))
        c.owner(key).fail(key, "non-finite", "a finite number");
    acceptKeys(f, kCameraKeys);
    acceptKeys(f, kIgnoredFrameKeys);
    f.rejectUnknown();
    man.frames.push_back(std::move(s));
  }
  acceptKeys(g, kCameraKeys);
  acceptKeys(g, kIgnoredTopKeys);
  g.rejectUnknown();
  return man;
}

}  // namespace inim
