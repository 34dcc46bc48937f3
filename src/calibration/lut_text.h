#pragma once
// Number text shared by the LUT writers and readers: shortest exact form out, strict parse in
// (both locale-independent, so files are identical on every machine).
#include <string>
#include <string_view>
#include <vector>

#include "core/geometry.h"

namespace inim {

// The shortest decimal that reads back as exactly v.
std::string exactNumber(double v);
// "r g b" with exactNumber.
std::string tripleText(const Vec3d& v);
// Whitespace-separated tokens of a line.
std::vector<std::string_view> splitWhitespace(std::string_view text);
// True when the whole token is a decimal number; non-finite spellings parse (check isfinite).
bool parseNumber(std::string_view token, double& value);
// The whole file; InputError when it cannot be read.
std::string readTextFile(const std::string& path, const std::string& expected);

}  // namespace inim
