#include "studies/study_report.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <utility>

namespace inim::study_detail {

StudyValue compare(const std::string& name, double measured, double predicted, double tolerance) {
  StudyValue v{name, measured, predicted, tolerance, false, StudyValue::Check::Relative};
  v.pass = std::isfinite(measured) && std::abs(measured - predicted) <= tolerance * std::abs(predicted);
  return v;
}

StudyValue bound(const std::string& name, double measured, double boundValue, bool atLeast) {
  StudyValue v{name, measured, boundValue, 0.0, false,
               atLeast ? StudyValue::Check::AtLeast : StudyValue::Check::AtMost};
  v.pass = std::isfinite(measured) && (atLeast ? measured >= boundValue : measured <= boundValue);
  return v;
}

bool allPass(const std::vector<StudyValue>& values) {
  for (const auto& v : values)
    if (!v.pass) return false;
  return !values.empty();
}

StudyReport makeReport(const std::string& study, std::vector<StudyValue> values) {
  StudyReport r;
  r.study = study;
  r.values = std::move(values);
  r.pass = allPass(r.values);
  return r;
}

std::string fixed(double v, int decimals) {
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", decimals, v);
  return b;
}

std::string signedFixed(double v, int decimals) {
  char b[64];
  std::snprintf(b, sizeof b, "%+.*f", decimals, v);
  return b;
}

std::string fixedOrDash(double v, int decimals) { return std::isfinite(v) ? fixed(v, decimals) : std::string("–"); }

std::string reproduceCommand(const std::string& study, const StudyOptions& o) {
  std::string c = "inim study " + study + " --out " + (o.outDir.empty() ? std::string("DIR") : o.outDir);
  if (!o.displayPath.empty()) c += " --display " + o.displayPath;
  if (o.quick) c += " --quick";
  return c;
}

std::string valuesTable(const std::vector<StudyValue>& values, const std::string& unit) {
  std::string s = "| quantity | measured (" + unit + ") | predicted (" + unit + ") | error | tolerance | pass |\n";
  s += "|---|---|---|---|---|---|\n";
  for (const auto& v : values) {
    const double err = v.predicted != 0.0 ? (v.measured - v.predicted) / std::abs(v.predicted) : 0.0;
    s += "| " + v.name + " | " + fixed(v.measured, 3) + " | " + fixed(v.predicted, 3) + " | " + fixed(100.0 * err, 2) +
         "% | ±" + fixed(100.0 * v.tolerance, 0) + "% | " + (v.pass ? "yes" : "**no**") + " |\n";
  }
  return s;
}

std::string boundsTable(const std::vector<StudyValue>& values) {
  std::string s = "| quantity | measured | bound | pass |\n|---|---|---|---|\n";
  for (const auto& v : values)
    s += "| " + v.name + " | " + fixed(v.measured, 2) + " | " + (v.check == StudyValue::Check::AtMost ? "≤ " : "≥ ") +
         fixed(v.predicted, 1) + " | " + (v.pass ? "yes" : "**no**") + " |\n";
  return s;
}

std::string verdictLine(const std::vector<StudyValue>& values) {
  int fails = 0, bounds = 0;
  for (const auto& v : values) {
    fails += v.pass ? 0 : 1;
    bounds += v.check == StudyValue::Check::Relative ? 0 : 1;
  }
  const std::string limit = bounds == int(values.size()) ? "bound" : "tolerance";
  if (fails == 0 && !values.empty()) return "**PASS**: every quantity is within its " + limit + ".";
  return "**FAIL**: " + std::to_string(fails) + " of " + std::to_string(values.size()) + " quantities are outside their " +
         limit + ".";
}

ReportWriter::ReportWriter(std::string study, const StudyOptions& options, const std::string& title)
    : study_(std::move(study)), options_(options), markdown_("# Study: " + title + "\n\n") {}

void ReportWriter::section(const std::string& label, const std::string& text) {
  markdown_ += "**" + label + ".** " + text + "\n\n";
}

void ReportWriter::text(const std::string& markdown) { markdown_ += markdown; }

void ReportWriter::results(const std::vector<StudyValue>& values, const std::string& unit) {
  markdown_ += "**Result.**\n\n" + valuesTable(values, unit) + "\n";
}

void ReportWriter::verdict(const std::string& criterion, const std::vector<StudyValue>& values) {
  markdown_ += "**Verdict** (" + criterion + "): " + verdictLine(values) + "\n\n";
}

void ReportWriter::changes(const std::string& why, const std::vector<StudyValue>& values,
                           const std::vector<EarlierValue>& before, const std::string& unit, int decimals) {
  if (before.size() != values.size()) throw std::logic_error("ReportWriter::changes: one earlier value per value");
  const std::string inUnit = unit.empty() ? "" : " (" + unit + ")";
  const bool bounds = !values.empty() && values.front().check != StudyValue::Check::Relative;
  std::string t = "**What changed.** " + why + "\n\n| quantity | before" + inUnit + " | now" + inUnit + " | " +
                  (bounds ? "bound" : "predicted") + inUnit + " | pass |\n|---|---|---|---|---|\n";
  for (size_t i = 0; i < values.size(); ++i) {
    const StudyValue& v = values[i];
    const EarlierValue& b = before[i];
    const std::string predictedThen = fixed(b.predicted, decimals), predictedNow = fixed(v.predicted, decimals);
    t += "| " + v.name + " | " + fixed(b.measured, decimals) + " | " + fixed(v.measured, decimals) + " | " +
         (predictedThen == predictedNow ? predictedNow : predictedThen + " → " + predictedNow) + " | " +
         (v.pass ? "yes" : "**no**") + " |\n";
  }
  markdown_ += t + "\n";
}

std::string ReportWriter::add(const std::string& name) {
  const std::string finalPath = (std::filesystem::path(options_.outDir) / name).string();
  files_.push_back(finalPath);
  return out_.add(finalPath);
}

void ReportWriter::csv(const std::string& name, const std::vector<std::string>& header,
                       const std::vector<std::vector<std::string>>& rows) {
  writeCsv(add(name), header, rows);
}

void ReportWriter::plot(const std::string& name, const Plot& plot) { writePlot(plot, add(name)); }

void ReportWriter::image(const std::string& name, const Image& image) { writeImage(image, add(name)); }

std::vector<std::string> ReportWriter::commit(const std::string& reproduceComment) {
  markdown_ += "**Reproduce.**\n\n```\n" + reproduceCommand(study_, options_) +
               (reproduceComment.empty() ? "" : "   # " + reproduceComment) + "\n```\n";
  const std::string reportPath = (std::filesystem::path(options_.outDir) / "report.md").string();
  {
    std::ofstream f(out_.add(reportPath));
    f << markdown_;
    if (!f) throw std::runtime_error("cannot write " + reportPath);
  }
  out_.commit();
  std::vector<std::string> files{reportPath};
  files.insert(files.end(), files_.begin(), files_.end());
  return files;
}

}  // namespace inim::study_detail
