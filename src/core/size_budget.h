#pragma once
// One memory budget for every large allocation a command makes from its input: image sizes,
// sample counts, EI counts, shapes declared in files. A command asks checkAllocation() before it
// allocates; a size beyond the limit is bad input (InputError naming the setting, the size asked
// for and the limit: exit status 2, nothing written) instead of std::bad_alloc, a machine that
// swaps, or an overflowed count.
//
// The limit: --max-memory (a global option of inim: "8G", "512M", "16GiB", "2e9"), else the
// default, 16 GiB or three quarters of the machine's physical memory when that is less. It bounds
// each request on its own (the largest a command asks for at once), not the sum over a run.
//
//   checkAllocation("", "width/height", "65536 x 65536", {{65536.0 * 65536.0, 5 * 4}}, "the image");
//   // InputError: ... the image needs 80 GiB, more than the memory limit 16 GiB (--max-memory)
#include <cstdint>
#include <initializer_list>
#include <string>

namespace inim {

// count elements of bytesPerElement bytes each (doubles: products of input sizes never wrap).
struct AllocationTerm {
  double count = 0.0;
  double bytesPerElement = 0.0;
};

// The limit in force, bytes.
uint64_t memoryLimitBytes();
// The default limit: min(16 GiB, 3/4 of physical memory).
uint64_t defaultMemoryLimitBytes();
// Sets the limit (the CLI's --max-memory). Tests restore it with ScopedMemoryLimit.
void setMemoryLimitBytes(uint64_t bytes);

class ScopedMemoryLimit {
 public:
  explicit ScopedMemoryLimit(uint64_t bytes) : saved_(memoryLimitBytes()) { setMemoryLimitBytes(bytes); }
  ~ScopedMemoryLimit() { setMemoryLimitBytes(saved_); }
  ScopedMemoryLimit(const ScopedMemoryLimit&) = delete;
  ScopedMemoryLimit& operator=(const ScopedMemoryLimit&) = delete;

 private:
  uint64_t saved_;
};

// "8G", "8GB", "8GiB", "512M", "64k", "2e9" (bytes): powers of 1024 for K/M/G/T, with or without
// "B"/"iB". InputError naming `key` for anything else, zero, or more than 2^62 bytes.
uint64_t parseByteSize(const std::string& text, const std::string& key);
// Bytes as people read them: "512 B", "3.5 MiB", "12 GiB", "11 TiB".
std::string formatBytes(double bytes);

// The bytes of all terms; throws InputError(file, key, value, ...) saying `what` needs that many
// bytes, more than the limit, when the sum is above memoryLimitBytes() (or not finite).
void checkAllocation(const std::string& file, const std::string& key, const std::string& value,
                     std::initializer_list<AllocationTerm> terms, const std::string& what);
// The sum checkAllocation compares with the limit.
double allocationBytes(std::initializer_list<AllocationTerm> terms);

}  // namespace inim
