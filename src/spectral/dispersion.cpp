#include "spectral/dispersion.h"

#include <cmath>

#include <algorithm>
#include <filesystem>

#include "core/error.h"
#include "core/format.h"
#include "core/json_config.h"
#include "core/output_file.h"
#include "spectral/glass_catalog.h"

namespace inim {

SellmeierIor::SellmeierIor(std::vector<double> B, std::vector<double> C)
    : B_(std::move(B)), C_(std::move(C)) {
  if (B_.size() != C_.size() || B_.empty())
    throw InputError("", "B, C", std::to_string(B_.size()) + " and " + std::to_string(C_.size()) + " terms",
                     "equally many Sellmeier B and C terms, at least one");
}

float SellmeierIor::n(float lambdaNm) const {
  double l2 = double(lambdaNm) * 1e-3;
  l2 *= l2;
  double n2 = 1.0;
  for (size_t i = 0; i < B_.size(); ++i) n2 += B_[i] * l2 / (l2 - C_[i]);
  return float(std::sqrt(std::max(n2, 0.0)));
}

float CauchyIor::n(float lambdaNm) const {
  double l2 = double(lambdaNm) * 1e-3;
  l2 *= l2;
  return float(A_ + B_ / l2 + C_ / (l2 * l2));
}

CauchyIor CauchyIor::fromAbbe(double nd, double Vd) {
  if (!(nd > 1.0)) throw InputError("", "nd", std::to_string(nd), "an index n_d > 1");
  if (!(Vd > 0.0)) throw InputError("", "Vd", std::to_string(Vd), "an Abbe number V_d > 0");
  constexpr double ld = 0.58756, lF = 0.48613, lC = 0.65627;  // um (d, F, C lines)
  // n_F - n_C = B (1/lF^2 - 1/lC^2) = (nd - 1) / Vd; n_d = A + B / ld^2.
  double B = (nd - 1.0) / Vd / (1.0 / (lF * lF) - 1.0 / (lC * lC));
  double A = nd - B / (ld * ld);
  return CauchyIor(A, B, 0.0);
}

TabulatedIor::TabulatedIor(std::shared_ptr<const PiecewiseLinearSpectrum> table)
    : table_(std::move(table)) {
  if (!table_ || table_->lambdas().empty())
    throw InputError("", "table", "(empty)", "a refractive-index table with at least one row");
}

float TabulatedIor::n(float lambdaNm) const {
  const auto& ls = table_->lambdas();
  const auto& vs = table_->values();
  if (lambdaNm <= ls.front()) return vs.front();
  if (lambdaNm >= ls.back()) return vs.back();
  return (*table_)(lambdaNm);
}

// ---------------------------------------------------------------- catalog

const MaterialCatalog& MaterialCatalog::standard() {
  static const MaterialCatalog c(dataPath("spectra/materials.json"));
  return c;
}

MaterialCatalog::MaterialCatalog(const std::string& jsonPath) : path_(jsonPath) {
  Json j = readJsonFile(path_);
  JsonObject top(j, path_, "");
  for (const auto& [key, value] : top.json().items())
    if (!key.empty() && key[0] == '_') top.raw(key);  // comments
  JsonObject mats = top.object("materials");
  top.rejectUnknown();
  for (const auto& [name, value] : mats.json().items()) {
    if (!name.empty() && name[0] == '_') {
      mats.raw(name);  // comment
      continue;
    }
    JsonObject m = mats.object(name);
    std::string type =
        m.choice("type", {"sellmeier", "cauchy", "abbe", "table", "constant", "conductor"});
    if (m.has("_source")) m.string("_source");
    if (type == "sellmeier") {
      auto B = m.numbers("B"), C = m.numbers("C");
      if (B.size() != C.size() || B.empty())
        m.fail("C", std::to_string(C.size()) + " terms", std::to_string(B.size()) + " terms as in B");
      dielectrics_[name] = std::make_shared<SellmeierIor>(B, C);
    } else if (type == "cauchy") {
      double A = m.number("A"), B = m.number("B"), C = m.number("C", 0.0);
      dielectrics_[name] = std::make_shared<CauchyIor>(A, B, C);
    } else if (type == "abbe") {
      double nd = m.number("nd"), Vd = m.positive("Vd");
      if (!(nd > 1.0)) m.fail("nd", std::to_string(nd), "an index n_d > 1");
      dielectrics_[name] = std::make_shared<CauchyIor>(CauchyIor::fromAbbe(nd, Vd));
    } else if (type == "table") {
      std::string file = m.path("file");
      std::string column = m.string("column", "n");
      dielectrics_[name] = std::make_shared<TabulatedIor>(loadSpectrumCSV(file, column));
    } else if (type == "constant") {
      dielectrics_[name] = std::make_shared<ConstantIor>(float(m.positive("n")));
    } else {  // conductor
      std::string file = m.path("file");
      conductors_[name] = ConductorIndex{loadSpectrumCSV(file, m.string("eta_column", "n")),
                                         loadSpectrumCSV(file, m.string("k_column", "k"))};
    }
    m.rejectUnknown();
  }
  mats.rejectUnknown();
}

namespace {
std::string joinNames(const std::vector<std::string>& names) {
  std::string s;
  for (size_t i = 0; i < names.size(); ++i) s += (i ? ", " : "") + names[i];
  return s;
}
}  // namespace

const std::vector<GlassCatalog>& MaterialCatalog::glassCatalogues() const {
  std::call_once(glassOnce_, [this] {
    auto cats = std::make_shared<std::vector<GlassCatalog>>();
    std::vector<std::string> files;
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(path_).parent_path() / "glass", ec))
      if (lowerExtension(e.path().string()) == ".agf") files.push_back(e.path().string());
    std::sort(files.begin(), files.end());
    for (const std::string& f : files) cats->push_back(loadAgf(f));
    glasses_ = std::move(cats);
  });
  return *glasses_;
}

IorPtr MaterialCatalog::catalogueGlass(const std::string& name) const {
  const size_t colon = name.find(':');
  const std::string catalogue = colon == std::string::npos ? "" : name.substr(0, colon);
  const std::string glass = colon == std::string::npos ? name : name.substr(colon + 1);
  const CatalogGlass* found = nullptr;
  std::string where;
  for (const GlassCatalog& c : glassCatalogues()) {
    if (!catalogue.empty() && c.name != catalogue) continue;
    const CatalogGlass* g = c.find(glass);
    if (!g) continue;
    // A bare name two makers use for different glasses (F2: CDGM n_d 1.61293, SCHOTT 1.62004)
    // is ambiguous; guessing one would change a lens silently.
    if (found && std::abs(found->nd - g->nd) > 1e-6)
      throw InputError(path_, "material", name,
                       "a glass name of one catalogue: " + where + " and " + c.name + ":" + g->name + " (n_d " +
                           formatNumber(g->nd) + ") differ; write CATALOGUE:NAME");
    if (!found) found = g, where = c.name + ":" + g->name + " (n_d " + formatNumber(g->nd) + ")";
  }
  return found ? std::make_shared<CatalogGlassIor>(*found) : nullptr;
}

bool MaterialCatalog::hasDielectric(const std::string& name) const {
  return dielectrics_.count(name) > 0 || catalogueGlass(name) != nullptr;
}

std::string MaterialCatalog::dielectricsText() const {
  std::string s = joinNames(dielectricNames());
  std::string cats;
  for (const GlassCatalog& c : glassCatalogues())
    cats += (cats.empty() ? "" : ", ") + c.name + " (" + std::to_string(c.glasses.size()) + " glasses)";
  return cats.empty() ? s : s + ", or a glass of the catalogues " + cats + " as NAME or CATALOGUE:NAME";
}

IorPtr MaterialCatalog::dielectric(const std::string& name) const {
  auto it = dielectrics_.find(name);
  if (it != dielectrics_.end()) return it->second;
  if (IorPtr g = catalogueGlass(name)) return g;
  throw InputError(path_, "material", name, "a dielectric of the catalog: " + dielectricsText());
}

const ConductorIndex& MaterialCatalog::conductor(const std::string& name) const {
  auto it = conductors_.find(name);
  if (it == conductors_.end())
    throw InputError(path_, "material", name,
                     "a conductor of the catalog: " + joinNames(conductorNames()));
  return it->second;
}

std::vector<std::string> MaterialCatalog::dielectricNames() const {
  std::vector<std::string> v;
  for (const auto& kv : dielectrics_) v.push_back(kv.first);
  return v;
}

std::vector<std::string> MaterialCatalog::conductorNames() const {
  std::vector<std::string> v;
  for (const auto& kv : conductors_) v.push_back(kv.first);
  return v;
}

}  // namespace inim
