#pragma once
// Text helpers shared by every stage: numbers in messages and reports, file extensions.
#include <string>
#include <vector>

namespace inim {

// A number as messages and reports print it: "%.6g" (shortest of fixed or exponent form).
std::string formatNumber(double v);
// A number in a printf format of one double ("%.2f").
std::string formatNumber(double v, const char* format);
// printf into a string (any length).
std::string formatText(const char* format, ...) __attribute__((format(printf, 1, 2)));

// The number of single-character edits between a and b (Levenshtein), for "did you mean".
size_t editDistance(const std::string& a, const std::string& b);
// The name in `names` nearest to `word` within `maxEdits` edits (the first of equals); "" if none.
std::string closestName(const std::string& word, const std::vector<std::string>& names, size_t maxEdits = 2);

// The extension of a file name, lower-cased, with its dot (".exr"); "" when there is none.
std::string lowerExtension(const std::string& path);
// `s` without leading and trailing whitespace (spaces, tabs, CR, LF).
std::string trim(const std::string& s);

}  // namespace inim
