#pragma once
// The Zemax ray text format of the paper's ZPL macro (docs/design.md §3.1): one line per ray,
// "x, y, z, l, m, n" (mm and direction cosines, +z toward the viewer), "%.8f", ", " between
// values, in ray order (rays/ray_set.h). The macro's own files are UTF-16LE with a BOM, CRLF
// line ends and two header lines; the reader takes those and UTF-8 (with or without BOM, LF or
// CRLF). The writer writes UTF-8 and LF by default.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "rays/pinhole_rays.h"
#include "rays/ray_set.h"

namespace inim {

class ProgressBar;

struct ZemaxTextOptions {
  bool utf16 = false;               // UTF-16LE with a BOM, as the macro writes
  bool crlf = false;                // CRLF line ends
  std::vector<std::string> header;  // lines written before the rays (ASCII)
};

// The macro's two header lines, for writing files that look like its output.
std::vector<std::string> zemaxMacroHeader(int64_t count);

// Writes `count` rays produced by `ray(i, xyzlmn)`, formatting in parallel and writing in
// order. Throws InputError naming the path when it cannot be written.
void writeZemaxRayText(const std::string& path, int64_t count,
                       const std::function<void(int64_t, double*)>& ray,
                       const ZemaxTextOptions& options = {}, ProgressBar* progress = nullptr);
// Float rays (values printed from their float values).
void writeZemaxRayText(const std::string& path, const RaySet& rays, const ZemaxTextOptions& options = {},
                       ProgressBar* progress = nullptr);
// All pinhole rays of a layout, computed in double precision as they are written.
void writeZemaxRayText(const std::string& path, const EiLayout& L, const ZemaxTextOptions& options = {},
                       ProgressBar* progress = nullptr);
// The macro's single-EI file: the eiRayCount(k, l) rays of EI (k, l) (eiW * eiH for square
// lattices), with positions relative to
// the EI's pinhole (so the origins are 0, as the macro wrote them for a lenslet on axis).
void writeZemaxEiRayText(const std::string& path, const EiLayout& L, int k, int l,
                         const ZemaxTextOptions& options = {});

// Reads a ray text file. Leading lines that are not six numbers are taken as header lines
// (returned in `header` when given); after the first ray, a bad line is an InputError naming
// the file and line. Directions must be unit length within 1e-4.
RaySet readZemaxRayText(const std::string& path, std::vector<std::string>* header = nullptr);

// Formats one line (without line end) exactly as "%.8f, %.8f, %.8f, %.8f, %.8f, %.8f".
std::string formatZemaxRayLine(const double v[6]);

}  // namespace inim
