#include "core/error.h"

#include <sstream>

namespace inim {

InputError::InputError(std::string file, std::string key, std::string value, std::string expected)
    : std::runtime_error(format(file, key, value, expected)),
      file_(std::move(file)),
      key_(std::move(key)),
      value_(std::move(value)),
      expected_(std::move(expected)) {}

std::string InputError::format(const std::string& file, const std::string& key,
                               const std::string& value, const std::string& expected) {
  std::ostringstream msg;
  const char* sep = "";
  if (!file.empty()) msg << file, sep = ": ";
  if (!key.empty()) msg << sep << "key '" << key << "'", sep = ": ";
  if (!value.empty()) msg << sep << "value " << value, sep = "; ";
  if (!expected.empty()) msg << (*sep ? "; " : "") << "expected " << expected;
  return msg.str();
}

InputError InputError::withFile(const std::string& file) const {
  if (!file_.empty()) return *this;
  return InputError(file, key_, value_, expected_);
}

}  // namespace inim
