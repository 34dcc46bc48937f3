#pragma once
// Text helpers shared by every stage: numbers in messages and reports, file extensions.
#include <string>

namespace inim {

// A number as messages and reports print it: "%.6g" (shortest of fixed or exponent form).
std::string formatNumber(double v);
// A number in a printf format of one double ("%.2f").
std::string formatNumber(double v, const char* format);

// The extension of a file name, lower-cased, with its dot (".exr"); "" when there is none.
std::string lowerExtension(const std::string& path);
// `s` without leading and trailing whitespace (spaces, tabs, CR, LF).
std::string trim(const std::string& s);

}  // namespace inim
