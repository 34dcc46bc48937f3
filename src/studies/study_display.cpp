#include "studies/study_display.h"

#include <algorithm>

#include "core/error.h"

namespace inim::study_detail {

StudyDisplay loadStudyDisplay(const StudyOptions& o) {
  StudyDisplay loaded;
  loaded.path = displayPathOrDefault(o.displayPath);
  loaded.display = loadDisplay(loaded.path);
  if (loaded.display.mla.lattice != Mla::Lattice::Square)
    throw InputError(loaded.path, "mla.lattice", "\"hex\"", "a square-lattice display (the studies sample square cells)");
  return loaded;
}

Display centralCrop(Display d, int cols, int rows) {
  if (cols > 0) d.eiCols = std::min(cols, d.eiCols);
  if (rows > 0) d.eiRows = std::min(rows, d.eiRows);
  return d;
}

Display pipelineDisplay(const Display& d, int cols, int rows, double gapMm, EiLayoutKind layout,
                        double viewingDistanceMm) {
  Display c = centralCrop(d, cols, rows);
  c.generationGapMm = gapMm;
  c.reconstructionGapMm = gapMm;
  c.layout = layout;
  c.viewingDistanceMm = viewingDistanceMm;
  return c;
}

}  // namespace inim::study_detail
