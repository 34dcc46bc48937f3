#pragma once
// The test toolbox shared by the stages' tests: small displays built in code (square or hex
// lattice on a panel just larger than the EIA, or the paper prototype with fewer EIs), a small
// display file for command-line tests, scratch folders and files, and the InputError check.
//
//   Display d = fixtures::squareDisplay({.cols = 7, .rows = 5, .eiPx = 9});
//   Display h = fixtures::hexDisplay({.layout = EiLayoutKind::ToedIn, .lensPitchMm = 0.92});
//   Display p = fixtures::paperDisplay({.cols = 5, .rows = 3, .gapMm = 3.3});
//   std::string file = fixtures::scratchFile("display.json", fixtures::smallDisplayJson({11, 9, 9}));
//   InputError e = expectInputError([&] { loadDisplay(file); });
#include <gtest/gtest.h>
#include <fcntl.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <string>

#include "core/error.h"
#include "display/display.h"
#include "display/ei_layout.h"

namespace fixtures {

using namespace inim;

// ---------------------------------------------------------------------------------------
// Scratch folders and files

// A scratch folder for one test program, removed when the program ends.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& tag)
      : dir_(std::filesystem::temp_directory_path() / ("inim_" + tag + "_" + std::to_string(getpid()))) {}
  ~ScratchDir() {
    recordDigests();
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const std::filesystem::path& dir() const { return dir_; }
  // With INIM_TEST_DIGESTS=FILE set, one line per file left in the folder is appended to FILE
  // before the folder goes: "<tag>/<path> <FNV-1a 64 of its bytes>", so that two runs of the
  // suite can be compared output by output (scripts/test-output-digests.sh).
  void recordDigests() const {
    const char* file = std::getenv("INIM_TEST_DIGESTS");
    std::error_code ec;
    if (!file || !*file || !std::filesystem::is_directory(dir_, ec)) return;
    std::string tag = dir_.filename().string();
    tag = tag.substr(0, tag.rfind('_'));  // without the process id
    std::string lines;
    for (auto it = std::filesystem::recursive_directory_iterator(dir_, ec); !ec && it != decltype(it)(); it.increment(ec)) {
      const auto type = it->symlink_status(ec).type();
      if (ec || type != std::filesystem::file_type::regular) {  // links (a test's loops) are not outputs
        ec.clear();
        continue;
      }
      std::ifstream in(it->path(), std::ios::binary);
      uint64_t h = 1469598103934665603ull;
      for (std::istreambuf_iterator<char> c(in), end; c != end; ++c) h = (h ^ uint8_t(*c)) * 1099511628211ull;
      char hex[17];
      std::snprintf(hex, sizeof hex, "%016llx", (unsigned long long)h);
      lines += tag + "/" + std::filesystem::relative(it->path(), dir_).string() + " " + hex + "\n";
    }
    const int fd = open(file, O_WRONLY | O_CREAT | O_APPEND, 0644);  // one write: runs in parallel do not interleave
    if (fd >= 0) (void)!write(fd, lines.data(), lines.size()), close(fd);
  }
  // `name` inside the folder, which is created on first use.
  std::string path(const std::string& name) const {
    std::filesystem::create_directories(dir_);
    return (dir_ / name).string();
  }

 private:
  std::filesystem::path dir_;
};

// `name` in this process's scratch folder (inim_test_<pid>, removed when the program ends).
inline std::string scratchPath(const std::string& name) {
  static const ScratchDir dir("test");
  return dir.path(name);
}

// The bytes of a file ("" when it cannot be read).
inline std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// Writes `bytes` to `path` as they are, replacing the file.
inline void writeBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

// Writes `bytes` to `name` in the scratch folder and returns the file's path.
inline std::string scratchFile(const std::string& name, const std::string& bytes) {
  const std::string path = scratchPath(name);
  writeBytes(path, bytes);
  return path;
}

// ---------------------------------------------------------------------------------------
// The InputError expectation

// Runs f and returns the InputError it throws; a test failure if it throws none.
template <class F>
InputError expectInputError(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError thrown";
  return InputError("", "", "", "");
}

// ---------------------------------------------------------------------------------------
// Small displays built in code

// A small display on the default display's panel primaries and MLA material: cols x rows EIs
// (one per lenslet) of eiPx pixels of pixelMm. Designated initializers name what differs:
// squareDisplay({.cols = 3, .rows = 3, .eiPx = 5}).
struct SmallDisplay {
  int cols = 9, rows = 7;  // EIs: K columns, R rows
  int eiPx = 9;            // EI size in pixels (hex: flat-to-flat width along a row)
  double pixelMm = 0.1;    // panel pixel pitch
  double gapMm = 3.0;      // generation and reconstruction gap
  EiLayoutKind layout = EiLayoutKind::Parallel;
  double lensPitchMm = 0.0;  // <= 0: the EI pitch, eiPx * pixelMm
  double viewingDistanceMm = 300.0;
  // Panel margin around the EIA, which also leaves room for toed-in EIs: 3 px (square) or
  // 4 px (hex) when not given.
  std::optional<int> borderPx = std::nullopt;
};

namespace detail {
// The EI grid, lens pitch and viewing distance, as every builder below sets them.
inline void setEiGrid(Display& d, int cols, int rows, int eiPx, EiLayoutKind layout, double lensPitchMm,
                      double viewingDistanceMm) {
  d.mla.pitchMm = lensPitchMm;
  d.eiWidthPx = d.eiHeightPx = eiPx;
  d.eiCols = cols;
  d.eiRows = rows;
  d.layout = layout;
  d.viewingDistanceMm = viewingDistanceMm;
}

inline Display smallDisplayOnDefaultPanel(const SmallDisplay& s, const std::string& file) {
  Display d = loadDisplay(defaultDisplayPath());
  d.file = file;
  d.panel.pixelPitchMm = s.pixelMm;
  d.generationGapMm = d.reconstructionGapMm = s.gapMm;
  setEiGrid(d, s.cols, s.rows, s.eiPx, s.layout, s.lensPitchMm > 0.0 ? s.lensPitchMm : s.eiPx * s.pixelMm,
            s.viewingDistanceMm);
  return d;
}
}  // namespace detail

// Square lattice; the panel holds cols x rows EIs of eiPx + 2 pixels plus the border.
inline Display squareDisplay(const SmallDisplay& s = {}) {
  Display d = detail::smallDisplayOnDefaultPanel(s, "small-test-display");
  const int border = s.borderPx.value_or(3);
  d.panel.widthPx = s.cols * (s.eiPx + 2) + 2 * border;
  d.panel.heightPx = s.rows * (s.eiPx + 2) + 2 * border;
  return d;
}

// Hex lattice of hex lenslets whose apertures span the pitch; the panel holds the staggered
// rows (cols + 1.5 EIs of eiPx + 2 pixels each way) plus the border.
inline Display hexDisplay(const SmallDisplay& s = {}) {
  Display d = detail::smallDisplayOnDefaultPanel(s, "small-hex-test-display");
  const int border = s.borderPx.value_or(4);
  d.panel.widthPx = int(std::ceil((s.cols + 1.5) * (s.eiPx + 2))) + 2 * border;
  d.panel.heightPx = int(std::ceil((s.rows + 1.5) * (s.eiPx + 2))) + 2 * border;
  d.mla.lattice = Mla::Lattice::Hex;
  d.mla.aperture = Mla::Aperture::Hex;
  d.mla.apertureMm = d.mla.pitchMm;
  return d;
}

// The paper prototype (its 3840 x 1644 panel of 0.0395 mm pixels and its MLA) with another EI
// count, EI size, gap, lens pitch or viewing distance. The defaults are the prototype's.
struct PaperVariant {
  int cols = 153, rows = 65;  // EIs
  int eiPx = 25;
  EiLayoutKind layout = EiLayoutKind::Parallel;
  std::optional<double> gapMm = std::nullopt;  // generation and reconstruction gap; default 3.3 and 4.0 mm
  double lensPitchMm = 1.0;
  double viewingDistanceMm = 350.0;
};

inline Display paperDisplay(const PaperVariant& v = {}) {
  Display d = loadDisplay(defaultDisplayPath());
  if (v.gapMm) d.generationGapMm = d.reconstructionGapMm = *v.gapMm;
  detail::setEiGrid(d, v.cols, v.rows, v.eiPx, v.layout, v.lensPitchMm, v.viewingDistanceMm);
  return d;
}

// ---------------------------------------------------------------------------------------
// A small display file (for command-line tests)

// cols x rows EIs of eiPx pixels of 0.1 mm, Gaussian primaries at 625/530/460 nm, an MLA of
// f = 3 mm PMMA lenslets, generation gap gapMm and reconstruction gap 3.5 mm. The panel is the
// EIA plus a 3 px border unless its size is given.
struct SmallDisplayFile {
  int cols = 11, rows = 9, eiPx = 9;
  double gapMm = 3.0;
  double lensPitchMm = 0.9;
  int panelWidthPx = 0, panelHeightPx = 0;  // 0: the EIA plus 6 px
};

inline std::string smallDisplayJson(const SmallDisplayFile& f = {}) {
  const int panelW = f.panelWidthPx ? f.panelWidthPx : f.cols * f.eiPx + 6;
  const int panelH = f.panelHeightPx ? f.panelHeightPx : f.rows * f.eiPx + 6;
  std::ostringstream s;
  s << R"({"name": "small test display",
  "panel": {"name": "test panel", "resolution_px": [)"
    << panelW << ", " << panelH << R"(], "pixel_pitch_mm": 0.1,
            "primaries": {"R": {"gaussian": {"mean_nm": 625, "fwhm_nm": 35}},
                          "G": {"gaussian": {"mean_nm": 530, "fwhm_nm": 35}},
                          "B": {"gaussian": {"mean_nm": 460, "fwhm_nm": 30}}},
            "peak_luminance_cd_m2": 500},
  "mla": {"name": "test mla", "pitch_mm": )"
    << f.lensPitchMm << R"(, "focal_length_mm": 3.0, "substrate_thickness_mm": 1.0, "material": "PMMA"},
  "generation_gap_mm": )"
    << f.gapMm << R"(, "reconstruction_gap_mm": 3.5, "ei_px": )" << f.eiPx << R"(, "ei_count": [)" << f.cols
    << ", " << f.rows << "]}";
  return s.str();
}

// ---------------------------------------------------------------------------------------
// The paper display reduced to K x R EIs of n x n pixels of `pixelMm`, lens pitch P, focal
// length f, gap g, the panel `border` px larger than the EIA on each side (MLA and view tests).

struct LensletTestDisplay {
  int cols, rows, eiPx;
  double pixelMm, lensPitchMm, focalLengthMm, gapMm;
  int border = 4;
};

inline Display lensletTestDisplay(const LensletTestDisplay& v) {
  Display d = loadDisplay(defaultDisplayPath());
  d.file = "small-test-display";
  d.panel.pixelPitchMm = v.pixelMm;
  d.panel.widthPx = v.cols * v.eiPx + 2 * v.border;
  d.panel.heightPx = v.rows * v.eiPx + 2 * v.border;
  d.mla.pitchMm = v.lensPitchMm;
  d.mla.apertureMm = v.lensPitchMm;
  d.mla.focalLengthMm = v.focalLengthMm;
  d.mla.radiusMm.reset();
  d.generationGapMm = d.reconstructionGapMm = v.gapMm;
  d.eiWidthPx = d.eiHeightPx = v.eiPx;
  d.eiCols = v.cols;
  d.eiRows = v.rows;
  d.layout = EiLayoutKind::Parallel;
  return d;
}

}  // namespace fixtures
