#include "core/input_file.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "core/error.h"
#include "core/size_budget.h"

namespace fs = std::filesystem;

namespace inim {

uint64_t inputFileLimitBytes() { return std::max(memoryLimitBytes(), kMinInputFileLimitBytes); }

uint64_t checkInputFile(const std::string& path) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);  // through symbolic links
  if (ec == std::errc::too_many_symbolic_link_levels)
    throw InputError(path, "", "a loop of symbolic links", "a regular file");
  if (ec || st.type() == fs::file_type::not_found) return 0;
  if (st.type() == fs::file_type::directory) throw InputError(path, "", "a directory", "a regular file");
  if (st.type() != fs::file_type::regular)
    throw InputError(path, "", "a device, pipe or socket", "a regular file (its size known before reading)");
  const uint64_t size = fs::file_size(path, ec);
  if (ec) return 0;
  const uint64_t limit = inputFileLimitBytes();
  if (size > limit)
    throw InputError(path, "", formatBytes(double(size)),
                     "a file no larger than " + formatBytes(double(limit)) + " (the memory limit, --max-memory)");
  return size;
}

std::string readInputFile(const std::string& path) {
  checkInputFile(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "unreadable", "a readable file");
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

}  // namespace inim
