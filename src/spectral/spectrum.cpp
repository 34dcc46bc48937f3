#include "spectral/spectrum.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/input_file.h"
#include "core/error.h"
#include "core/format.h"

namespace inim {

// ---------------------------------------------------------------- piecewise linear

PiecewiseLinearSpectrum::PiecewiseLinearSpectrum(std::vector<float> lambdas,
                                                 std::vector<float> values, std::string source)
    : lambdas_(std::move(lambdas)), values_(std::move(values)), source_(std::move(source)) {
  if (lambdas_.size() != values_.size() || lambdas_.empty())
    throw InputError(source_, "", std::to_string(lambdas_.size()) + " wavelengths and " +
                                      std::to_string(values_.size()) + " values",
                     "equally many wavelengths and values, at least one");
  for (size_t i = 1; i < lambdas_.size(); ++i)
    if (!(lambdas_[i] > lambdas_[i - 1]))
      throw InputError(source_, "wavelength_nm", std::to_string(lambdas_[i]),
                       "strictly increasing wavelengths");
}

float PiecewiseLinearSpectrum::operator()(float l) const {
  if (!(l >= lambdas_.front()) || !(l <= lambdas_.back())) return 0.0f;
  // First index with lambda > l; the segment is [i-1, i].
  auto it = std::upper_bound(lambdas_.begin(), lambdas_.end(), l);
  if (it == lambdas_.end()) return values_.back();
  size_t i = size_t(it - lambdas_.begin());
  if (i == 0) return values_.front();
  float t = (l - lambdas_[i - 1]) / (lambdas_[i] - lambdas_[i - 1]);
  return values_[i - 1] + t * (values_[i] - values_[i - 1]);
}

float PiecewiseLinearSpectrum::maxValue() const {
  return *std::max_element(values_.begin(), values_.end());
}

void PiecewiseLinearSpectrum::scale(float s) {
  for (float& v : values_) v *= s;
}

// ---------------------------------------------------------------- blackbody

double BlackbodySpectrum::planck(double lambdaNm, double T) {
  if (T <= 0.0) return 0.0;
  constexpr double c = 299792458.0;     // m/s
  constexpr double h = 6.62607015e-34;  // J s
  constexpr double kb = 1.380649e-23;   // J/K
  double l = lambdaNm * 1e-9;           // m
  return (2.0 * h * c * c) / (std::pow(l, 5) * std::expm1((h * c) / (l * kb * T)));
}

BlackbodySpectrum::BlackbodySpectrum(float temperatureK) : T_(temperatureK) {
  if (!(temperatureK > 0.0f))
    throw InputError("", "temperature_K", std::to_string(temperatureK), "a temperature > 0 K");
  double lambdaMaxNm = 2.897771955e6 / double(T_);  // Wien's displacement law
  normalization_ = float(1.0 / planck(lambdaMaxNm, T_));
}

float BlackbodySpectrum::operator()(float l) const {
  return float(planck(l, T_)) * normalization_;
}

// ---------------------------------------------------------------- gaussian

GaussianSpectrum::GaussianSpectrum(float meanNm, float fwhmNm, float scale)
    : mean_(meanNm), sigma_(fwhmNm / (2.0f * std::sqrt(2.0f * std::log(2.0f)))), scale_(scale) {
  if (!(fwhmNm > 0.0f)) throw InputError("", "fwhm_nm", std::to_string(fwhmNm), "a width > 0 nm");
}

float GaussianSpectrum::operator()(float l) const {
  float d = (l - mean_) / sigma_;
  return scale_ * std::exp(-0.5f * d * d);
}

// ---------------------------------------------------------------- CSV

namespace {

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) out.push_back(trim(cell));
  if (!line.empty() && line.back() == ',') out.push_back("");
  return out;
}

struct CsvTable {
  std::string comments;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::vector<int> lineNumbers;
};

CsvTable readCsv(const std::string& path) {
  checkInputFile(path);
  std::ifstream in(path);
  if (!in) throw InputError(path, "", "", "a readable CSV file (cannot open it)");
  CsvTable t;
  std::string line;
  int lineNo = 0;
  while (std::getline(in, line)) {
    ++lineNo;
    std::string s = trim(line);
    if (s.empty()) continue;
    if (s[0] == '#') {
      std::string c = trim(s.substr(1));
      if (!t.comments.empty()) t.comments += "\n";
      t.comments += c;
      continue;
    }
    if (t.header.empty()) {
      t.header = splitCsv(s);
      continue;
    }
    t.rows.push_back(splitCsv(s));
    t.lineNumbers.push_back(lineNo);
  }
  if (t.header.size() < 2)
    throw InputError(path, "(header)", t.header.empty() ? "(none)" : t.header[0],
                     "a header line naming wavelength_nm and at least one value column");
  return t;
}

float parseNumber(const std::string& path, int line, const std::string& column,
                  const std::string& text) {
  try {
    size_t pos = 0;
    float v = std::stof(text, &pos);
    if (pos == text.size() && std::isfinite(v)) return v;
  } catch (const std::exception&) {
  }
  throw InputError(path, "line " + std::to_string(line) + ", column " + column,
                   "'" + text + "'", "a finite number");
}

}  // namespace

std::vector<std::string> csvColumns(const std::string& path) {
  CsvTable t = readCsv(path);
  return {t.header.begin() + 1, t.header.end()};
}

std::shared_ptr<PiecewiseLinearSpectrum> loadSpectrumCSV(const std::string& path,
                                                         const std::string& column) {
  CsvTable t = readCsv(path);
  size_t col = 0;
  for (size_t i = 1; i < t.header.size(); ++i)
    if (t.header[i] == column) col = i;
  if (col == 0) {
    std::string known;
    for (size_t i = 1; i < t.header.size(); ++i) known += (i > 1 ? ", " : "") + t.header[i];
    throw InputError(path, "column", column, "one of the file's columns: " + known);
  }
  std::vector<float> ls, vs;
  for (size_t r = 0; r < t.rows.size(); ++r) {
    const auto& row = t.rows[r];
    if (row.size() != t.header.size())
      throw InputError(path, "line " + std::to_string(t.lineNumbers[r]),
                       std::to_string(row.size()) + " cells",
                       std::to_string(t.header.size()) + " cells as in the header");
    ls.push_back(parseNumber(path, t.lineNumbers[r], t.header[0], row[0]));
    vs.push_back(parseNumber(path, t.lineNumbers[r], column, row[col]));
  }
  if (ls.empty()) throw InputError(path, column, "(no rows)", "at least one data row");
  for (size_t i = 1; i < ls.size(); ++i)
    if (!(ls[i] > ls[i - 1]))
      throw InputError(path, "line " + std::to_string(t.lineNumbers[i]) + ", column " + t.header[0],
                       std::to_string(ls[i]), "strictly increasing wavelengths");
  return std::make_shared<PiecewiseLinearSpectrum>(std::move(ls), std::move(vs), t.comments);
}

double integrate(const Spectrum& s, float lmin, float lmax) {
  if (!(lmax > lmin)) return 0.0;
  int n = std::max(1, int(std::ceil(double(lmax) - double(lmin) - 1e-9)));
  double h = (double(lmax) - double(lmin)) / n;
  double sum = 0.5 * (double(s(lmin)) + double(s(lmax)));
  for (int i = 1; i < n; ++i) sum += s(float(lmin + i * h));
  return sum * h;
}

}  // namespace inim
