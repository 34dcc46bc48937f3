// The Academy/ASC Common LUT Format writer and reader (declared in lut_io.h). The reader parses
// XML with the pugixml that OpenImageIO ships (already linked by inim_core).
#include <OpenImageIO/detail/pugixml/pugixml.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "calibration/lut_io.h"
#include "calibration/lut_text.h"
#include "core/error.h"
#include "core/output_file.h"

namespace inim {
namespace {

std::string xmlEscape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string matrixNode(const glm::dmat3& m) {
  std::string text = "    <Matrix id=\"matrix\" inBitDepth=\"32f\" outBitDepth=\"32f\">\n";
  text += "        <Array dim=\"3 3 3\">\n";
  for (int row = 0; row < 3; ++row) text += tripleText(Vec3d(m[0][row], m[1][row], m[2][row])) + "\n";
  return text + "        </Array>\n    </Matrix>\n";
}

std::string lutNode(const Lut3d& lut) {
  const int n = lut.size();
  std::string text = "    <LUT3D id=\"lut\" interpolation=\"tetrahedral\" inBitDepth=\"32f\" outBitDepth=\"32f\">\n";
  text += "        <Array dim=\"" + std::to_string(n) + " " + std::to_string(n) + " " + std::to_string(n) + " 3\">\n";
  for (int r = 0; r < n; ++r)
    for (int g = 0; g < n; ++g)
      for (int b = 0; b < n; ++b) text += tripleText(lut.at(r, g, b)) + "\n";  // blue fastest
  return text + "        </Array>\n    </LUT3D>\n";
}

// Reads one CLF file; remembers the text to turn node offsets into line numbers.
struct ClfReader {
  std::string path, text;

  std::string lineOf(ptrdiff_t offset) const {
    if (offset < 0) return "";
    const size_t end = std::min(text.size(), size_t(offset));
    return ", line " + std::to_string(1 + std::count(text.begin(), text.begin() + ptrdiff_t(end), '\n'));
  }
  std::string where(const pugi::xml_node& node, const std::string& what) const {
    return std::string(node.name()) + (what.empty() ? "" : " " + what) + lineOf(node.offset_debug());
  }

  void requireAttribute(const pugi::xml_node& node, const char* name, const std::string& wanted) const {
    const std::string value = node.attribute(name).as_string("(missing)");
    if (value != wanted) throw InputError(path, where(node, name), value, wanted);
  }

  // The node's one Array child. Any other child but a Description is refused: an IndexMap
  // (CLF 2) would remap the input domain, and a second Array would be ignored.
  pugi::xml_node arrayChild(const pugi::xml_node& owner) const {
    pugi::xml_node found;
    for (const pugi::xml_node& child : owner.children()) {
      if (child.type() != pugi::node_element) continue;
      const std::string name = child.name();
      if (name == "Description") continue;
      if (name != "Array" || found)
        throw InputError(path, where(child, ""), name, "one Array (and Descriptions) inside " + std::string(owner.name()));
      found = child;
    }
    if (!found) throw InputError(path, where(owner, ""), "no Array", "an Array child");
    return found;
  }

  // The numbers in an Array whose dim must equal `dims`.
  std::vector<double> array(const pugi::xml_node& owner, const std::string& dims, size_t count) const {
    const pugi::xml_node node = arrayChild(owner);
    requireAttribute(node, "dim", dims);
    const std::vector<std::string_view> tokens = splitWhitespace(node.child_value());
    if (tokens.size() != count)
      throw InputError(path, where(node, "values"), std::to_string(tokens.size()), std::to_string(count) + " numbers");
    std::vector<double> values(count);
    for (size_t i = 0; i < count; ++i) {
      if (!parseNumber(tokens[i], values[i]))
        throw InputError(path, where(node, "value " + std::to_string(i)), std::string(tokens[i]), "a number");
      if (!std::isfinite(values[i]))
        throw InputError(path, where(node, "value " + std::to_string(i)), std::string(tokens[i]), "a finite number");
    }
    return values;
  }

  glm::dmat3 matrix(const pugi::xml_node& node) const {
    requireAttribute(node, "inBitDepth", "32f");
    requireAttribute(node, "outBitDepth", "32f");
    const std::vector<double> v = array(node, "3 3 3", 9);
    glm::dmat3 m;
    for (int row = 0; row < 3; ++row)
      for (int col = 0; col < 3; ++col) m[col][row] = v[size_t(row) * 3 + col];
    return m;
  }

  Lut3d lut(const pugi::xml_node& node) const {
    requireAttribute(node, "interpolation", "tetrahedral");
    requireAttribute(node, "inBitDepth", "32f");
    requireAttribute(node, "outBitDepth", "32f");
    const pugi::xml_node arrayNode = arrayChild(node);
    const std::vector<std::string_view> dims = splitWhitespace(arrayNode.attribute("dim").as_string());
    double n = 0.0;
    if (dims.size() != 4 || !parseNumber(dims[0], n) || n != std::floor(n) || n < 2 || n > 256)
      throw InputError(path, where(arrayNode, "dim"), arrayNode.attribute("dim").as_string("(missing)"),
                       "\"N N N 3\" with N from 2 to 256");
    const int size = int(n);
    const std::string side = std::to_string(size);
    const std::vector<double> v = array(node, side + " " + side + " " + side + " 3", size_t(size) * size * size * 3);
    Lut3d lut(size);
    size_t i = 0;
    for (int r = 0; r < size; ++r)
      for (int g = 0; g < size; ++g)
        for (int b = 0; b < size; ++b, i += 3) lut.set(r, g, b, Vec3d(v[i], v[i + 1], v[i + 2]));
    return lut;
  }

  ClfProcess process(const pugi::xml_node& root) const {
    if (std::string(root.name()) != "ProcessList")
      throw InputError(path, "root element", root.name(), "ProcessList");
    const std::string version = root.attribute("compCLFversion").as_string("(missing)");
    if (version != "3" && version != "3.0") throw InputError(path, where(root, "compCLFversion"), version, "3");
    std::optional<glm::dmat3> m;
    std::optional<Lut3d> table;
    for (const pugi::xml_node& node : root.children()) {
      if (node.type() != pugi::node_element) continue;
      const std::string name = node.name();
      if (name == "Description" || name == "Info") continue;
      if (name == "Matrix" && !m && !table) m = matrix(node);
      else if (name == "LUT3D" && !table) table = lut(node);
      else throw InputError(path, where(node, ""), name, "an optional Matrix, then one LUT3D");
    }
    if (!table) throw InputError(path, "LUT3D", "missing", "one LUT3D node");
    return {m, *table};
  }
};

}  // namespace

void writeClf(const std::string& path, const ClfProcess& process, const std::string& name) {
  std::string text = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  text += "<ProcessList id=\"inim_calibration\" name=\"" + xmlEscape(name) + "\" compCLFversion=\"3\">\n";
  text += "    <Description>" + xmlEscape(name) + "</Description>\n";
  if (process.matrix) text += matrixNode(*process.matrix);
  text += lutNode(process.lut);
  writeTextFile(path, text + "</ProcessList>\n");
}

ClfProcess readClf(const std::string& path) {
  ClfReader reader{path, readTextFile(path, "CLF file")};
  pugi::xml_document document;
  const pugi::xml_parse_result parsed = document.load_buffer(reader.text.data(), reader.text.size());
  if (!parsed)
    throw InputError(path, "XML" + reader.lineOf(parsed.offset), parsed.description(), "well-formed XML");
  return reader.process(document.document_element());
}

}  // namespace inim
