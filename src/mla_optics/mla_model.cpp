#include "mla_optics/mla_model.h"

namespace inim {

const char* fresnelModeName(FresnelMode m) {
  switch (m) {
    case FresnelMode::Stochastic: return "stochastic";
    case FresnelMode::Weighted: return "weighted";
    case FresnelMode::Off: return "off";
  }
  return "?";
}

}  // namespace inim
