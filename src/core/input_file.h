#pragma once
// Every file inim reads passes this check before it is opened: a regular file (a directory, a
// device such as /dev/zero, a pipe or a loop of symbolic links is refused at once, instead of a
// raw library error or a read that never ends) no larger than inputFileLimitBytes(), since most
// readers hold a file whole (core/size_budget.h). A file that does not exist is left to the reader, which
// names what it expected.
#include <cstdint>
#include <string>

namespace inim {

// The largest input file: the memory limit, but never below 64 MiB, so that the program's own
// data (spectra, optics) loads under any --max-memory a small run is given.
constexpr uint64_t kMinInputFileLimitBytes = uint64_t(64) << 20;
uint64_t inputFileLimitBytes();
// The file's size in bytes (0 when it does not exist); InputError naming `path` otherwise.
uint64_t checkInputFile(const std::string& path);
// The file's bytes, after checkInputFile; InputError naming `path` when it cannot be read.
std::string readInputFile(const std::string& path);

}  // namespace inim
