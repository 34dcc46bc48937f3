#include "core/error.h"

namespace inim {

InputError::InputError(std::string file, std::string key, std::string value, std::string expected)
    : std::runtime_error(format(file, key, value, expected)),
      file_(std::move(file)),
      key_(std::move(key)),
      value_(std::move(value)),
      expected_(std::move(expected)) {}

std::string InputError::format(const std::string& file, const std::string& key,
                               const std::string& value, const std::string& expected) {
  std::string msg = file;
  auto part = [&msg](const char* sep, const char* label, const std::string& text) {
    if (text.empty()) return;
    if (!msg.empty()) msg.append(sep);
    msg.append(label).append(text);
  };
  part(": ", "key '", key);
  if (!key.empty()) msg.append("'");
  part(": ", "value ", value);
  part("; ", "expected ", expected);
  return msg;
}

InputError InputError::withFile(const std::string& file) const {
  if (!file_.empty()) return *this;
  return InputError(file, key_, value_, expected_);
}

}  // namespace inim
