#pragma once
// The display a study runs on (not part of the public interface): StudyOptions::displayPath,
// or the paper's prototype when it is empty, and the crops the studies take of it.
#include <string>

#include "display/display.h"
#include "studies/studies.h"

namespace inim::study_detail {

struct StudyDisplay {
  std::string path;  // the description it was loaded from (named in the report)
  Display display;
};

// Loads the study's display. InputError when its MLA is not a square lattice: the studies
// sample lenslet cells and EIs as squares (the paper's MLA).
StudyDisplay loadStudyDisplay(const StudyOptions& o);

// The central cols x rows EIs of `d` (same panel, MLA, pixel and lens pitch); a count of 0, or
// one larger than the display's, keeps that dimension whole.
Display centralCrop(Display d, int cols, int rows);

// The display of a pipeline study (depth-sharpness, braiding, telecentric): the central
// cols x rows EIs, rays generated and viewed at the gap `gapMm`, EI layout `layout` (toed-in
// for a viewer at viewingDistanceMm).
Display pipelineDisplay(const Display& d, int cols, int rows, double gapMm, EiLayoutKind layout,
                        double viewingDistanceMm);

}  // namespace inim::study_detail
