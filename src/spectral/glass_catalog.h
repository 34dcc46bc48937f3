#pragma once
// Glass catalogues in Zemax's .agf format, as glass makers publish them (SCHOTT, OHARA, CDGM,
// HOYA): each glass's dispersion formula and coefficients, n_d, V_d and the wavelength range its
// data cover. Read as the files come: UTF-8 or UTF-16 (with its byte-order mark), CRLF or LF.
//
//   NM <name> <formula> <MIL#> <n_d> <V_d> [<exclude> <status> <melt>]   a glass
//   CD <c0> <c1> ...                                                    its formula's coefficients
//   LD <min um> <max um>                                                the range of the data
//   CC, GC, ED, TD, OD, IT, BD, MD                                      comments and data not used here
//
// The formulas (wavelength l in um; Zemax's codes):
//   1 Schott        n^2 = a0 + a1 l^2 + a2 l^-2 + a3 l^-4 + a4 l^-6 + a5 l^-8
//   2 Sellmeier 1   n^2 - 1 = sum_{i=1..3} K_i l^2 / (l^2 - L_i)        (CD: K1 L1 K2 L2 K3 L3)
//   3 Herzberger    n = A + B L + C L^2 + D l^2 + E l^4 + F l^6, L = 1 / (l^2 - 0.028)
//   4 Sellmeier 2   n^2 - 1 = A + B1 l^2 / (l^2 - l1^2) + B2 / (l^2 - l2^2)   (CD: A B1 l1 B2 l2)
//   5 Conrady       n = n0 + A / l + B / l^3.5
//   6 Sellmeier 3   as 2 with four terms
//   7 Handbook 1    n^2 = A + B / (l^2 - C) - D l^2
//   8 Handbook 2    n^2 = A + B l^2 / (l^2 - C) - D l^2
//   9 Sellmeier 4   n^2 = A + B l^2 / (l^2 - C) + D l^2 / (l^2 - E)
//  10 Extended      n^2 = a0 + a1 l^2 + a2 l^-2 + a3 l^-4 + a4 l^-6 + a5 l^-8 + a6 l^-10 + a7 l^-12
//  11 Sellmeier 5   as 2 with five terms
//  12 Extended 2    n^2 = a0 + a1 l^2 + a2 l^-2 + a3 l^-4 + a4 l^-6 + a5 l^-8 + a6 l^4 + a7 l^6
//  13 Extended 3    n^2 = a0 + a1 l^2 + a2 l^4 + a3 l^-2 + a4 l^-4 + a5 l^-6 + a6 l^-8 + a7 l^-10 + a8 l^-12
// Any other code is refused (InputError naming the file, the line and the glass).
#include <string>
#include <vector>

#include "spectral/dispersion.h"

namespace inim {

struct CatalogGlass {
  std::string name;
  int formula = 0;
  std::vector<double> coefficients;  // as many as the formula takes (missing ones 0)
  double nd = 0.0, vd = 0.0;         // as the catalogue states them
  double minUm = 0.0, maxUm = 0.0;   // the range of the data (0, 0: not given)
  int line = 0;                      // of its NM line

  // The index at `lambdaUm` by the glass's formula (NaN where the formula has no real root).
  double index(double lambdaUm) const;
  bool covers(double lambdaUm) const { return maxUm <= minUm || (lambdaUm >= minUm && lambdaUm <= maxUm); }
};

// The formula's name ("Sellmeier 1"), or "" for a code inim does not know.
std::string dispersionFormulaName(int code);

struct GlassCatalog {
  std::string name;  // the file's stem, upper case ("SCHOTT")
  std::string file;
  std::vector<CatalogGlass> glasses;
  // The glass of that name (case-insensitive), or null.
  const CatalogGlass* find(const std::string& glass) const;
};

// Parses the bytes of an .agf file; `file` names it in messages. InputError naming the file, the
// line and the value for: an unknown line key, a number that does not read, an NM line without
// its fields, a formula code not listed above, CD before any NM, a glass without CD, a range
// with min >= max, text that is neither UTF-8 nor UTF-16.
GlassCatalog parseAgf(const std::string& bytes, const std::string& file);
GlassCatalog loadAgf(const std::string& path);

// n(lambda) of a catalogue glass, for the renderers (IndexOfRefraction takes nm).
class CatalogGlassIor final : public IndexOfRefraction {
 public:
  explicit CatalogGlassIor(CatalogGlass glass) : glass_(std::move(glass)) {}
  float n(float lambdaNm) const override { return float(glass_.index(double(lambdaNm) * 1e-3)); }
  const CatalogGlass& glass() const { return glass_; }

 private:
  CatalogGlass glass_;
};

}  // namespace inim
