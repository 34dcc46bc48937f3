#include "spectral/cmf_table.h"

#include "spectral/cie.h"

namespace inim {

CmfTable::CmfTable() {
  const double norm = 1.0 / cie::yIntegral();
  for (int i = 0; i < kN; ++i) {
    float l = kLambdaMin + float(i);
    xyz_[size_t(i)] = Vec3(float(cie::X()(l) * norm), float(cie::Y()(l) * norm), float(cie::Z()(l) * norm));
  }
}

const CmfTable& cmfTable() {
  static const CmfTable t;
  return t;
}

}  // namespace inim
