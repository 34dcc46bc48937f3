// inim query: a field's colour along every ray of a ray table (`inim rays --for-field`), written
// as the colour table `inim eia --field-colors` reads. It is what an external NeRF does with the
// table, done by one of inim's own fields, so the exchange can be checked end to end.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "cli/scene_options.h"
#include "core/error.h"
#include "core/image.h"
#include "core/npy.h"
#include "core/output_file.h"
#include "core/parallel.h"
#include "core/rng.h"
#include "field/ray_table.h"
#include "spectral/cie.h"
#include "spectral/color.h"

namespace inim::cli {

void addQueryCommand(CLI::App& app) {
  struct Opts {
    std::string field, rays, out;
    RunOptions run;
  };
  auto o = std::make_shared<Opts>();
  auto* cmd = app.add_subcommand(
      "query", "Query a field along the rays of a table written by `inim rays --for-field`; writes linear Rec.709 "
               "R G B A depth per ray (.npy or .exr) for `inim eia --field-colors FILE --field-colors-encoding linear`");
  cmd->add_option("--field", o->field, "Scene JSON or trained radiance field (.inimrf)")->required();
  cmd->add_option("--rays", o->rays, "Ray table (.npy or .exr) from `inim rays --for-field`")->required();
  cmd->add_option("--out", o->out, "Colour table (.npy: float32 N x 5, or .exr: R G B A Z)")->required();
  addRunOptions(cmd, o->run);
  cmd->callback([o] {
    ThreadLimit threads(o->run.threads);
    const auto t0 = std::chrono::steady_clock::now();
    std::string ext = std::filesystem::path(o->out).extension().string();
    if (ext != ".npy" && ext != ".exr") throw InputError("", "--out", "\"" + o->out + "\"", "a .npy or .exr table");
    LoadedField lf = loadField(o->field, "--field");
    const RayTable t = readRayTable(o->rays, 1);
    const size_t n = t.rays.size();
    const bool spectral = lf.field->encoding() == FieldEncoding::Spectral;
    const Mat3 toRgb = ColorSystem::xyzToRec709();
    std::vector<float> rows(n * 5, 0.0f);
    constexpr uint64_t kWavelengthSalt = 0x51EC7A1ull;
    constexpr size_t kBatch = 4096;
    parallelForRange(int64_t(n), [&](int64_t begin, int64_t end) {
      const size_t b0 = size_t(begin), b1 = size_t(end);
      std::vector<FieldRay> rays(t.rays.begin() + std::ptrdiff_t(b0), t.rays.begin() + std::ptrdiff_t(b1));
      std::vector<SampledWavelengths> lambdas;
      if (spectral)
        for (const FieldRay& r : rays) {
          Rng rng = Rng::forSample(o->run.seed ^ kWavelengthSalt, r.id, r.sample);
          lambdas.push_back(SampledWavelengths::sampleVisible(rng.uniform()));
        }
      std::vector<FieldSample> out(rays.size());
      // Rays that never reach the VCP (far < near) are answered with nothing.
      for (auto& r : rays)
        if (!(r.tFar >= r.tNear)) r.tFar = r.tNear;
      lf.field->query(rays, lambdas, out, o->run.seed);
      for (size_t i = 0; i < rays.size(); ++i) {
        const Vec3 rgb = spectral ? toRgb * sampledToXYZ(out[i].L, lambdas[i]) : out[i].rgb;
        float* row = &rows[(b0 + i) * 5];
        row[0] = rgb.x, row[1] = rgb.y, row[2] = rgb.z;
        row[3] = out[i].opacity;
        row[4] = std::isfinite(out[i].depth) ? out[i].depth : std::numeric_limits<float>::infinity();
      }
    }, nullptr, int64_t(kBatch));
    OutputSet outputs;
    const std::string tmp = outputs.add(o->out);
    if (ext == ".npy") {
      NpyArray a;
      a.rows = int64_t(n), a.cols = 5;
      a.data = std::move(rows);
      writeNpy(tmp, a);
    } else {
      const int w = int(std::min<size_t>(std::max<size_t>(n, 1), 4096));
      Image img(w, int((n + size_t(w) - 1) / size_t(w)), {"R", "G", "B", "A", "Z"});
      std::copy(rows.begin(), rows.end(), img.data.begin());
      writeImage(img, tmp);
    }
    outputs.commit();
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("queried %s (%s) along %zu rays of %s: %s in %.2f s\n", lf.path.c_str(), lf.kind.c_str(), n,
                o->rays.c_str(), o->out.c_str(), s);
  });
}

}  // namespace inim::cli
