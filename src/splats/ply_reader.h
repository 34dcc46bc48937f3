#pragma once
// A PLY file (binary little-endian or ascii) held in memory: its header (elements and their
// scalar properties, looked up by name) and typed access to the rows. Enough for the splat layouts
// (splats/splat_loaders.h), which name their properties but do not agree on order, normals,
// comments or types. Every element's row count is checked against the file size when the
// header is read, before any caller allocates for it; bytes after the last element are
// allowed (some writers leave them). ASCII rows are parsed once into float64 slots.
//
//   PlyFile ply = PlyFile::read("scene.ply");
//   const PlyElement& v = ply.element("vertex");       // InputError when absent
//   int ix = v.require("x", ply.path());                  // InputError "vertex.x" when absent
//   double x0 = ply.value(v, 0, ix);
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace inim {

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float32;
  size_t offset = 0;  // bytes from the start of the row
};

struct PlyElement {
  std::string name;
  size_t count = 0;
  size_t stride = 0;      // bytes per row
  size_t dataOffset = 0;  // file offset of the first row
  std::vector<PlyProperty> properties;

  int find(const std::string& property) const;  // -1 when absent
  // The property's index; InputError(file, "element.property", "missing", ...) when absent.
  int require(const std::string& property, const std::string& file) const;
};

class PlyFile {
 public:
  // Reads and checks the header (InputError naming the file and the offending line's key).
  static PlyFile read(const std::string& path);
  // Parses a file already in memory (`path` names it in errors).
  static PlyFile parse(std::string path, std::vector<char> bytes);

  const std::string& path() const { return path_; }
  const std::vector<PlyElement>& elements() const { return elements_; }
  bool has(const std::string& element) const;
  const PlyElement& element(const std::string& name) const;  // InputError when absent
  double value(const PlyElement& e, size_t row, int property) const;
  uint32_t valueU32(const PlyElement& e, size_t row, int property) const;  // exact for uint32

 private:
  std::string path_;
  std::vector<char> bytes_;
  std::vector<PlyElement> elements_;
  bool ascii_ = false;
  void convertAscii(size_t dataStart);
};

}  // namespace inim
