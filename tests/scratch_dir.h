#pragma once
// A scratch folder for one test program, removed when the program ends.
#include <unistd.h>

#include <filesystem>
#include <string>

class ScratchDir {
 public:
  explicit ScratchDir(const std::string& tag)
      : dir_(std::filesystem::temp_directory_path() / ("inim_" + tag + "_" + std::to_string(getpid()))) {}
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  const std::filesystem::path& dir() const { return dir_; }
  // `name` inside the folder, which is created on first use.
  std::string path(const std::string& name) const {
    std::filesystem::create_directories(dir_);
    return (dir_ / name).string();
  }

 private:
  std::filesystem::path dir_;
};
