#include "core/size_budget.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/error.h"

namespace inim {

namespace {

constexpr uint64_t kGiB = uint64_t(1) << 30;
constexpr double kMaxLimit = 4611686018427387904.0;  // 2^62 bytes

uint64_t physicalMemoryBytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && pageSize > 0 ? uint64_t(pages) * uint64_t(pageSize) : 0;
}

std::atomic<uint64_t>& limit() {
  static std::atomic<uint64_t> bytes{defaultMemoryLimitBytes()};
  return bytes;
}

}  // namespace

uint64_t defaultMemoryLimitBytes() {
  const uint64_t physical = physicalMemoryBytes();
  return physical ? std::min(16 * kGiB, physical / 4 * 3) : 16 * kGiB;
}

uint64_t memoryLimitBytes() { return limit().load(); }
void setMemoryLimitBytes(uint64_t bytes) { limit().store(bytes); }

uint64_t parseByteSize(const std::string& text, const std::string& key) {
  const std::string expected = "a memory size such as 8G, 512M or 2e9 (bytes; K, M, G, T are powers of 1024)";
  const char* begin = text.c_str();
  char* end = nullptr;
  const double number = std::strtod(begin, &end);
  if (end == begin) throw InputError("", key, "\"" + text + "\"", expected);
  std::string unit(end);
  for (char& c : unit) c = char(std::toupper(static_cast<unsigned char>(c)));
  if (unit.size() > 1 && unit.back() == 'B') unit.pop_back();
  if (unit.size() > 1 && unit.back() == 'I') unit.pop_back();
  const std::string units = "KMGT";
  double scale = 1.0;
  if (unit.size() == 1 && units.find(unit[0]) != std::string::npos)
    scale = std::pow(1024.0, double(units.find(unit[0]) + 1));
  else if (!unit.empty())
    throw InputError("", key, "\"" + text + "\"", expected);
  const double bytes = number * scale;
  if (!(bytes >= 1.0 && bytes <= kMaxLimit)) throw InputError("", key, "\"" + text + "\"", expected + ", 1 byte to 4 EiB");
  return uint64_t(bytes);
}

std::string formatBytes(double bytes) {
  static const char* kUnits[] = {"B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  if (!std::isfinite(bytes)) return "more than 2^64 bytes";
  int u = 0;
  while (bytes >= 1024.0 && u < 6) bytes /= 1024.0, ++u;
  char buf[64];
  std::snprintf(buf, sizeof buf, u == 0 ? "%.0f %s" : "%.3g %s", bytes, kUnits[u]);
  return buf;
}

double allocationBytes(std::initializer_list<AllocationTerm> terms) {
  double sum = 0.0;
  for (const AllocationTerm& t : terms) sum += std::max(0.0, t.count) * std::max(0.0, t.bytesPerElement);
  return sum;
}

void checkAllocation(const std::string& file, const std::string& key, const std::string& value,
                     std::initializer_list<AllocationTerm> terms, const std::string& what) {
  const double bytes = allocationBytes(terms);
  const uint64_t max = memoryLimitBytes();
  if (bytes <= double(max)) return;
  throw InputError(file, key, value,
                   "a size within the memory limit: " + what + " needs " + formatBytes(bytes) +
                       ", more than the memory limit of " + formatBytes(double(max)) +
                       " (--max-memory raises it)");
}

}  // namespace inim
