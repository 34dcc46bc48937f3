#include "rays/zemax_ray_text.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>

#include "core/input_file.h"
#include "core/error.h"
#include "core/parallel.h"
#include "core/progress.h"

namespace inim {

namespace {

// Appends "%.8f" of v.
void appendFixed8(std::string& s, double v) {
  char buf[64];
  auto res = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, 8);
  s.append(buf, res.ptr);
}

void appendLine(std::string& s, const double v[6], bool crlf) {
  for (int c = 0; c < 6; ++c) {
    if (c) s += ", ";
    appendFixed8(s, v[c]);
  }
  s += crlf ? "\r\n" : "\n";
}

// ASCII text to the bytes of the chosen encoding.
std::string encode(const std::string& text, bool utf16) {
  if (!utf16) return text;
  std::string out(text.size() * 2, '\0');
  for (size_t i = 0; i < text.size(); ++i) out[2 * i] = text[i];
  return out;
}

struct FileCloser {
  void operator()(std::FILE* f) const {
    if (f) std::fclose(f);
  }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

FilePtr openForWrite(const std::string& path) {
  FilePtr f(std::fopen(path.c_str(), "wb"));
  if (!f) throw InputError(path, "", "", "a writable output file (" + std::string(std::strerror(errno)) + ")");
  return f;
}

void writeBytes(std::FILE* f, const std::string& bytes, const std::string& path) {
  if (!bytes.empty() && std::fwrite(bytes.data(), 1, bytes.size(), f) != bytes.size())
    throw InputError(path, "", "", "a writable output file (write failed: disk full?)");
}

}  // namespace

std::string formatZemaxRayLine(const double v[6]) {
  std::string s;
  appendLine(s, v, false);
  s.pop_back();
  return s;
}

std::vector<std::string> zemaxMacroHeader(int64_t count) {
  return {"Ray data for the pupil of one lenslet: x, y, z, l, m, n (mm, direction cosines)",
          "Number of rays: " + std::to_string(count)};
}

void writeZemaxRayText(const std::string& path, int64_t count,
                       const std::function<void(int64_t, double*)>& ray,
                       const ZemaxTextOptions& options, ProgressBar* progress) {
  FilePtr f = openForWrite(path);
  std::string head;
  if (options.utf16) head = "\xFF\xFE";
  std::string lines;
  for (const auto& h : options.header) lines += h + (options.crlf ? "\r\n" : "\n");
  head += encode(lines, options.utf16);
  writeBytes(f.get(), head, path);

  // Format chunks in parallel, a batch at a time, and write them in order.
  constexpr int64_t kChunk = 16384;
  const int64_t chunksPerBatch = std::max(4, 4 * hardwareThreads());
  std::vector<std::string> chunks(static_cast<size_t>(chunksPerBatch));
  for (int64_t b0 = 0; b0 < count; b0 += kChunk * chunksPerBatch) {
    int64_t nChunks = std::min(chunksPerBatch, (count - b0 + kChunk - 1) / kChunk);
    parallelForRange(
        nChunks,
        [&](int64_t c0, int64_t c1) {
          for (int64_t c = c0; c < c1; ++c) {
            std::string& s = chunks[size_t(c)];
            s.clear();
            int64_t r0 = b0 + c * kChunk, r1 = std::min(count, r0 + kChunk);
            s.reserve(size_t(r1 - r0) * 80);
            double v[6];
            for (int64_t r = r0; r < r1; ++r) {
              ray(r, v);
              appendLine(s, v, options.crlf);
            }
            if (options.utf16) s = encode(s, true);
          }
        },
        nullptr, 1);
    for (int64_t c = 0; c < nChunks; ++c) writeBytes(f.get(), chunks[size_t(c)], path);
    if (progress) progress->add(uint64_t(std::min(count - b0, kChunk * nChunks)));
  }
  if (std::fflush(f.get()) != 0) throw InputError(path, "", "", "a writable output file (flush failed)");
}

void writeZemaxRayText(const std::string& path, const RaySet& rays, const ZemaxTextOptions& options,
                       ProgressBar* progress) {
  writeZemaxRayText(
      path, int64_t(rays.size()),
      [&](int64_t i, double* v) {
        size_t k = size_t(i);
        v[0] = rays.ox[k], v[1] = rays.oy[k], v[2] = rays.oz[k];
        v[3] = rays.dx[k], v[4] = rays.dy[k], v[5] = rays.dz[k];
      },
      options, progress);
}

void writeZemaxRayText(const std::string& path, const EiLayout& L, const ZemaxTextOptions& options,
                       ProgressBar* progress) {
  writeZemaxRayText(
      path, L.numRays(),
      [&](int64_t i, double* v) {
        RayD r = pinholeRay(L, i);
        v[0] = r.o.x, v[1] = r.o.y, v[2] = r.o.z;
        v[3] = r.d.x, v[4] = r.d.y, v[5] = r.d.z;
      },
      options, progress);
}

void writeZemaxEiRayText(const std::string& path, const EiLayout& L, int k, int l,
                         const ZemaxTextOptions& options) {
  const int64_t first = L.eiRayBegin(k, l);  // the EI's first ray in ray order
  const double cx = L.pinholeXAt(k, l), cy = L.pinholeYAt(k, l);
  writeZemaxRayText(
      path, L.eiRayCount(k, l),
      [&](int64_t i, double* v) {
        RayD r = pinholeRay(L, first + i);
        v[0] = r.o.x - cx, v[1] = r.o.y - cy, v[2] = r.o.z;
        v[3] = r.d.x, v[4] = r.d.y, v[5] = r.d.z;
      },
      options);
}

// ---------------------------------------------------------------- reader

namespace {

bool parseRayLine(const char* b, const char* e, double v[6]) {
  const char* p = b;
  for (int c = 0; c < 6; ++c) {
    while (p < e && (*p == ' ' || *p == '\t')) ++p;
    if (p < e && *p == '+') ++p;
    auto res = std::from_chars(p, e, v[c]);
    if (res.ec != std::errc() || !std::isfinite(v[c])) return false;
    p = res.ptr;
    while (p < e && (*p == ' ' || *p == '\t')) ++p;
    if (c < 5) {
      if (p >= e || *p != ',') return false;
      ++p;
    }
  }
  return p == e;
}

// A line of six comma-separated fields made of number characters (a ray with a NaN or an
// unreadable number), as opposed to a header line of words.
bool looksLikeRayLine(const char* b, const char* e) {
  if (std::count(b, e, ',') != 5) return false;
  return std::all_of(b, e, [](char c) { return std::strchr("0123456789+-.eE, \tnaNAifIF", c) != nullptr; });
}

}  // namespace

RaySet readZemaxRayText(const std::string& path, std::vector<std::string>* header) {
  checkInputFile(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "", "a readable ray text file (cannot open it)");
  in.seekg(0, std::ios::end);
  const int64_t fileSize = int64_t(in.tellg());
  in.seekg(0);

  // Encoding from the BOM (or, without one, from a zero second byte).
  unsigned char bom[3] = {0, 0, 0};
  in.read(reinterpret_cast<char*>(bom), 3);
  std::streamsize got = in.gcount();
  in.clear();
  enum { Utf8, Utf16LE, Utf16BE } enc = Utf8;
  int skip = 0;
  if (got >= 2 && bom[0] == 0xFF && bom[1] == 0xFE) enc = Utf16LE, skip = 2;
  else if (got >= 2 && bom[0] == 0xFE && bom[1] == 0xFF) enc = Utf16BE, skip = 2;
  else if (got >= 3 && bom[0] == 0xEF && bom[1] == 0xBB && bom[2] == 0xBF) skip = 3;
  else if (got >= 2 && bom[0] != 0 && bom[1] == 0) enc = Utf16LE;
  else if (got >= 2 && bom[0] == 0 && bom[1] != 0) enc = Utf16BE;
  in.seekg(skip);

  RaySet rays;
  const size_t estimate = size_t(std::max<int64_t>(0, fileSize) / (enc == Utf8 ? 60 : 120));
  for (auto* v : {&rays.ox, &rays.oy, &rays.oz, &rays.dx, &rays.dy, &rays.dz}) v->reserve(estimate);

  int64_t lineNo = 0;
  bool inData = false;
  auto handleLine = [&](const char* b, const char* e) {
    ++lineNo;
    while (e > b && (e[-1] == '\r' || e[-1] == ' ' || e[-1] == '\t')) --e;
    const char* s = b;
    while (s < e && (*s == ' ' || *s == '\t')) ++s;
    if (s == e) return;  // blank
    double v[6];
    if (!parseRayLine(s, e, v)) {
      if (!inData && !looksLikeRayLine(s, e)) {
        if (header) header->emplace_back(b, e);
        return;
      }
      throw InputError(path, "line " + std::to_string(lineNo), "\"" + std::string(b, std::min(e, b + 80)) + "\"",
                       "six comma-separated numbers x, y, z, l, m, n");
    }
    checkRay(Vec3d(v[0], v[1], v[2]), Vec3d(v[3], v[4], v[5]), path, "line " + std::to_string(lineNo));
    inData = true;
    rays.ox.push_back(float(v[0]));
    rays.oy.push_back(float(v[1]));
    rays.oz.push_back(float(v[2]));
    rays.dx.push_back(float(v[3]));
    rays.dy.push_back(float(v[4]));
    rays.dz.push_back(float(v[5]));
  };

  constexpr size_t kBlock = 1 << 20;
  std::vector<char> raw(kBlock);
  std::string text;        // decoded, not yet split into lines
  std::string carryBytes;  // an odd trailing byte of UTF-16
  while (in) {
    in.read(raw.data(), std::streamsize(raw.size()));
    size_t n = size_t(in.gcount());
    if (n == 0) break;
    if (enc == Utf8) {
      text.append(raw.data(), n);
    } else {
      std::string bytes = carryBytes + std::string(raw.data(), n);
      size_t pairs = bytes.size() / 2;
      carryBytes = bytes.substr(pairs * 2);
      size_t base = text.size();
      text.resize(base + pairs);
      for (size_t i = 0; i < pairs; ++i) {
        unsigned lo = (unsigned char)bytes[2 * i], hi = (unsigned char)bytes[2 * i + 1];
        unsigned cu = enc == Utf16LE ? (lo | hi << 8) : (hi | lo << 8);
        text[base + i] = cu < 128 ? char(cu) : '?';
      }
    }
    size_t start = 0;
    for (size_t nl; (nl = text.find('\n', start)) != std::string::npos; start = nl + 1)
      handleLine(text.data() + start, text.data() + nl);
    text.erase(0, start);
  }
  if (!text.empty()) handleLine(text.data(), text.data() + text.size());
  if (rays.empty()) throw InputError(path, "", "no ray lines", "at least one line x, y, z, l, m, n");
  return rays;
}

}  // namespace inim
