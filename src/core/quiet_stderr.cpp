#include "core/quiet_stderr.h"
#include "core/file_kinds.h"

#include <fcntl.h>
#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <mutex>

namespace inim {

namespace {
std::mutex gMutex;
int gUsers = 0;     // readers in progress
int gSaved = -1;    // the real stderr while redirected
}  // namespace

LibraryStderrSilenced::LibraryStderrSilenced(const std::string& path) {
  if (!isFileKind(path, FileKind::Png)) return;
  std::lock_guard<std::mutex> lock(gMutex);
  active_ = true;
  if (gUsers++ > 0) return;
  std::fflush(stderr);
  const int null = open("/dev/null", O_WRONLY);
  if (null < 0) return;
  gSaved = dup(STDERR_FILENO);
  if (gSaved >= 0) dup2(null, STDERR_FILENO);
  close(null);
}

LibraryStderrSilenced::~LibraryStderrSilenced() {
  if (!active_) return;
  std::lock_guard<std::mutex> lock(gMutex);
  if (--gUsers > 0 || gSaved < 0) return;
  std::fflush(stderr);
  dup2(gSaved, STDERR_FILENO);
  close(gSaved);
  gSaved = -1;
}

}  // namespace inim
