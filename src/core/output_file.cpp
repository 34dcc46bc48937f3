#include "core/output_file.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "core/error.h"

namespace fs = std::filesystem;

namespace inim {

OutputSet::~OutputSet() {
  if (committed_) return;
  std::error_code ec;
  for (const auto& e : entries_) fs::remove(e.tmp, ec);
}

std::string OutputSet::add(const std::string& finalPath) {
  fs::path p(finalPath);
  std::error_code ec;
  if (p.has_parent_path()) {
    fs::create_directories(p.parent_path(), ec);
    if (ec) throw InputError(finalPath, "", "", "a writable output folder (" + ec.message() + ")");
  }
  fs::path tmp = p.parent_path() /
                 ("." + p.stem().string() + ".tmp" + std::to_string(getpid()) + p.extension().string());
  entries_.push_back({tmp.string(), finalPath});
  return tmp.string();
}

void OutputSet::commit() {
  for (const auto& e : entries_) {
    std::error_code ec;
    fs::rename(e.tmp, e.final, ec);
    if (ec) throw std::runtime_error("cannot move " + e.tmp + " to " + e.final + ": " + ec.message());
  }
  committed_ = true;
}

std::string dataDir() {
  if (const char* env = std::getenv("INIM_DATA_DIR"); env && *env) return env;
  return INIM_SOURCE_DATA_DIR;
}

std::string dataPath(const std::string& rel) {
  fs::path p(rel);
  if (p.is_absolute() || fs::exists(p)) return rel;
  return (fs::path(dataDir()) / p).string();
}

void writeTextFile(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error("cannot write " + path);
  out << text;
  out.close();
  if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace inim
