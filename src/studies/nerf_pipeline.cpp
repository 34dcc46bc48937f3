// inim study nerf-pipeline: the paper's whole reference workflow in software against exact
// ground truth. The analytic scene (scenes/paper-fig7.json) is captured like a phone scan
// (capture/), a voxel radiance field is trained on the photos (radiance/), the field's EIA is
// synthesised (synthesis/) and seen through the display by the paper's camera (view/); every
// step is compared with the same step done with the analytic scene itself, so the error each
// step adds is measured, not guessed.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <unistd.h>
#include <utility>

#include "analysis/contact_sheet.h"
#include "analysis/metrics.h"
#include "analysis/plot.h"
#include "camera/camera_config.h"
#include "capture/capture.h"
#include "capture/capture_poses.h"
#include "core/error.h"
#include "core/output_file.h"
#include "dataset/dataset.h"
#include "fitting/dataset_fit.h"
#include "display/display.h"
#include "display/ei_layout.h"
#include "radiance/radiance_field.h"
#include "radiance/trainer.h"
#include "radiance/volume_renderer.h"
#include "camera/fov_camera.h"
#include "render/renderer.h"
#include "scene/analytic_scene.h"
#include "studies/studies.h"
#include "studies/study_common.h"
#include "studies/study_pipeline.h"
#include "synthesis/eia_synthesis.h"
#include "view/display_model.h"
#include "view/display_pose.h"
#include "view/reference_renderer.h"
#include "view/view_camera.h"
#include "view/view_image.h"
#include "view/view_renderer.h"

namespace fs = std::filesystem;

namespace inim {

namespace {

using namespace study_detail;
using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The budget of one run. Full: the validation/nerf-pipeline/ report; quick: the CI test.
struct Budget {
  int views, width, height, captureSpp, truthSpp;
  int iterations, batch;
  std::vector<int> resolutions;  // per stage: about resolutions[s]^3 cells
  int eiaSpp;             // analytic EIA (the field is deterministic: 1)
  int eiCols, eiRows;     // display crop (central EIs); 0 = the whole display
  int viewWidth, viewSpp, refSpp;
  bool sideView;          // also the +7 deg H view
};

Budget budgetFor(bool quick) {
  if (quick) return {24, 64, 48, 4, 32, 300, 4096, {32, 64}, 8, 41, 21, 200, 4, 4, false};
  return {64, 200, 150, 16, 256, 1000, 4096, {48, 96, 128}, 8, 0, 0, 648, 16, 8, true};
}

// What the training box holds: the display's whole depth range in front of and behind it
// (the backdrop at z = -60 mm included, which every display ray behind the objects sees)
// and the x-y extent the capture's views see of it.
const Box3d kTrainBox{{-110.0, -75.0, -64.0}, {110.0, 75.0, 46.0}};
// What the capture frames (the paper-fig7 objects).
const Box3d kCaptureTarget{{-60.0, -30.0, -20.0}, {60.0, 30.0, 40.0}};

// A render (linear R, G, B, A, ...) as the dataset loader sees its capture PNG: straight
// colour sRGB-encoded, composited onto black (c a), not quantised.
Image photoValues(const Image& render) {
  const int W = render.width, H = render.height, C = render.numChannels();
  Image straight(W, H, {"R", "G", "B"});
  for (size_t p = 0; p < size_t(W) * H; ++p) {
    const float a = std::clamp(render.data[p * C + 3], 0.0f, 1.0f);
    const float s = a > 1e-6f ? 1.0f / a : 0.0f;
    for (int c = 0; c < 3; ++c) straight.data[p * 3 + c] = render.data[p * C + c] * s;
  }
  Image enc = encodeSRGB(straight);
  for (size_t p = 0; p < size_t(W) * H; ++p) {
    const float a = std::clamp(render.data[p * C + 3], 0.0f, 1.0f);
    for (int c = 0; c < 3; ++c) enc.data[p * 3 + c] = std::clamp(enc.data[p * 3 + c], 0.0f, 1.0f) * a;
  }
  return enc;
}

// EIA pixels (panel resolution) that see the scene: the analytic EIA's opacity A > 0.5.
PixelMask eiaSceneMask(const Image& eia) {
  PixelMask m;
  m.width = eia.width;
  m.height = eia.height;
  m.source = "analytic EIA opacity";
  m.on.assign(size_t(m.width) * m.height, 0);
  const int a = eia.channelIndex("A");
  if (a < 0) throw std::logic_error("nerf-pipeline: EIA without A");
  for (size_t p = 0; p < m.on.size(); ++p) m.on[p] = eia.data[p * eia.channels.size() + size_t(a)] > 0.5f ? 1 : 0;
  return m;
}

// A crop of a panel-resolution RGB image around the display point (x, y) mm, w x h pixels
// (clamped to the EIA area), enlarged `zoom` times (nearest pixel).
Image eiaCrop(const EiLayout& L, const Image& panelRgb, double xMm, double yMm, int w, int h, int zoom) {
  w = std::min(w, L.eiaW), h = std::min(h, L.eiaH);
  int c0 = int(std::lround(xMm / L.pixelMm + 0.5 * L.eiaW)) - w / 2;
  int r0 = int(std::lround(0.5 * L.eiaH - yMm / L.pixelMm)) - h / 2;
  c0 = std::clamp(c0, 0, L.eiaW - w);
  r0 = std::clamp(r0, 0, L.eiaH - h);
  Image out(w * zoom, h * zoom, {"R", "G", "B"});
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int c = 0; c < 3; ++c)
        out.at(x, y, c) = panelRgb.at(L.panelCol0 + c0 + x / zoom, L.panelRow0 + r0 + y / zoom, c);
  return out;
}

// One line of the results: a comparison of step `step`.
struct Row {
  Row(int s, std::string c) : step(s), comparison(std::move(c)) {}
  int step;
  std::string comparison;
  double psnr = std::nan(""), ssim = std::nan(""), deMean = std::nan(""), deP95 = std::nan("");
  int64_t pixels = 0;
  std::string note;
};

std::string num(double v, int d) { return std::isfinite(v) ? fmt(v, d) : std::string("–"); }

// A one-sided verdict value: pass when measured >= threshold (atLeast) or <= threshold.
StudyValue bound(const std::string& name, double measured, double threshold, bool atLeast) {
  StudyValue v{name, measured, threshold, 0.0, false};
  v.pass = std::isfinite(measured) && (atLeast ? measured >= threshold : measured <= threshold);
  return v;
}

}  // namespace

StudyReport runNerfPipeline(const StudyOptions& o) {
  const auto tStart = Clock::now();
  const Budget B = budgetFor(o.quick);
  const std::string displayPath = displayPathOrDefault(o.displayPath);
  const std::string scenePath = dataPath("scenes/paper-fig7.json");
  Display display = loadDisplay(displayPath);
  if (B.eiCols > 0) display.eiCols = std::min(display.eiCols, B.eiCols);
  if (B.eiRows > 0) display.eiRows = std::min(display.eiRows, B.eiRows);
  const EiLayout L = computeLayout(display);
  auto scene = AnalyticScene::load(scenePath);
  const CameraDescription camDesc = loadCameraDescription("alvium-1800-u-500c");
  std::vector<Row> rows;

  // A private scratch folder for the capture (removed at the end, also on failure).
  const fs::path scratch =
      fs::temp_directory_path() / ("inim_study_nerf_pipeline_" + std::to_string(::getpid()) + "_" +
                                   std::to_string(Clock::now().time_since_epoch().count()));
  struct Cleanup {
    fs::path p;
    ~Cleanup() {
      std::error_code ec;
      fs::remove_all(p, ec);
    }
  } cleanup{scratch};

  // ---- 1. Capture ----------------------------------------------------------------------
  auto t0 = Clock::now();
  CaptureSettings cs;
  cs.views = B.views;
  cs.width = B.width;
  cs.height = B.height;
  cs.spp = B.captureSpp;
  cs.target = kCaptureTarget;
  cs.sceneFile = scenePath;
  cs.seed = 1;
  cs.progress = false;
  const CaptureResult cap = captureScene(*scene, cs, (scratch / "capture").string());
  const double captureSeconds = since(t0);

  DatasetOptions dopt;
  dopt.holdoutEvery = 8;
  dopt.background = glm::vec3(0.0f);
  dopt.sceneBox = kTrainBox;
  dopt.nearPlane = 10.0;  // the box clips the rays; the pose-based estimate of far is too short for it
  dopt.farPlane = 1000.0;
  const Dataset data = loadDataset((scratch / "capture").string(), dopt);

  // Capture noise: frame 1 (index 0, held out) against a render with truthSpp samples.
  t0 = Clock::now();
  Image truth0;
  {
    const std::vector<glm::dvec3> dirs = capDirections(cs.views, cs.minElevationDeg, cs.maxElevationDeg);
    const glm::dvec3 centre = cap.target.center();
    FovCameraSettings spec;
    spec.width = cs.width;
    spec.height = cs.height;
    spec.hfovDeg = float(cs.hfovDeg);
    spec.pose.eye = roundedToFloat(centre + cap.radiusMm * dirs[0]);
    spec.pose.lookAt = roundedToFloat(centre);
    const glm::dmat4 c2w = lookAtCameraToWorld(spec.pose.eye, spec.pose.lookAt);
    spec.pose.up = glm::dvec3(c2w[1]);
    FovCameraModel camera(spec);
    RenderSettings rs;
    rs.spp = B.truthSpp;
    rs.seed = 977;
    rs.progress = false;
    truth0 = photoValues(renderField(*scene, camera, rs).image);
  }
  const double truthSeconds = since(t0);
  const Image& photo0 = data.frames[0].image;
  {
    Row r{1, "capture photo (frame 1, " + std::to_string(B.captureSpp) + " spp, 8-bit) vs " +
                 std::to_string(B.truthSpp) + "-spp render"};
    r.psnr = psnr(photo0, truth0);
    r.ssim = ssim(photo0, truth0).value;
    r.pixels = int64_t(photo0.width) * photo0.height;
    r.note = "sRGB on black, as training sees it";
    rows.push_back(r);
  }

  // ---- 2. Trained field ----------------------------------------------------------------
  t0 = Clock::now();
  TrainConfig tc;
  tc.boxLo = Point3(data.sceneBox.lo), tc.boxHi = Point3(data.sceneBox.hi);
  tc.background = Vec3(data.background);
  tc.iterations = B.iterations;
  tc.batchSize = B.batch;
  tc.resolutions = B.resolutions;
  {
    const int n = int(tc.resolutions.size());
    tc.stageStarts.assign(size_t(n), 0);
    if (n == 3) tc.stageStarts = {0, B.iterations / 6, B.iterations / 2};
    else
      for (int s = 1; s < n; ++s) tc.stageStarts[size_t(s)] = B.iterations * s / (2 * (n - 1));
  }
  tc.seed = 1;
  VoxelGrid grid;
  TrainStats tstats;
  {
    const TrainingRays rays = datasetRays(data, data.train);
    tstats = train(grid, rays, tc);
  }
  const double trainSeconds = since(t0);
  const RadianceField field(std::move(grid));
  double heldPsnr = 0.0, heldSsim = 0.0;
  Image field0;
  {
    VolumeRenderer renderer(field.grid());
    for (int i : data.test) {
      const DatasetFrame& f = data.frames[size_t(i)];
      Image img = renderFrame(renderer, data, f);
      heldPsnr += psnr(img, f.image);
      heldSsim += ssim(img, f.image).value;
      if (i == 0) field0 = std::move(img);
    }
    heldPsnr /= double(data.test.size());
    heldSsim /= double(data.test.size());
  }
  {
    Row r{2, "field vs held-out photos (" + std::to_string(data.test.size()) + " views)"};
    r.psnr = heldPsnr;
    r.ssim = heldSsim;
    r.pixels = int64_t(data.test.size()) * B.width * B.height;
    r.note = std::to_string(tstats.iterations) + " iterations, " + fmt(trainSeconds, 0) + " s";
    rows.push_back(r);
    Row t{2, "field vs " + std::to_string(B.truthSpp) + "-spp render (frame 1)"};
    t.psnr = psnr(field0, truth0);
    t.ssim = ssim(field0, truth0).value;
    t.pixels = int64_t(B.width) * B.height;
    t.note = "the field against the truth, not the noisy photo";
    rows.push_back(t);
  }

  // ---- 3. EIA --------------------------------------------------------------------------
  t0 = Clock::now();
  SynthesisSettings sa;
  sa.spp = B.eiaSpp;
  sa.seed = 1;
  sa.autoExposure = true;
  sa.aovs = true;
  sa.progress = false;
  const SynthesisResult eiaA = synthesizeEia(L, display.panel, *scene, sa);
  const double eiaASeconds = since(t0);
  t0 = Clock::now();
  SynthesisSettings sf = sa;
  sf.spp = 1;
  sf.autoExposure = false;
  sf.exposure = eiaA.stats.exposureUsed;
  const SynthesisResult eiaF = synthesizeEia(L, display.panel, field, sf);
  const double eiaFSeconds = since(t0);
  const Image encA = encodeForPanel(eiaA.eia, display.panel.eotf), encF = encodeForPanel(eiaF.eia, display.panel.eotf);
  const PixelMask eiMask = eiaSceneMask(eiaA.eia);
  double eiaPsnr = 0.0;
  // Depth, field - analytic, where both see a surface: over all such EI pixels, and over those
  // whose analytic surface is an object (in front of the backdrop at z = -60 mm).
  struct DepthStats {
    double meanDiff = std::nan(""), meanAbs = std::nan(""), medianAbs = std::nan(""), within2 = std::nan("");
    int64_t pixels = 0;
  } zAll, zObj;
  {
    Row r{3, "field EIA vs analytic EIA"};
    r.psnr = psnr(encA, encF, 1.0, &eiMask);
    r.ssim = ssim(encA, encF, {}, &eiMask).value;
    r.pixels = eiMask.count();
    r.note = "panel-encoded drive values, EI pixels with A > 0.5";
    eiaPsnr = r.psnr;
    rows.push_back(r);
    const int za = eiaA.eia.channelIndex("Z"), aa = eiaA.eia.channelIndex("A");
    const int zf = eiaF.eia.channelIndex("Z"), af = eiaF.eia.channelIndex("A");
    const size_t ca = eiaA.eia.channels.size(), cf = eiaF.eia.channels.size();
    std::vector<double> dAll, dObj;
    for (size_t p = 0; p < size_t(eiaA.eia.width) * eiaA.eia.height; ++p) {
      if (eiaA.eia.data[p * ca + size_t(aa)] <= 0.5f || eiaF.eia.data[p * cf + size_t(af)] <= 0.5f) continue;
      const double zA = eiaA.eia.data[p * ca + size_t(za)];
      const double d = double(eiaF.eia.data[p * cf + size_t(zf)]) - zA;
      dAll.push_back(d);
      if (zA > -55.0) dObj.push_back(d);
    }
    auto stats = [](std::vector<double>& d, DepthStats& st) {
      if (d.empty()) return;
      double sum = 0.0, sa = 0.0;
      int64_t w2 = 0;
      for (double& x : d) sum += x, sa += std::abs(x), w2 += std::abs(x) <= 2.0 ? 1 : 0, x = std::abs(x);
      st.pixels = int64_t(d.size());
      st.meanDiff = sum / double(d.size());
      st.meanAbs = sa / double(d.size());
      st.within2 = double(w2) / double(d.size());
      st.medianAbs = percentile(d, 50.0);
    };
    stats(dAll, zAll);
    stats(dObj, zObj);
  }
  // The analytic EIA's own Monte Carlo noise: the same EIA with another seed. With independent
  // noise of variance s2 per value, E|F - A1|^2 = |F - T|^2 + s2 and E|A1 - A2|^2 = 2 s2, so
  // |F - T|^2 ~ MSE(F, A1) - MSE(A1, A2) / 2: the field EIA against the exact (noise-free) EIA.
  t0 = Clock::now();
  SynthesisSettings s2 = sa;
  s2.seed = 2;
  s2.autoExposure = false;
  s2.exposure = eiaA.stats.exposureUsed;
  const SynthesisResult eiaA2 = synthesizeEia(L, display.panel, *scene, s2);
  double eiaPsnrExact = std::nan("");
  {
    const Image enc2 = encodeForPanel(eiaA2.eia, display.panel.eotf);
    Row r{3, "analytic EIA, seed 2 vs seed 1 (its noise floor)"};
    r.psnr = psnr(encA, enc2, 1.0, &eiMask);
    r.ssim = ssim(encA, enc2, {}, &eiMask).value;
    r.pixels = eiMask.count();
    r.note = std::to_string(B.eiaSpp) + " spp each";
    rows.push_back(r);
    const double mseFT = meanSquaredError(encA, encF, &eiMask) - 0.5 * meanSquaredError(encA, enc2, &eiMask);
    Row c{3, "field EIA vs exact EIA (noise-corrected estimate)"};
    if (mseFT > 0.0) c.psnr = psnrFromMse(mseFT, 1.0);
    c.pixels = eiMask.count();
    c.note = "MSE(F, A1) - MSE(A1, A2) / 2";
    eiaPsnrExact = c.psnr;
    rows.push_back(c);
  }
  const double eiaNoiseSeconds = since(t0);

  // ---- 4, 5. Views -----------------------------------------------------------------------
  t0 = Clock::now();
  const DisplayModel dmA = makeDisplayModel(display, L, colorImage(eiaA.eia), "(analytic EIA)", MlaKind::Real);
  const DisplayModel dmF = makeDisplayModel(display, L, colorImage(eiaF.eia), "(field EIA)", MlaKind::Real);
  const DisplayModel dmA2 = makeDisplayModel(display, L, colorImage(eiaA2.eia), "(analytic EIA, seed 2)", MlaKind::Real);
  const Transform identity = Placement{}.toDisplay();
  Image stripViewA, stripViewF, stripRef;
  double view0Psnr = 0.0, view0De = 0.0;
  std::vector<double> angles{0.0};
  if (B.sideView) angles.push_back(7.0);
  for (double angle : angles) {
    DisplayPose pose;
    pose.rotHDeg = angle;
    pose.distanceMm = camDesc.distanceMm;
    ViewCameraOptions co;
    co.width = B.viewWidth;
    // Quick: the display crop is small; a thin-lens camera (f/4, 3 mm pupil) at the same distance
    // frames it (0.25 mm per pixel on the MLA plane) instead of the full sensor's view.
    std::unique_ptr<CameraModel> camera =
        B.eiCols > 0 ? axialThinLens(camDesc.distanceMm, 0.0, B.viewWidth, B.viewWidth / 2, 0.25)
                     : makeViewCamera(camDesc, pose, co);
    ViewSettings vs;
    vs.spp = B.viewSpp;
    vs.seed = 1;
    vs.progress = false;
    const ViewResult vA = renderView(*camera, camDesc.sensor, *dmA.mla, *dmA.panel, dmA.area, vs);
    const ViewResult vF = renderView(*camera, camDesc.sensor, *dmF.mla, *dmF.panel, dmA.area, vs);
    ViewSettings vs2 = vs;
    vs2.seed = 2;
    const ViewResult vA2 = renderView(*camera, camDesc.sensor, *dmA2.mla, *dmA2.panel, dmA.area, vs2);
    ReferenceSettings rs;
    rs.spp = B.refSpp;
    rs.seed = 1;
    rs.progress = false;
    const ViewResult ref = renderReference(*scene, identity, *camera, camDesc.sensor, rs);
    // One exposure for all, as `inim fig11`: the reference in the panel's units (the EIA's
    // exposure x peak luminance), auto-exposed; that factor applies to every view.
    const Image refCdM2 = scaledImage(ref.image, eiaA.stats.exposureUsed * display.panel.peakLuminanceCdM2);
    const double k = exposureFactor(refCdM2, camDesc.sensor, Exposure{});
    const Image sA = cameraRgbToSrgb(scaledImage(vA.image, k), camDesc.sensor);
    const Image sF = cameraRgbToSrgb(scaledImage(vF.image, k), camDesc.sensor);
    const Image sA2 = cameraRgbToSrgb(scaledImage(vA2.image, k), camDesc.sensor);
    const Image sR = cameraRgbToSrgb(scaledImage(refCdM2, k), camDesc.sensor);
    const PixelMask mask = displayMask(*camera, dmA.area);
    CompareOptions copt;
    copt.spaceA = copt.spaceB = "srgb";
    const std::string at = angle == 0.0 ? "0°" : "H +" + fmt(angle, 0) + "°";
    auto add = [&](int step, const std::string& what, const Image& a, const Image& b, const std::string& note) {
      const ImageMetrics m = compareImages(a, b, copt, &mask);
      Row r{step, what + ", " + at};
      r.psnr = m.psnrDb, r.ssim = m.ssim, r.deMean = m.deltaE.mean, r.deP95 = m.deltaE.p95, r.pixels = m.pixels;
      r.note = note;
      rows.push_back(r);
      return m;
    };
    const ImageMetrics m = add(4, "view(field EIA) vs view(analytic EIA)", sA, sF, "same camera, same samples");
    add(4, "view(analytic EIA), seed 2 vs seed 1 (its noise floor)", sA, sA2,
        "EIA and view seeds 2; " + std::to_string(B.viewSpp) + " spp each");
    add(5, "view(analytic EIA) vs reference view", sR, sA, "what the display itself loses");
    add(5, "view(field EIA) vs reference view", sR, sF, "end to end");
    if (angle == 0.0) {
      view0Psnr = m.psnrDb, view0De = m.deltaE.mean;
      stripViewA = sA, stripViewF = sF, stripRef = sR;
    }
  }
  const double viewSeconds = since(t0);
  const double totalSeconds = since(tStart);

  // ---- Verdict -------------------------------------------------------------------------
  // Thresholds: what the budget reaches, with margin (see the report's Verdict).
  const double kHeld = o.quick ? 14.0 : 19.0, kEia = o.quick ? 11.0 : 17.0, kView = o.quick ? 13.0 : 16.5,
               kDe = o.quick ? 18.0 : 10.0;
  StudyReport rep;
  rep.study = "nerf-pipeline";
  rep.values.push_back(bound("held-out PSNR of the field (dB)", heldPsnr, kHeld, true));
  rep.values.push_back(bound("field EIA vs analytic EIA, PSNR (dB)", eiaPsnr, kEia, true));
  rep.values.push_back(bound("view(field EIA) vs view(analytic EIA) at 0°, PSNR (dB)", view0Psnr, kView, true));
  rep.values.push_back(bound("view(field EIA) vs view(analytic EIA) at 0°, mean ΔE2000", view0De, kDe, false));
  rep.pass = allPass(rep.values);

  // ---- Files ---------------------------------------------------------------------------
  OutputSet out;
  const fs::path dir(o.outDir);
  const std::string mdPath = (dir / "report.md").string(), csvPath = (dir / "steps.csv").string(),
                    pngPath = (dir / "psnr_per_step.png").string(), stripPath = (dir / "strip.png").string();
  {
    std::vector<std::vector<std::string>> cr;
    for (const auto& r : rows)
      cr.push_back({std::to_string(r.step), r.comparison, csvNumber(r.psnr), csvNumber(r.ssim), csvNumber(r.deMean),
                    csvNumber(r.deP95), std::to_string(r.pixels), r.note});
    for (const auto& [label, st] : {std::pair<std::string, const DepthStats&>{"all", zAll}, {"objects", zObj}}) {
      const std::string n = std::to_string(st.pixels);
      cr.push_back({"3", "EIA depth (" + label + "): mean Z(field) - Z(analytic), mm", csvNumber(st.meanDiff), "", "", "", n, ""});
      cr.push_back({"3", "EIA depth (" + label + "): mean |dZ|, mm", csvNumber(st.meanAbs), "", "", "", n, ""});
      cr.push_back({"3", "EIA depth (" + label + "): median |dZ|, mm", csvNumber(st.medianAbs), "", "", "", n, ""});
      cr.push_back({"3", "EIA depth (" + label + "): fraction |dZ| <= 2 mm", csvNumber(st.within2), "", "", "", n, ""});
    }
    writeCsv(out.add(csvPath),
             {"step", "comparison", "psnr_db", "ssim", "de2000_mean", "de2000_p95", "pixels", "note"}, cr);
  }
  {
    // PSNR per step: the pipeline's comparisons (filled), and the noise floors (dashed).
    Plot p;
    p.title = "nerf-pipeline: PSNR per step";
    p.x.title = "step (1 capture, 2 field, 3 EIA, 4 view, 5 view vs scene)";
    p.y.title = "PSNR (dB)";
    PlotSeries chain{"field chain vs analytic chain (0 deg)", {}, {}};
    PlotSeries floors{"analytic noise floors (seed 2 vs 1)", {}, {}};
    PlotSeries context{"vs truth / the scene itself", {}, {}};
    double top = 0.0, bottom = 1e9;
    for (const auto& r : rows) {
      if (!std::isfinite(r.psnr)) continue;
      top = std::max(top, r.psnr), bottom = std::min(bottom, r.psnr);
      const bool floor = r.comparison.find("noise floor") != std::string::npos;
      const bool side = r.comparison.find("H +") != std::string::npos;
      if (side) continue;
      if (floor) floors.x.push_back(r.step), floors.y.push_back(r.psnr);
      else if (r.step == 1 || r.step == 5 || r.comparison.find("-spp render") != std::string::npos ||
               r.comparison.find("exact EIA") != std::string::npos)
        context.x.push_back(r.step), context.y.push_back(r.psnr);
      else
        chain.x.push_back(r.step), chain.y.push_back(r.psnr);
    }
    floors.line = false;
    context.line = false;
    p.x.min = 0.5, p.x.max = 5.5;
    p.y.min = std::floor(bottom - 1.0), p.y.max = std::ceil(top + 0.45 * (top - bottom) + 2.0);  // room for the legend
    p.series = {chain, floors, context};
    writePlot(p, out.add(pngPath));
  }
  {
    const int zoom = 2, cw = 12 * L.eiW, ch = 9 * L.eiH;
    SheetGrid g(1);
    g[0].push_back(SheetCell{"analytic EIA (crop)", eiaCrop(L, encA, 15.0, -5.0, cw, ch, zoom)});
    g[0].push_back(SheetCell{"field EIA (crop)", eiaCrop(L, encF, 15.0, -5.0, cw, ch, zoom)});
    g[0].push_back(SheetCell{"view of analytic EIA", stripViewA});
    g[0].push_back(SheetCell{"view of field EIA", stripViewF});
    g[0].push_back(SheetCell{"reference (scene)", stripRef});
    ContactSheetOptions so;
    so.heading = "nerf-pipeline: paper-fig7 -> capture -> field -> EIA -> view (0 deg)";
    writeImage(composeContactSheet(g, so), out.add(stripPath));
  }

  const double Pmm = display.mla.pitchMm;
  std::string md;
  md += "# Study: the NeRF workflow against exact ground truth\n\n";
  md += "**What.** The paper's reference workflow — photograph a scene, train a radiance field on the photos, "
        "synthesise the display's EIA from the field, look at the display — run in software on the analytic scene "
        "`scenes/paper-fig7.json`, so that every step can be compared with the same step done with the scene itself "
        "(exact geometry, spectral materials). The table gives the error each step adds.\n\n";
  md += "**Prediction.** No closed form: this is a measurement of the chain. What to expect: the trained field "
        "differs from the photos by the capture's Monte Carlo noise plus what the grid cannot represent (a voxel "
        "grid of about " + fmt(double(field.grid().res.x), 0) + " vertices across " +
        fmt(field.grid().hi.x - field.grid().lo.x, 0) + " mm, i.e. " +
        fmt((field.grid().hi.x - field.grid().lo.x) / std::max(1, field.grid().res.x - 1), 2) +
        " mm cells, against a lens pitch P = " + fmt(Pmm, 2) + " mm), view-dependent effects (the brass coin's "
        "mirror image, the yellow filter) and the photos' 8-bit sRGB; the field's EIA inherits that error on every EI "
        "pixel; the display then blurs both EIAs alike (each lenslet shows one facet of about P), so in structure "
        "(SSIM) the views of the two EIAs should agree better than the EIAs themselves, while their PSNR also "
        "carries the views' Monte Carlo noise (the analytic EIA's noise seen through the display, and the camera's "
        "sampling).\n\n";
  md += "**Method.**\n\n";
  md += "1. *Capture* (`captureScene`): " + std::to_string(B.views) + " views of " + std::to_string(B.width) + " × " +
        std::to_string(B.height) + " px, " + std::to_string(B.captureSpp) + " spp, horizontal field of view 40°, "
        "cameras on the cap 50–90° above the display plane at " + fmt(cap.radiusMm, 0) + " mm from the centre of "
        "the target box x −60…60, y −30…30, z −20…40 mm (the fig7 objects), RGBA PNG with alpha = coverage. "
        "Loaded with `loadDataset` onto a black background (the scene's dim environment is kept only in partly "
        "covered pixels), every 8th view held out. The capture noise is measured on view 1 (held out) against a "
        "render of the same camera with " + std::to_string(B.truthSpp) + " spp, both as training sees them "
        "(sRGB on black).\n";
  md += "2. *Field* (`train`): a voxel grid (density + SH degree 1 colour, coarse to fine over resolutions ";
  for (size_t i = 0; i < B.resolutions.size(); ++i) md += (i ? ", " : "") + std::to_string(B.resolutions[i]);
  md += "), " + std::to_string(B.iterations) + " iterations of " + std::to_string(B.batch) + " rays, in the box "
        "x −110…110, y −75…75, z −64…46 mm (the backdrop at z = −60 mm included: every display ray that misses the "
        "objects ends on it). Held-out PSNR / SSIM against the held-out photos (as `inim eval`), and the field's "
        "render of view 1 against its " + std::to_string(B.truthSpp) + "-spp truth.\n";
  md += "3. *EIA* (`synthesizeEia`, identity placement: the capture is in mm): the display " +
        std::string(B.eiCols > 0 ? "cropped to its central " + std::to_string(display.eiCols) + " × " +
                                       std::to_string(display.eiRows) + " lenslets (quick run)"
                                 : "in full (" + std::to_string(display.eiCols) + " × " +
                                       std::to_string(display.eiRows) + " lenslets)") +
        ". The analytic EIA with " + std::to_string(B.eiaSpp) + " spp and automatic exposure (" +
        fmt(eiaA.stats.exposureUsed, 4) + "), the field's with 1 spp (it is deterministic) and that same fixed "
        "exposure. PSNR / SSIM of the panel-encoded drive values (what the phone shows) over the EI pixels that see "
        "the scene (analytic A > 0.5); depth: the difference of the Z channels (display z of the first surface for "
        "the scene, the expected depth for the field) where both A > 0.5. A second analytic EIA with another seed "
        "gives the analytic EIA's own noise, and with it an estimate of the field EIA against the exact, "
        "noise-free EIA: MSE(F, A1) − MSE(A1, A2) / 2 (independent noise of equal variance in A1 and A2).\n";
  md += "4. *View* (`renderView`, as `inim fig11`): the paper prototype's real refracting MLA and RGB-stripe "
        "subpixels, " +
        (B.eiCols > 0 ? std::string("a thin-lens camera (f = 12 mm, f/4) at ") + fmt(camDesc.distanceMm, 0) +
                            " mm framing the crop (0.25 mm per pixel on the MLA plane) with the sensor of " + camDesc.name
                      : "camera " + camDesc.name + " at " + fmt(camDesc.distanceMm, 0) + " mm") +
        ", " + std::to_string(B.viewWidth) + " px wide, " + std::to_string(B.viewSpp) + " spp, at 0°" +
        (B.sideView ? " and turned 7° H" : "") + "; both EIAs with the same samples (seed), one exposure for all "
        "(the reference's auto exposure in panel units, as fig11), compared as sRGB over the camera pixels that see "
        "the display. The second analytic EIA, seen with another view seed, gives the views' noise floor.\n";
  md += "5. *Context*: each view against the reference view of the scene itself (`renderReference`, " +
        std::to_string(B.refSpp) + " spp): what the display loses whatever its EIA.\n\n";
  md += "**Result.**\n\n";
  md += "| step | comparison | PSNR (dB) | SSIM | ΔE2000 mean | ΔE2000 p95 | pixels | note |\n";
  md += "|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows)
    md += "| " + std::to_string(r.step) + " | " + r.comparison + " | " + num(r.psnr, 2) + " | " + num(r.ssim, 4) +
          " | " + num(r.deMean, 2) + " | " + num(r.deP95, 2) + " | " + std::to_string(r.pixels) + " | " + r.note +
          " |\n";
  md += "\nThe field EIA against the exact EIA (noise-corrected estimate): " + num(eiaPsnrExact, 2) + " dB.\n";
  auto depthLine = [](const DepthStats& st) {
    return std::to_string(st.pixels) + " px: mean " + num(st.meanDiff, 2) + " mm, mean |ΔZ| " + num(st.meanAbs, 2) +
           " mm, median |ΔZ| " + num(st.medianAbs, 2) + " mm, " + num(100.0 * st.within2, 1) + "% within 2 mm";
  };
  md += "\nEIA depth, field − analytic, where both see a surface (A > 0.5):\n\n"
        "- all EI pixels (" + depthLine(zAll) + ");\n"
        "- EI pixels whose analytic surface is an object, in front of the backdrop (z > −55 mm; " + depthLine(zObj) +
        ").\n\n"
        "Most display rays end on the backdrop (z = −60 mm), a uniform diffuse wall: nothing in the photos pins its "
        "depth, so the field spreads it as a semi-transparent haze in front of it and the expected depth lands tens "
        "of mm too close, while its colour (what the EIA shows) is right. The yellow filter (92% transmission) has "
        "the same ambiguity by nature: the scene's first surface is the filter, the field's expected depth lies "
        "between it and what is seen through it. The depth is therefore reported, not judged.\n\n";
  md += "Training: " + std::to_string(tstats.iterations) + " iterations, last batch PSNR " + fmt(tstats.psnr, 2) +
        " dB, final grid " + std::to_string(field.grid().res.x) + " × " + std::to_string(field.grid().res.y) + " × " +
        std::to_string(field.grid().res.z) + ".\n\n";
  md += "Time (wall, 2 shared cores): capture " + fmt(captureSeconds, 1) + " s, truth render " + fmt(truthSeconds, 1) +
        " s, training " + fmt(trainSeconds, 1) + " s, analytic EIA " + fmt(eiaASeconds, 1) + " s, field EIA " +
        fmt(eiaFSeconds, 1) + " s, EIA noise floor " + fmt(eiaNoiseSeconds, 1) + " s, views and references " +
        fmt(viewSeconds, 1) + " s; total " + fmt(totalSeconds, 1) + " s.\n\n";
  md += "![PSNR per step](psnr_per_step.png)\n\n";
  md += "![analytic EIA | field EIA | view of each | reference](strip.png)\n\n";
  md += "Data: `steps.csv`.\n\n";
  md += "**Verdict.** One-sided bounds set about 2 dB (and a few ΔE units) short of what this budget measured when "
        "the bounds were chosen, so that the same run passes on another machine (the run is deterministic for a "
        "given build: every step's sampling depends on fixed seeds, not on the thread count) while a field that "
        "did not converge, or a step that loses the placement, exposure or colour space, falls below them. They "
        "are not a quality target: the noise floors in the table show how much of each difference is the "
        "analytic reference's own Monte Carlo noise (" + std::to_string(B.eiaSpp) + " spp per EI pixel, " +
        std::to_string(B.viewSpp) + " spp per camera pixel), and the field's own error is what a " +
        std::to_string(B.iterations) + "-iteration CPU voxel grid reaches" +
        (o.quick ? " (quick form: bounds for its tiny budget)" : "") + ":\n\n";
  md += "| quantity | measured | bound | pass |\n|---|---|---|---|\n";
  for (const auto& v : rep.values) {
    const bool atLeast = v.name.find("PSNR") != std::string::npos;
    md += "| " + v.name + " | " + fmt(v.measured, 2) + " | " + (atLeast ? "≥ " : "≤ ") + fmt(v.predicted, 1) + " | " +
          (v.pass ? "yes" : "**no**") + " |\n";
  }
  md += "\n" + std::string(rep.pass ? "**PASS**: every quantity is within its bound."
                                    : "**FAIL**: a quantity is outside its bound.") +
        "\n\n";
  md += "**Reproduce.**\n\n```\n" + reproduceCommand(rep.study, o) + (o.quick ? "   # quick form (the CI test)" : "") +
        "\n```\n";
  {
    std::ofstream fo(out.add(mdPath));
    fo << md;
    if (!fo) throw std::runtime_error("cannot write " + mdPath);
  }
  out.commit();
  rep.files = {mdPath, pngPath, csvPath, stripPath};
  return rep;
}

}  // namespace inim
