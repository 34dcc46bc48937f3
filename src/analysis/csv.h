#pragma once
// CSV (RFC 4180) for the data behind figures and for tables: fields with a comma, quote or
// newline are quoted, quotes doubled.
#include <string>
#include <vector>

namespace inim {

std::string csvField(const std::string& s);
// A number as CSV text: %.10g; "inf", "-inf" and "nan" for non-finite values.
std::string csvNumber(double v);
std::string csvText(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows);
// Writes header + rows directly to `path`; std::runtime_error if the file cannot be written.
void writeCsv(const std::string& path, const std::vector<std::string>& header,
              const std::vector<std::vector<std::string>>& rows);

}  // namespace inim
