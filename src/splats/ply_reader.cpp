#include "splats/ply_reader.h"

#include <cctype>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/input_file.h"
#include "core/error.h"

namespace inim {

namespace {

bool parseType(const std::string& t, PlyType* out) {
  static const struct { const char* name; PlyType type; } kTypes[] = {
      {"char", PlyType::Int8},      {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
      {"uint8", PlyType::UInt8},    {"short", PlyType::Int16},     {"int16", PlyType::Int16},
      {"ushort", PlyType::UInt16},  {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
      {"int32", PlyType::Int32},    {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
      {"float", PlyType::Float32},  {"float32", PlyType::Float32}, {"double", PlyType::Float64},
      {"float64", PlyType::Float64}};
  for (const auto& k : kTypes)
    if (t == k.name) {
      *out = k.type;
      return true;
    }
  return false;
}

size_t typeSize(PlyType t) {
  switch (t) {
    case PlyType::Int8: case PlyType::UInt8: return 1;
    case PlyType::Int16: case PlyType::UInt16: return 2;
    case PlyType::Int32: case PlyType::UInt32: case PlyType::Float32: return 4;
    case PlyType::Float64: return 8;
  }
  return 0;
}

template <typename T>
T load(const char* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return v;
}

// The header's lines up to and including end_header; `headerBytes` = where the data starts.
std::vector<std::string> headerLines(const std::string& path, const std::vector<char>& bytes,
                                     size_t* headerBytes) {
  std::vector<std::string> lines;
  size_t start = 0;
  while (start < bytes.size()) {
    size_t end = start;
    while (end < bytes.size() && bytes[end] != '\n') ++end;
    if (end == bytes.size()) break;
    std::string line(bytes.begin() + start, bytes.begin() + end);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
    start = end + 1;
    if (line == "end_header") {
      *headerBytes = start;
      return lines;
    }
    if (lines.size() > 100000) break;
  }
  throw InputError(path, "header", lines.empty() ? "empty" : "no end_header line",
                   "a PLY header ending in end_header");
}

}  // namespace

int PlyElement::find(const std::string& property) const {
  for (size_t i = 0; i < properties.size(); ++i)
    if (properties[i].name == property) return int(i);
  return -1;
}

int PlyElement::require(const std::string& property, const std::string& file) const {
  const int i = find(property);
  if (i < 0) throw InputError(file, name + "." + property, "missing", "a property '" + property + "' in element '" + name + "'");
  return i;
}

PlyFile PlyFile::read(const std::string& path) {
  checkInputFile(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "file", "\"" + path + "\"", "a readable PLY file");
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return parse(path, std::move(bytes));
}

PlyFile PlyFile::parse(std::string path, std::vector<char> bytes) {
  PlyFile f;
  f.path_ = std::move(path);
  f.bytes_ = std::move(bytes);
  size_t dataStart = 0;
  const std::vector<std::string> lines = headerLines(f.path_, f.bytes_, &dataStart);
  if (lines[0] != "ply") throw InputError(f.path_, "magic", "\"" + lines[0] + "\"", "a PLY file starting with 'ply'");
  bool sawFormat = false;
  for (size_t i = 1; i + 1 < lines.size(); ++i) {
    std::istringstream ls(lines[i]);
    std::string word;
    ls >> word;
    if (word == "comment" || word == "obj_info" || word.empty()) continue;
    if (word == "format") {
      std::string fmt, version;
      ls >> fmt >> version;
      if (fmt != "binary_little_endian" && fmt != "ascii")
        throw InputError(f.path_, "format", "\"" + fmt + " " + version + "\"",
                         "binary_little_endian or ascii (big-endian splat files are not supported)");
      f.ascii_ = fmt == "ascii";
      sawFormat = true;
    } else if (word == "element") {
      PlyElement e;
      long long count = -1;
      ls >> e.name >> count;
      if (e.name.empty() || count < 0 || ls.fail())
        throw InputError(f.path_, "element", "\"" + lines[i] + "\"", "'element NAME COUNT' with COUNT >= 0");
      e.count = size_t(count);
      f.elements_.push_back(e);
    } else if (word == "property") {
      if (f.elements_.empty()) throw InputError(f.path_, "property", "\"" + lines[i] + "\"", "a property after an element line");
      PlyElement& e = f.elements_.back();
      std::string type, name;
      ls >> type >> name;
      if (type == "list")
        throw InputError(f.path_, e.name + "." + name, "a list property", "scalar properties only (a splat file has no lists)");
      PlyProperty p;
      p.name = name;
      if (!parseType(type, &p.type) || name.empty())
        throw InputError(f.path_, e.name + "." + name, "\"" + type + "\"", "a PLY scalar type (char uchar short ushort int uint float double)");
      p.offset = e.stride;
      e.stride += typeSize(p.type);
      e.properties.push_back(p);
    } else {
      throw InputError(f.path_, "header", "\"" + lines[i] + "\"", "format, comment, element, property or end_header lines");
    }
  }
  if (!sawFormat) throw InputError(f.path_, "format", "missing", "a 'format binary_little_endian 1.0' line");
  if (f.ascii_) {
    f.convertAscii(dataStart);
    return f;
  }
  // Rows must fit the file: checked before anyone allocates per row.
  size_t offset = dataStart;
  for (PlyElement& e : f.elements_) {
    const size_t remaining = f.bytes_.size() - offset;
    const size_t fits = e.stride == 0 ? e.count : remaining / e.stride;
    if (e.count > fits)
      throw InputError(f.path_, e.name, "count " + std::to_string(e.count),
                       "at most " + std::to_string(fits) + " rows of " + std::to_string(e.stride) +
                           " bytes (the file holds " + std::to_string(remaining) + " bytes from there: truncated?)");
    e.dataOffset = offset;
    offset += e.count * e.stride;
  }
  return f;
}

bool PlyFile::has(const std::string& element) const {
  for (const PlyElement& e : elements_)
    if (e.name == element) return true;
  return false;
}

const PlyElement& PlyFile::element(const std::string& name) const {
  for (const PlyElement& e : elements_)
    if (e.name == name) return e;
  throw InputError(path_, name, "missing", "an element '" + name + "'");
}

// ASCII rows become float64 slots, one per property, so value() reads them like binary ones.
// Each value takes at least 2 characters (a digit and a separator): the counts are checked
// against that before the table is allocated.
void PlyFile::convertAscii(size_t dataStart) {
  size_t slots = 0;
  for (const PlyElement& e : elements_) {
    const size_t maxRows = e.properties.empty() ? e.count : (bytes_.size() - dataStart) / 2 / e.properties.size() + 1;
    if (e.count > maxRows)
      throw InputError(path_, e.name, "count " + std::to_string(e.count),
                       "at most " + std::to_string(maxRows) + " ascii rows in the " + std::to_string(bytes_.size() - dataStart) +
                           " bytes after the header: truncated?");
    slots += e.count * e.properties.size();
  }
  std::vector<char> table(slots * sizeof(double));
  std::string text(bytes_.begin() + std::ptrdiff_t(dataStart), bytes_.end());
  const char* cur = text.c_str();
  size_t offset = 0;
  for (PlyElement& e : elements_) {
    e.stride = e.properties.size() * sizeof(double);
    for (size_t k = 0; k < e.properties.size(); ++k) e.properties[k].offset = k * sizeof(double);
    e.dataOffset = offset;
    for (size_t row = 0; row < e.count; ++row)
      for (const PlyProperty& p : e.properties) {
        while (*cur == ' ' || *cur == '\t' || *cur == '\r' || *cur == '\n') ++cur;
        if (*cur == '\0')
          throw InputError(path_, e.name, "count " + std::to_string(e.count),
                           "as many ascii rows (the file ends in row " + std::to_string(row) + ")");
        char* end = nullptr;
        const double v = std::strtod(cur, &end);
        if (end == cur || (*end != '\0' && !std::isspace(static_cast<unsigned char>(*end)))) {
          std::string token(cur, std::strcspn(cur, " \t\r\n"));
          throw InputError(path_, e.name + "." + p.name, "\"" + token + "\" (row " + std::to_string(row) + ")", "a number");
        }
        std::memcpy(&table[offset], &v, sizeof v);
        offset += sizeof v;
        cur = end;
      }
  }
  bytes_ = std::move(table);
}

double PlyFile::value(const PlyElement& e, size_t row, int property) const {
  const PlyProperty& p = e.properties[size_t(property)];
  const char* at = bytes_.data() + e.dataOffset + row * e.stride + p.offset;
  if (ascii_) return load<double>(at);
  switch (p.type) {
    case PlyType::Int8: return load<int8_t>(at);
    case PlyType::UInt8: return load<uint8_t>(at);
    case PlyType::Int16: return load<int16_t>(at);
    case PlyType::UInt16: return load<uint16_t>(at);
    case PlyType::Int32: return load<int32_t>(at);
    case PlyType::UInt32: return load<uint32_t>(at);
    case PlyType::Float32: return load<float>(at);
    case PlyType::Float64: return load<double>(at);
  }
  return 0.0;
}

uint32_t PlyFile::valueU32(const PlyElement& e, size_t row, int property) const {
  return uint32_t(value(e, row, property));
}

}  // namespace inim
