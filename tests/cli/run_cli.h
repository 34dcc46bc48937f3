#pragma once
// Runs the built inim binary and captures its exit status and output.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

struct CliResult {
  int status = -1;
  std::string output;  // stdout and stderr
};

inline CliResult runInimBinary(const std::string& binary, const std::string& args) {
  std::string cmd = binary + " " + args + " 2>&1";
  CliResult r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.output.append(buf.data(), n);
  int st = pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

inline CliResult runInim(const std::string& args) { return runInimBinary(INIM_BINARY, args); }
