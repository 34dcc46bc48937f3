#include "core/text_encoding.h"

#include "core/error.h"

namespace inim {

namespace {

void appendUtf8(std::string& out, unsigned u) {
  if (u < 0x80) {
    out += char(u);
  } else if (u < 0x800) {
    out += char(0xC0 | u >> 6), out += char(0x80 | (u & 0x3F));
  } else if (u < 0x10000) {
    out += char(0xE0 | u >> 12), out += char(0x80 | (u >> 6 & 0x3F)), out += char(0x80 | (u & 0x3F));
  } else {
    out += char(0xF0 | u >> 18), out += char(0x80 | (u >> 12 & 0x3F));
    out += char(0x80 | (u >> 6 & 0x3F)), out += char(0x80 | (u & 0x3F));
  }
}

// The length of the valid UTF-8 sequence at bytes[i] and its code point, or 0 when invalid.
size_t utf8Sequence(const std::string& bytes, size_t i, unsigned& codePoint) {
  const unsigned char c = static_cast<unsigned char>(bytes[i]);
  const size_t n = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 0;
  if (n == 0 || i + n > bytes.size()) return 0;
  codePoint = n == 1 ? c : n == 2 ? (c & 0x1F) : n == 3 ? (c & 0x0F) : (c & 0x07);
  for (size_t k = 1; k < n; ++k) {
    const unsigned char t = static_cast<unsigned char>(bytes[i + k]);
    if ((t >> 6) != 0x2) return 0;
    codePoint = codePoint << 6 | (t & 0x3F);
  }
  return n;
}

bool isUtf8(const std::string& bytes) {
  unsigned cp = 0;
  for (size_t i = 0, n; i < bytes.size(); i += n)
    if ((n = utf8Sequence(bytes, i, cp)) == 0) return false;
  return true;
}

// Windows files that are not UTF-8 are almost always Latin-1 (Windows-1252's printable range).
std::string utf8FromLatin1(const std::string& bytes) {
  std::string out;
  out.reserve(bytes.size());
  for (char c : bytes) appendUtf8(out, static_cast<unsigned char>(c));
  return out;
}

}  // namespace

std::string utf8FromBytes(const std::string& bytes, const std::string& file) {
  auto at = [&](size_t i) { return static_cast<unsigned char>(bytes[i]); };
  if (bytes.size() >= 3 && at(0) == 0xEF && at(1) == 0xBB && at(2) == 0xBF) return bytes.substr(3);
  bool le = bytes.size() >= 2 && at(0) == 0xFF && at(1) == 0xFE;
  const bool be = bytes.size() >= 2 && at(0) == 0xFE && at(1) == 0xFF;
  const size_t start = le || be ? 2 : 0;
  if (!le && !be && bytes.size() >= 4 && bytes[1] == '\0' && bytes[3] == '\0') le = true;  // no mark
  if (!le && !be) return isUtf8(bytes) ? bytes : utf8FromLatin1(bytes);
  if ((bytes.size() - start) % 2 != 0) throw InputError(file, "", "an odd number of bytes", "UTF-16 text");
  std::string out;
  out.reserve((bytes.size() - start) / 2);
  for (size_t i = start; i + 1 < bytes.size(); i += 2) {
    const unsigned u = le ? at(i) | at(i + 1) << 8 : at(i) << 8 | at(i + 1);
    const bool high = u >= 0xD800 && u <= 0xDBFF, low = u >= 0xDC00 && u <= 0xDFFF;
    if (high && i + 3 < bytes.size()) {
      const unsigned v = le ? at(i + 2) | at(i + 3) << 8 : at(i + 2) << 8 | at(i + 3);
      if (v >= 0xDC00 && v <= 0xDFFF) {
        appendUtf8(out, 0x10000 + ((u - 0xD800) << 10) + (v - 0xDC00));
        i += 2;
        continue;
      }
    }
    appendUtf8(out, high || low ? unsigned('?') : u);  // an unpaired surrogate
  }
  return out;
}

std::string utf16leWithBom(const std::string& utf8) {
  std::string out = "\xFF\xFE";
  auto unit = [&](unsigned u) { out += char(u & 0xFF), out += char(u >> 8); };
  for (size_t i = 0; i < utf8.size();) {
    unsigned cp = 0;
    const size_t n = utf8Sequence(utf8, i, cp);
    if (n == 0) cp = static_cast<unsigned char>(utf8[i]);  // Latin-1
    if (cp >= 0x10000) {
      unit(0xD800 + ((cp - 0x10000) >> 10)), unit(0xDC00 + ((cp - 0x10000) & 0x3FF));
    } else {
      unit(cp);
    }
    i += n == 0 ? 1 : n;
  }
  return out;
}

}  // namespace inim
