#include "runs/query_run.h"

#include "core/format.h"
#include "core/file_kinds.h"
#include "core/output_file.h"
#include "field/ray_table.h"

namespace inim {

QueryRunResult runQuery(const QueryRunSettings& s) {
  requireFileKind(s.out, "out", {FileKind::Npy, FileKind::Exr}, "a .npy or .exr table");
  const LoadedField lf = loadField(s.fieldPath, "field");
  const RayTable table = readRayTable(s.raysPath, 1);
  OutputSet outputs;
  writeColorTable(outputs.add(s.out), answerRayTable(*lf.field, table, s.seed));
  outputs.commit();
  return {lf.path, lf.kind, table.rays.size()};
}

std::string queryText(const QueryRunSettings& s, const QueryRunResult& r, double seconds) {
  return formatText("queried %s (%s) along %zu rays of %s: %s in %.2f s\n", r.fieldPath.c_str(),
                    fieldKindName(r.fieldKind), r.rays, s.raysPath.c_str(), s.out.c_str(), seconds);
}

}  // namespace inim
