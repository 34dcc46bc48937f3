#pragma once
// Refractive index as a function of wavelength (nm), and the material catalog
// (spectra/materials.json): dielectrics with n(lambda), conductors with n and k. A dielectric
// not named there is looked up in the glass catalogues of the glass/ folder beside it
// (spectra/glass/*.agf: SCHOTT, OHARA; spectral/glass_catalog.h), as "NAME" (the first
// catalogue, alphabetically, that has it) or "CATALOGUE:NAME" ("OHARA:S-LAH66").
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "spectral/spectrum.h"

namespace inim {

class IndexOfRefraction {
 public:
  virtual ~IndexOfRefraction() = default;
  virtual float n(float lambdaNm) const = 0;
  // Constant indices keep all 4 wavelengths of a sample; dispersive ones terminate secondary.
  virtual bool isDispersive() const { return true; }
};
using IorPtr = std::shared_ptr<const IndexOfRefraction>;

class ConstantIor final : public IndexOfRefraction {
 public:
  explicit ConstantIor(float n) : n_(n) {}
  float n(float) const override { return n_; }
  bool isDispersive() const override { return false; }

 private:
  float n_;
};

// n^2 = 1 + sum B_i l^2 / (l^2 - C_i), l in um (Schott form).
class SellmeierIor final : public IndexOfRefraction {
 public:
  SellmeierIor(std::vector<double> B, std::vector<double> C);
  float n(float lambdaNm) const override;

 private:
  std::vector<double> B_, C_;
};

// n = A + B / l^2 + C / l^4, l in um.
class CauchyIor final : public IndexOfRefraction {
 public:
  CauchyIor(double A, double B, double C = 0.0) : A_(A), B_(B), C_(C) {}
  float n(float lambdaNm) const override;
  // Two-term Cauchy through n_d (587.56 nm) with Abbe number V_d = (n_d-1)/(n_F-n_C).
  static CauchyIor fromAbbe(double nd, double Vd);

 private:
  double A_, B_, C_;
};

// Tabulated n(lambda), linear interpolation, clamped at the ends.
class TabulatedIor final : public IndexOfRefraction {
 public:
  explicit TabulatedIor(std::shared_ptr<const PiecewiseLinearSpectrum> table);
  float n(float lambdaNm) const override;

 private:
  std::shared_ptr<const PiecewiseLinearSpectrum> table_;
};

struct ConductorIndex {
  SpectrumPtr eta, k;
};

struct GlassCatalog;

class MaterialCatalog {
 public:
  // The shipped catalog, spectra/materials.json.
  static const MaterialCatalog& standard();
  explicit MaterialCatalog(const std::string& jsonPath);
  bool hasDielectric(const std::string& name) const;
  bool hasConductor(const std::string& name) const { return conductors_.count(name) > 0; }
  // Throw InputError naming the material and listing known names when absent.
  IorPtr dielectric(const std::string& name) const;
  const ConductorIndex& conductor(const std::string& name) const;
  std::vector<std::string> dielectricNames() const;  // those of materials.json
  std::vector<std::string> conductorNames() const;
  // What a dielectric's name may be, for messages: materials.json's names and the catalogues.
  std::string dielectricsText() const;
  // The glass catalogues (loaded on first use; empty when the folder has none).
  const std::vector<GlassCatalog>& glassCatalogues() const;

 private:
  // A catalogue glass by "NAME" or "CATALOGUE:NAME", or null.
  IorPtr catalogueGlass(const std::string& name) const;
  std::string path_;
  std::map<std::string, IorPtr> dielectrics_;
  std::map<std::string, ConductorIndex> conductors_;
  mutable std::once_flag glassOnce_;
  mutable std::shared_ptr<const std::vector<GlassCatalog>> glasses_;
};

}  // namespace inim
