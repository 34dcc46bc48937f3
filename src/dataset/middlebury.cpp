#include "dataset/middlebury.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/input_file.h"
#include "core/error.h"

namespace inim {

glm::dmat4 openCvWorldToCameraToGl(const glm::dmat3& R, const glm::dvec3& t) {
  glm::dmat3 Rt = glm::transpose(R);
  glm::dmat4 c2w(Rt);
  c2w[3] = glm::dvec4(-(Rt * t), 1.0);
  // Flip the camera's y and z axes: OpenCV (y down, looks +z) -> OpenGL (y up, looks -z).
  c2w[1] = -c2w[1];
  c2w[2] = -c2w[2];
  return c2w;
}

DatasetManifest readMiddleburyPar(const std::string& path) {
  checkInputFile(path);
  std::ifstream in(path);
  if (!in) throw InputError(path, "", "", "a readable Middlebury *_par.txt file");
  DatasetManifest man;
  man.file = path;
  man.format = "middlebury";
  std::string line;
  long count = -1;
  int lineNo = 0;
  while (std::getline(in, line)) {
    ++lineNo;
    std::istringstream ls(line);
    std::string first;
    if (!(ls >> first)) continue;  // blank line
    std::string where = "line " + std::to_string(lineNo);
    if (count < 0) {
      char* end = nullptr;
      count = std::strtol(first.c_str(), &end, 10);
      if (*end != 0 || count <= 0) throw InputError(path, where, first, "the number of images (> 0)");
      continue;
    }
    double v[21];
    for (int i = 0; i < 21; ++i) {
      std::string tok;
      if (!(ls >> tok)) throw InputError(path, where, line, "name k11..k33 r11..r33 t1 t2 t3 (22 fields)");
      char* end = nullptr;
      v[i] = std::strtod(tok.c_str(), &end);
      if (*end != 0) throw InputError(path, where + " field " + std::to_string(i + 2), tok, "a number");
      if (!std::isfinite(v[i]))
        throw InputError(path, where + " field " + std::to_string(i + 2), tok, "a finite number");
    }
    FrameSpec s;
    s.filePath = first;
    s.key = where;
    glm::dmat3 R;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) R[c][r] = v[9 + 3 * r + c];
    glm::dvec3 t(v[18], v[19], v[20]);
    double det = glm::determinant(R);
    if (std::abs(det - 1.0) > 1e-3)
      throw InputError(path, where + " R", "det " + std::to_string(det), "a rotation matrix (det 1)");
    if (v[0] <= 0 || v[4] <= 0 || v[1] != 0 || v[3] != 0 || v[6] != 0 || v[7] != 0 || v[8] != 1)
      throw InputError(path, where + " K", line, "an upper-triangular K with positive fx, fy, zero skew and K33 = 1");
    s.intrinsics.fx = v[0];
    s.intrinsics.fy = v[4];
    s.intrinsics.cx = v[2] + 0.5;
    s.intrinsics.cy = v[5] + 0.5;
    s.cameraToWorld = openCvWorldToCameraToGl(R, t);
    man.frames.push_back(std::move(s));
  }
  if (count < 0) throw InputError(path, "line 1", "empty", "the number of images");
  if (long(man.frames.size()) != count)
    throw InputError(path, "line 1", std::to_string(count),
                     "the number of image lines that follow (" + std::to_string(man.frames.size()) + ")");
  return man;
}

}  // namespace inim
