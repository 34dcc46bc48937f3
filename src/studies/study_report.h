#pragma once
// The toolbox every study writes its report with (not part of the public interface): the
// verdict's values, the markdown of report.md (title, sections, value table, verdict, the
// command that reproduces the run) and the files beside it (CSV, plots, images). Every file
// goes through one OutputSet, so report.md and the others are renamed into place together,
// and only when the whole study succeeded.
#include <string>
#include <vector>

#include "analysis/plot.h"
#include "core/image.h"
#include "core/output_file.h"
#include "studies/studies.h"

namespace inim::study_detail {

// A value judged against its prediction: pass when |measured - predicted| <= tolerance |predicted|.
StudyValue compare(const std::string& name, double measured, double predicted, double tolerance);
// A value judged against a one-sided bound: measured >= bound (atLeast) or measured <= bound.
StudyValue bound(const std::string& name, double measured, double boundValue, bool atLeast);
// Every value passes (and there is at least one).
bool allPass(const std::vector<StudyValue>& values);
// The public result of a study: its name, values and verdict (the files are added by commit).
StudyReport makeReport(const std::string& study, std::vector<StudyValue> values);

// A number with a fixed count of decimals ("%.*f"), as the reports' tables print it.
std::string fixed(double v, int decimals);
// The same with its sign always written ("+0.028", "-0.011").
std::string signedFixed(double v, int decimals);
// The same as fixed, or "–" for a value that could not be measured.
std::string fixedOrDash(double v, int decimals);

// "inim study NAME --out DIR [--display FILE] [--quick]": the command that reproduces the run.
std::string reproduceCommand(const std::string& study, const StudyOptions& o);
// Markdown table of values judged against predictions (measured, predicted, error, tolerance).
std::string valuesTable(const std::vector<StudyValue>& values, const std::string& unit);
// Markdown table of values judged against one-sided bounds (measured, bound).
std::string boundsTable(const std::vector<StudyValue>& values);
// "**PASS**: ..." or "**FAIL**: n of m ...".
std::string verdictLine(const std::vector<StudyValue>& values);

// A verdict value as an earlier version of the study measured it (for "What changed").
struct EarlierValue {
  double measured = 0.0, predicted = 0.0;
};

// report.md of one study and the files written beside it, in the folder StudyOptions::outDir.
//   ReportWriter w("flip-onset", o, "flip onset");
//   w.section("What", "...");  w.csv("data.csv", header, rows);  w.plot("data.png", plot);
//   w.results(values, "deg");  w.verdict("tolerance ±10%", values);
//   report.files = w.commit();
class ReportWriter {
 public:
  // `title` follows "# Study: " on the report's first line.
  ReportWriter(std::string study, const StudyOptions& options, const std::string& title);

  // A paragraph "**Label.** text" (What, Prediction, Method, Discussion, ...).
  void section(const std::string& label, const std::string& text);
  // Markdown appended as it is (lists, extra tables, image links); the caller ends it with "\n\n".
  void text(const std::string& markdown);
  // "**Result.**" and the table of the values (unit of the measured and predicted columns).
  void results(const std::vector<StudyValue>& values, const std::string& unit);
  // "**Verdict** (criterion): " and the verdict line of the values.
  void verdict(const std::string& criterion, const std::vector<StudyValue>& values);
  // "**What changed.** why" and a table of the values against `before` (the same quantities, in
  // the same order): measured then and now, the prediction or bound (then -> now where it moved).
  // An empty unit leaves the columns without one (the quantities name their own).
  void changes(const std::string& why, const std::vector<StudyValue>& values, const std::vector<EarlierValue>& before,
               const std::string& unit, int decimals = 3);

  // Files beside report.md, named relative to the study's folder; each is recorded for commit.
  void csv(const std::string& name, const std::vector<std::string>& header,
           const std::vector<std::vector<std::string>>& rows);
  void plot(const std::string& name, const Plot& plot);
  void image(const std::string& name, const Image& image);
  // A file the caller writes itself: the temporary path for `name` (recorded for commit).
  std::string file(const std::string& name) { return add(name); }
  // The report's outputs, for runs that add files of their own (renamed with the report).
  OutputSet& outputs() { return out_; }

  // Appends the Reproduce block (with an optional comment on the command), writes report.md and
  // renames every file into place. Returns the final paths, report.md first, then the files in
  // the order they were added.
  std::vector<std::string> commit(const std::string& reproduceComment = "");

 private:
  std::string add(const std::string& name);  // the temporary path to write for `name`

  std::string study_;
  StudyOptions options_;
  std::string markdown_;
  OutputSet out_;
  std::vector<std::string> files_;
};

}  // namespace inim::study_detail
