#include "display/gap_range.h"

#include <cmath>

#include "core/error.h"
#include "core/format.h"

namespace inim {

double checkGapMm(double gapMm, const std::string& file, const std::string& key) {
  if (!(gapMm >= kMinGapMm && gapMm <= kMaxGapMm))
    throw InputError(file, key, formatNumber(gapMm),
                     "a panel-to-MLA gap from " + formatNumber(kMinGapMm) + " to " + formatNumber(kMaxGapMm) + " mm");
  return gapMm;
}

}  // namespace inim
