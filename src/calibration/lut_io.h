#pragma once
// 3D LUT exchange files: Iridas/Resolve .cube and the Academy/ASC Common LUT Format (CLF 3).
// Readers accept what the writers write and refuse anything else with an InputError naming the
// file, the line or element, and the value.
#include <optional>
#include <string>

#include "calibration/lut3d.h"

namespace inim {

// .cube: TITLE, LUT_3D_SIZE, DOMAIN_MIN 0 0 0, DOMAIN_MAX 1 1 1, then N^3 lines "r g b" with
// red changing fastest. Numbers are written in their shortest exact form (the file round-trips).
void writeCube(const std::string& path, const Lut3d& lut, const std::string& title);
// Refuses a 1D LUT, a missing or bad size, a domain other than [0,1], malformed or non-finite
// lines and a wrong number of lines.
Lut3d readCube(const std::string& path);

// A CLF process list as inim writes it: an optional 3x3 Matrix node, then one LUT3D node.
struct ClfProcess {
  std::optional<glm::dmat3> matrix;  // applied first: out = lut(matrix * in)
  Lut3d lut;
  Vec3d apply(const Vec3d& rgb) const { return lut.eval(matrix ? *matrix * rgb : rgb); }
};

// ProcessList with compCLFversion="3"; the LUT3D is tetrahedral, 32f in and out, its Array
// "N N N 3" with BLUE changing fastest (the CLF order, the reverse of .cube's).
void writeClf(const std::string& path, const ClfProcess& process, const std::string& name);
// Checks the root, version, bit depths, interpolation, Array dimensions, value counts and
// finiteness; refuses any node but Matrix and LUT3D (Range, LUT1D, ...) and any child of theirs
// but one Array (an IndexMap, which would remap the [0,1] domain, or a second Array).
ClfProcess readClf(const std::string& path);

}  // namespace inim
