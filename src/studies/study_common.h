#pragma once
// Helpers shared by the studies (not part of the public interface).
#include <string>
#include <vector>

#include "studies/studies.h"

namespace inim::study_detail {

StudyValue compare(const std::string& name, double measured, double predicted, double tolerance);
// "inim study NAME --out DIR [--display FILE]" for the report.
std::string reproduceCommand(const std::string& study, const StudyOptions& o);
// Markdown table of the values, and a verdict line.
std::string valuesTable(const std::vector<StudyValue>& v, const std::string& unit);
std::string verdictLine(const std::vector<StudyValue>& v);
std::string fmt(double v, int decimals);
bool allPass(const std::vector<StudyValue>& v);

}  // namespace inim::study_detail
