#pragma once
// Errors caused by user input carry their context: file, key, bad value, and what was
// expected. The CLI turns them into one clear message and exit status 2.
#include <stdexcept>
#include <string>

namespace inim {

class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::string key, std::string value, std::string expected);
  const std::string& file() const { return file_; }
  const std::string& key() const { return key_; }
  const std::string& value() const { return value_; }
  const std::string& expected() const { return expected_; }
  // Returns a copy with the file filled in, when the thrower did not know it.
  InputError withFile(const std::string& file) const;

 private:
  static std::string format(const std::string& file, const std::string& key,
                            const std::string& value, const std::string& expected);
  std::string file_, key_, value_, expected_;
};

// Exit status for bad input, as the README promises.
constexpr int kExitBadInput = 2;
// Exit status of a run that worked and wrote its outputs but whose result misses the grade it
// was held to (inim calibrate --grade): distinct from bad input.
constexpr int kExitGradeFailed = 3;

class GradeFailed : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace inim
