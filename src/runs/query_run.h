#pragma once
// `inim query` as a library: a field's colour along every ray of a ray table (`inim rays
// --for-field`), written as the colour table `inim eia --field-colors` reads. It is what an
// external NeRF does with the table, done by one of inim's own fields, so the exchange can be
// checked end to end.
#include <cstdint>
#include <string>

#include "field_files/field_factory.h"

namespace inim {

struct QueryRunSettings {
  std::string fieldPath;  // scene JSON, .inimrf or splats
  std::string raysPath;   // .npy or .exr ray table
  std::string out;        // .npy (float32 N x 5) or .exr (R G B A Z)
  uint64_t seed = 1;
};

struct QueryRunResult {
  std::string fieldPath;
  FieldKind fieldKind = FieldKind::AnalyticScene;
  size_t rays = 0;
};

// InputError naming `out` for another extension, before any work.
QueryRunResult runQuery(const QueryRunSettings& s);
// "queried FIELD (kind) along N rays of TABLE: OUT in S s".
std::string queryText(const QueryRunSettings& s, const QueryRunResult& r, double seconds);

}  // namespace inim
