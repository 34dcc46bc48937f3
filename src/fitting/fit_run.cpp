#include "fitting/fit_run.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/format.h"
#include "analysis/metrics.h"
#include "core/error.h"
#include "field/placement.h"
#include "radiance/grid_io.h"

namespace fs = std::filesystem;

namespace inim {

std::vector<int> defaultStageStarts(int iterations, int stages) {
  if (stages == 3) return {0, iterations / 6, iterations / 2};
  std::vector<int> starts(size_t(std::max(stages, 0)), 0);
  for (int s = 1; s < stages; ++s) starts[size_t(s)] = iterations * s / (2 * (stages - 1));
  return starts;
}

std::vector<int> parseIntList(const std::string& text, const std::string& key) {
  std::vector<int> v;
  size_t pos = 0;
  while (pos <= text.size()) {
    size_t comma = text.find(',', pos);
    std::string item = text.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos);
    char* end = nullptr;
    long x = std::strtol(item.c_str(), &end, 10);
    if (item.empty() || *end) throw InputError("", key, "\"" + text + "\"", "comma-separated whole numbers");
    v.push_back(int(x));
    if (comma == std::string::npos) break;
    pos = comma + 1;
  }
  return v;
}

glm::vec3 parseBackground(const std::string& text) {
  glm::vec3 c;
  if (text == "white") c = glm::vec3(1.0f);
  else if (text == "black") c = glm::vec3(0.0f);
  else c = glm::vec3(parseVec3(text, "background"));
  if (!(glm::all(glm::greaterThanEqual(c, glm::vec3(0.0f))) && glm::all(glm::lessThanEqual(c, glm::vec3(1.0f)))))
    throw InputError("", "background", "\"" + text + "\"", "white, black or r,g,b in [0, 1]");
  return c;
}

std::string datasetText(const Dataset& data) {
  const int w = data.frames.empty() ? 0 : data.frames[0].image.width;
  const int h = data.frames.empty() ? 0 : data.frames[0].image.height;
  char buf[2][4096];
  std::snprintf(buf[0], sizeof buf[0], "dataset:     %s (%s): %zu frames (%zu train, %zu held out), %d x %d px\n",
                data.file.c_str(), data.format.c_str(), data.frames.size(), data.train.size(), data.test.size(), w, h);
  std::snprintf(buf[1], sizeof buf[1], "scene box:   (%.4g, %.4g, %.4g) - (%.4g, %.4g, %.4g), near %.4g, far %.4g\n",
                data.sceneBox.lo.x, data.sceneBox.lo.y, data.sceneBox.lo.z, data.sceneBox.hi.x, data.sceneBox.hi.y,
                data.sceneBox.hi.z, data.nearPlane, data.farPlane);
  return std::string(buf[0]) + buf[1];
}

std::string trainingText(const TrainingRunSettings& s, const TrainingRunResult& r, double totalSeconds) {
  const TrainStats& st = r.stats;
  char buf[3][4096] = {};
  std::snprintf(buf[0], sizeof buf[0], "trained:     %d iterations of %d rays in %.1f s (last batch: loss %.5f, PSNR "
                "%.2f dB)%s\n", st.iterations, s.config.batchSize, st.seconds, st.loss, st.psnr,
                st.stoppedEarly ? ", stopped early" : "");
  if (!r.heldOut.empty())
    std::snprintf(buf[1], sizeof buf[1], "held out:    %zu views, PSNR %.2f dB, SSIM %.4f (rendered in %.1f s)\n",
                  r.heldOut.size(), meanPsnr(r.heldOut), meanSsim(r.heldOut), r.evalSeconds);
  std::snprintf(buf[2], sizeof buf[2], "wrote:       %s (grid %dx%dx%d, SH degree %d), %s; total %.1f s\n",
                s.modelPath.c_str(), r.gridResolution.x, r.gridResolution.y, r.gridResolution.z, r.shDegree,
                r.logPath.c_str(), totalSeconds);
  return std::string(buf[0]) + buf[1] + buf[2];
}

EvalRunResult runEval(const EvalRunSettings& s) {
  const VoxelGrid grid = loadVoxelGrid(s.modelPath);
  const Dataset data = loadDataset(s.dataPath, s.data);
  std::vector<int> frames = data.test;
  if (s.allFrames) {
    frames.clear();
    for (int i = 0; i < int(data.frames.size()); ++i) frames.push_back(i);
  }
  if (frames.empty())
    throw InputError(data.file, "holdout_every", std::to_string(s.data.holdoutEvery),
                     "a split that holds out at least one frame (or --all)");
  EvalRunResult r;
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<Image> renders;
  r.scores = evaluate(grid, data, frames, s.outDir.empty() ? nullptr : &renders);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!s.outDir.empty()) {
    OutputSet outputs;
    writeEvaluation(s.outDir, s.modelPath, data, r.scores, renders, outputs);
    outputs.commit();
  }
  return r;
}

namespace {

void writeTrainingLogHeader(std::ostream& csv) {
  csv << "iteration,loss,psnr_db,seconds,resolution_x,resolution_y,resolution_z,occupied_fraction,samples_per_ray\n";
}

void writeTrainingLogRow(std::ostream& csv, const TrainProgress& p) {
  csv << p.iteration << ',' << p.loss << ',' << p.psnr << ',' << p.elapsedSeconds << ',' << p.res.x << ',' << p.res.y
      << ',' << p.res.z << ',' << p.occupiedFraction << ',' << p.samplesPerRay << '\n';
}

double mean(const std::vector<ViewScore>& v, double ViewScore::*m) {
  double s = 0;
  for (const auto& x : v) s += x.*m;
  return v.empty() ? 0.0 : s / double(v.size());
}
}  // namespace

TrainingRunResult runTraining(const TrainingRunSettings& s) {
  if (fs::path(s.modelPath).extension() != ".inimrf")
    throw InputError("", "out", "\"" + s.modelPath + "\"", "a model file name ending in .inimrf");
  TrainingRunResult r;
  r.logPath = s.logPath.empty() ? fs::path(s.modelPath).replace_extension(".csv").string() : s.logPath;
  const Dataset data = loadDataset(s.dataPath, s.data);
  TrainConfig cfg = s.config;
  cfg.boxLo = Point3(data.sceneBox.lo), cfg.boxHi = Point3(data.sceneBox.hi);
  cfg.background = Vec3(data.background);
  const TrainingRays rays = datasetRays(data, data.train);
  if (s.loaded) s.loaded(data);

  OutputSet outputs;
  const std::string modelTmp = outputs.add(s.modelPath), logTmp = outputs.add(r.logPath);
  std::ofstream csv(logTmp);
  writeTrainingLogHeader(csv);
  VoxelGrid grid;
  r.stats = train(grid, rays, cfg, [&](const TrainProgress& p) {
    writeTrainingLogRow(csv, p);
    if (s.progress) s.progress(p);
    return true;
  });
  csv.close();
  if (!csv) throw std::runtime_error("cannot write " + r.logPath);
  grid.metadata = modelMetadata(data);
  saveVoxelGrid(grid, modelTmp);
  const auto te = std::chrono::steady_clock::now();
  r.heldOut = evaluate(grid, data, data.test, nullptr);
  r.evalSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - te).count();
  outputs.commit();
  r.gridResolution = grid.res;
  r.shDegree = grid.shDegree;
  return r;
}

double meanPsnr(const std::vector<ViewScore>& scores) { return mean(scores, &ViewScore::psnr); }
double meanSsim(const std::vector<ViewScore>& scores) { return mean(scores, &ViewScore::ssim); }

void writeEvaluation(const std::string& dir, const std::string& model, const Dataset& data,
                     const std::vector<ViewScore>& scores, const std::vector<Image>& renders, OutputSet& outputs) {
  nlohmann::json j = {{"model", model}, {"dataset", data.file}, {"views", nlohmann::json::array()}};
  std::string csv = "frame,image,psnr_db,ssim\n";
  for (size_t k = 0; k < scores.size(); ++k) {
    const ViewScore& s = scores[k];
    char name[64];
    std::snprintf(name, sizeof name, "view_%04d", s.frame);
    writeImage(renders[k], outputs.add((fs::path(dir) / (std::string(name) + "_model.png")).string()));
    writeImage(colorImage(data.frames[size_t(s.frame)].image),
               outputs.add((fs::path(dir) / (std::string(name) + "_photo.png")).string()));
    j["views"].push_back({{"frame", s.frame}, {"image", s.image}, {"psnr_db", s.psnr}, {"ssim", s.ssim}});
    char line[512];
    std::snprintf(line, sizeof line, "%d,%s,%.4f,%.5f\n", s.frame, s.image.c_str(), s.psnr, s.ssim);
    csv += line;
  }
  j["mean_psnr_db"] = meanPsnr(scores);
  j["mean_ssim"] = meanSsim(scores);
  std::ofstream(outputs.add((fs::path(dir) / "metrics.json").string())) << j.dump(2) << "\n";
  std::ofstream(outputs.add((fs::path(dir) / "metrics.csv").string())) << csv;
}

std::string trainProgressText(const TrainProgress& p) {
  return formatText("\rtrain  iteration %d/%d  loss %.5f  PSNR %.2f dB  grid %dx%dx%d  %.0f s   ", p.iteration,
                    p.iterations, p.loss, p.psnr, p.res.x, p.res.y, p.res.z, p.elapsedSeconds);
}

std::string evalText(const EvalRunResult& r, bool perView) {
  std::string t;
  for (const auto& v : r.scores)
    if (perView) t += formatText("frame %4d  PSNR %6.2f dB  SSIM %.4f  %s\n", v.frame, v.psnr, v.ssim, v.image.c_str());
  return t + formatText("mean over %zu views: PSNR %.2f dB, SSIM %.4f (%.1f s)\n", r.scores.size(),
                        meanPsnr(r.scores), meanSsim(r.scores), r.seconds);
}

}  // namespace inim
