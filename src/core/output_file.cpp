#include "core/output_file.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <mutex>
#include <regex>
#include <stdexcept>

#include "core/error.h"
#include "core/interrupt.h"

namespace fs = std::filesystem;

namespace inim {

namespace {

std::string temporaryName(const fs::path& finalPath, pid_t pid) {
  return "." + finalPath.stem().string() + ".tmp" + std::to_string(pid) + finalPath.extension().string();
}

// The process id in an inim temporary's name (as temporaryName makes it), or 0 if `name` is
// not one.
pid_t temporaryPid(const std::string& name) {
  static const std::regex pattern(R"(^\..+\.tmp([1-9][0-9]{0,9})(\.[^.]*)?$)");
  std::smatch m;
  if (!std::regex_match(name, m, pattern)) return 0;
  const long long pid = std::stoll(m[1].str());
  return pid <= std::numeric_limits<pid_t>::max() ? pid_t(pid) : 0;
}

// Alive unless the kernel says there is no such process (EPERM: someone else's, alive).
bool processAlive(pid_t pid) { return kill(pid, 0) == 0 || errno != ESRCH; }

// fsync, so that a crash after the rename cannot leave an empty or partial output.
void syncFile(const std::string& path) {
  const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0 || fsync(fd) != 0) {
    const std::string why = std::strerror(errno);
    if (fd >= 0) close(fd);
    throw std::runtime_error("cannot flush " + path + " to disk: " + why);
  }
  close(fd);
}

// fsync of a folder makes its renames durable. Best effort: some file systems refuse it, and
// the outputs are already in place.
void syncFolder(const std::string& folder) {
  const int fd = open(folder.empty() ? "." : folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  fsync(fd);
  close(fd);
}

}  // namespace

int removeStaleTemporaries(const std::string& folder) {
  std::error_code ec;
  int removed = 0;
  for (fs::directory_iterator it(folder.empty() ? "." : folder, ec), end; !ec && it != end; it.increment(ec)) {
    const pid_t pid = temporaryPid(it->path().filename().string());
    std::error_code statEc;
    if (pid == 0 || processAlive(pid) || it->symlink_status(statEc).type() != fs::file_type::regular) continue;
    if (fs::remove(it->path(), statEc)) ++removed;
  }
  return removed;
}

OutputSet::~OutputSet() {
  if (committed_) return;
  std::error_code ec;
  for (const auto& e : entries_) fs::remove(e.tmp, ec);
}

namespace {

// Where an output named `asked` is written: the file itself, or the file a symbolic link (or a
// chain of them) names, so that the link stays a link. InputError naming `asked` for a loop or
// a directory.
fs::path outputTarget(const std::string& asked) {
  fs::path p(asked);
  for (int hops = 0; fs::is_symlink(fs::symlink_status(p)); ++hops) {
    if (hops == 40) throw InputError(asked, "", "a loop of symbolic links", "an output file, a new name or a link to one");
    const fs::path to = fs::read_symlink(p);
    p = to.is_absolute() ? to : p.parent_path() / to;
  }
  if (fs::is_directory(p)) throw InputError(asked, "", "a directory", "an output file name");
  return p;
}

}  // namespace

namespace {

std::mutex outputNamesMutex;
std::vector<std::pair<std::string, std::string>> outputNames;  // temporary -> the output asked for

}  // namespace

std::string withOutputNames(std::string message) {
  std::lock_guard<std::mutex> lock(outputNamesMutex);
  for (const auto& [tmp, asked] : outputNames)
    for (size_t at = message.find(tmp); at != std::string::npos; at = message.find(tmp, at + asked.size()))
      message.replace(at, tmp.size(), asked);
  return message;
}

std::string OutputSet::add(const std::string& finalPath) {
  const fs::path p = outputTarget(finalPath);
  std::error_code ec;
  if (p.has_parent_path()) {
    fs::create_directories(p.parent_path(), ec);
    if (ec) throw InputError(finalPath, "", "", "a writable output folder (" + ec.message() + ")");
  }
  const std::string dir = p.has_parent_path() ? p.parent_path().string() : ".";
  if (access(dir.c_str(), W_OK) != 0)  // read-only, or not ours: refused before any work
    throw InputError(finalPath, "", "", "a writable output folder (" + std::string(std::strerror(errno)) + ")");
  const std::string folder = p.parent_path().string();
  if (std::find(folders_.begin(), folders_.end(), folder) == folders_.end()) {
    removeStaleTemporaries(folder);
    folders_.push_back(folder);
  }
  const fs::path tmp = p.parent_path() / temporaryName(p, getpid());
  entries_.push_back({tmp.string(), p.string()});
  {
    std::lock_guard<std::mutex> lock(outputNamesMutex);
    outputNames.emplace_back(tmp.string(), finalPath);
  }
  return tmp.string();
}

void OutputSet::commit() {
  throwIfInterrupted();
  for (const auto& e : entries_) syncFile(e.tmp);
  throwIfInterrupted();  // the last point at which stopping leaves every old output as it was
  // No polling from here: a signal now waits for all renames, so the outputs change together.
  for (const auto& e : entries_) {
    std::error_code ec;
    fs::rename(e.tmp, e.final, ec);
    if (ec) throw std::runtime_error("cannot move " + e.tmp + " to " + e.final + ": " + ec.message());
  }
  committed_ = true;
  for (const auto& folder : folders_) syncFolder(folder);
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
