#include "runs/error_budget.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <optional>

#include "analysis/plot.h"
#include "colour_chain/chain_response.h"
#include "colour_chain/patch_sets.h"
#include "core/error.h"
#include "core/format.h"
#include "display_view/display_model.h"
#include "display_view/estimators/channel_response.h"
#include "display_view/estimators/quadrature_tables.h"
#include "display_view/view_image.h"
#include "display_view/view_renderer.h"

namespace inim {

namespace {

BudgetRung rung(std::string name, std::string label, bool sub, bool mla, bool glass, bool colour, bool cal = false) {
  const bool removal = name[0] == '-';
  return BudgetRung{std::move(name), std::move(label), sub, mla, glass, colour, cal, removal};
}

// Each panel pixel a uniform emitter of its R, G and B: three whole-pixel squares, one per
// channel (they overlap; each channel is looked up among its own polygons only).
SubpixelLayout uniformPixelLayout() {
  SubpixelLayout L;
  L.type = "custom";
  L.tileW = L.tileH = 1;
  L.fillFactor = 1.0;
  for (int c = 0; c < kNumPrimaries; ++c) L.subpixels.push_back({c, {{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}}});
  return L;
}

// What the observer sees of the display, in the camera RGB the reference gives an RGB field:
// XYZ through the inverse of the sensor's fitted camera RGB -> XYZ matrix.
Image observerAsCamera(const Image& whiteBalancedXyz, const CameraSensor& sensor) {
  const Vec3d white = d65WhiteXyz();
  return transformedRgb(whiteBalancedXyz, sensor.xyzToCameraRgb() * glm::dmat3(glm::dvec3(white.x, 0, 0),
                                                                               glm::dvec3(0, white.y, 0),
                                                                               glm::dvec3(0, 0, white.z)));
}

std::string skipReason(const BudgetScene& s, const BudgetRung& r) {
  if ((r.name == "+cover_glass" || r.name == "-cover_glass") && !s.display->panel.coverGlass)
    return "the panel has no cover glass";
  if (r.calibrated && !s.calibratedEia) return "no calibration given (--budget-calibration FILE)";
  return "";
}

bool hasLayer(const Display& d, StackLayer::Kind kind) {
  return d.stackTraced && d.stack &&
         std::any_of(d.stack->layers.begin(), d.stack->layers.end(), [&](const StackLayer& l) { return l.kind == kind; });
}

// The stack without the layers of `kind`: air of the same thickness, or nothing when thin.
void clearLayers(OpticalStack& s, StackLayer::Kind kind) {
  std::vector<StackLayer> kept;
  for (StackLayer l : s.layers) {
    if (l.kind == kind) {
      if (!(l.thicknessMm > 0.0)) continue;
      l.kind = StackLayer::Kind::Gap;
      l.material.clear();
    }
    kept.push_back(std::move(l));
  }
  s.layers = std::move(kept);
}

// A rung's display: the scene's, its panel's subpixels uniform pixels without the subpixel rung,
// its stack's sheets or walls air without their rungs.
Display rungDescription(const BudgetScene& s, const BudgetRung& r) {
  Display d = *s.display;
  if (!r.subpixels) d.panel.subpixels = uniformPixelLayout();
  if (d.stack && !r.apertures) clearLayers(*d.stack, StackLayer::Kind::Apertures);
  if (d.stack && !r.barriers) clearLayers(*d.stack, StackLayer::Kind::Barriers);
  return d;
}

// A rung's emitter settings; `drive`: the drive table of another emitter of the same EIA
// (PanelEmitter::driveTable), or null.
EmitterSettings rungEmitter(const BudgetRung& r, std::shared_ptr<const std::vector<float>> drive) {
  EmitterSettings emitter;
  emitter.coverGlass = r.coverGlass;
  emitter.drive = std::move(drive);
  return emitter;
}

const Image& rungEia(const BudgetScene& s, const BudgetRung& r) { return r.calibrated ? *s.calibratedEia : *s.eia; }

// The display model of a rung's optics and panel (`drive`: as rungEmitter's).
DisplayModel rungDisplay(const BudgetScene& s, const BudgetRung& r,
                         std::shared_ptr<const std::vector<float>> drive = nullptr) {
  return makeDisplayModel(rungDescription(s, r), *s.layout, rungEia(s, r), "(EIA)",
                          r.realMla ? MlaKind::Real : MlaKind::Ideal, s.gapMm, rungEmitter(r, std::move(drive)));
}

// A rung's optics (what its panels are seen through).
std::string opticsKey(const BudgetRung& r) {
  return std::string(r.realMla ? "r" : "i") + (r.realMla && !r.apertures ? "-a" : "") +
         (r.realMla && !r.barriers ? "-b" : "") + (r.coverGlass ? "g" : "n");
}

// A rung's optics and panel (what a render depends on besides the sensor).
std::string geometryKey(const BudgetRung& r) {
  return std::string(r.subpixels ? "s" : "u") + opticsKey(r) + (r.calibrated ? "c" : "e");
}

bool isFullChain(const BudgetRung& r) {
  return r.subpixels && r.realMla && r.coverGlass && r.colourChain && !r.calibrated && r.apertures && r.barriers;
}

// The renders of one pose, each once: through the camera's sensor, and, for the rungs without
// the colour chain, through the observer (by sensorSwap when exact, else rendered). Rungs that
// share their optics and sensor are rendered in one pass (renderViews).
class RungRenders {
 public:
  RungRenders(const BudgetScene& s, const CameraModel& camera, const std::vector<MadeRungView>& made,
              std::shared_ptr<QuadratureTableCache> tables)
      : s_(s), camera_(camera), observer_(cieObserverSensor(s.camera->sensor.geometry())),
        tables_(tables ? std::move(tables) : std::make_shared<QuadratureTableCache>(camera)) {
    for (const MadeRungView& m : made)
      if (m.view) cameraViews_[geometryKey(m.rung)] = Render{*m.view, 0.0, m.note};
  }

  // Renders what `rungs` need and is not made yet, one pass per optics and sensor; each pass's
  // time goes to its first rung.
  void prepare(const std::vector<BudgetRung>& rungs) {
    std::map<std::string, std::vector<BudgetRung>> passes;
    for (const BudgetRung& r : rungs) {
      const bool camera = throughCamera(r);
      const std::string key = geometryKey(r);
      if ((camera ? cameraViews_ : observerViews_).count(key)) continue;
      std::vector<BudgetRung>& pass = passes[std::string(camera ? "camera " : "observer ") + opticsKey(r)];
      if (std::none_of(pass.begin(), pass.end(), [&](const BudgetRung& o) { return geometryKey(o) == key; }))
        pass.push_back(r);
    }
    for (const auto& [optics, pass] : passes) render(pass, optics[0] == 'c');
  }

  // The rung's linear view in camera RGB (prepared), with a note on how it was made and the
  // seconds of its render that no rung has taken yet.
  Image view(const BudgetRung& r, std::string& note, double& seconds) {
    Render& made = (throughCamera(r) ? cameraViews_ : observerViews_).at(geometryKey(r));
    seconds = made.seconds;
    made.seconds = 0.0;
    note = made.note;
    if (!throughCamera(r)) return observerAsCamera(made.image, s_.camera->sensor);
    if (r.colourChain) return made.image;
    note = (note.empty() ? "" : note + "; ") + "the render of the same optics through the camera, seen by the observer (exact 3 x 3)";
    // The matrix depends on the panel's primaries only (any rung's emitter gives it).
    if (!toObserver_) toObserver_ = sensorSwap(*display(r).panel, s_.camera->sensor, observer_);
    return observerAsCamera(transformedRgb(made.image, *toObserver_), s_.camera->sensor);
  }

 private:
  struct Render {
    Image image;
    double seconds = 0.0;
    std::string note;
  };

  bool throughCamera(const BudgetRung& r) const { return r.colourChain || sensorSwapIsExact(s_.view); }

  void render(const std::vector<BudgetRung>& pass, bool camera) {
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<DisplayModel> dms;
    std::vector<const PanelEmitter*> panels;
    for (const BudgetRung& r : pass) {
      dms.push_back(display(r));
      panels.push_back(dms.back().panel.get());
    }
    ViewSettings vs = s_.view;
    vs.progress = false;
    vs.tableCache = tables_;  // the rungs differ in the display only
    std::vector<ViewResult> views = renderViews(camera_, camera ? s_.camera->sensor : observer_, *dms[0].mla,
                                                panels, dms[0].area, vs);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    for (size_t k = 0; k < pass.size(); ++k)
      (camera ? cameraViews_ : observerViews_)[geometryKey(pass[k])] =
          Render{std::move(views[k].image), k == 0 ? seconds : 0.0,
                 views[k].carried ? "rendered in one pass with " + pass[0].name : ""};
  }

  // The rungs of one EIA read it into a drive table once.
  DisplayModel display(const BudgetRung& r) {
    std::shared_ptr<const std::vector<float>>& drive = drives_[r.calibrated];
    DisplayModel dm = rungDisplay(s_, r, drive);
    drive = dm.panel->driveTable();
    return dm;
  }

  const BudgetScene& s_;
  const CameraModel& camera_;
  const CameraSensor observer_;
  std::map<std::string, Render> cameraViews_, observerViews_;  // by geometryKey
  std::map<bool, std::shared_ptr<const std::vector<float>>> drives_;  // per EIA: calibrated or not
  std::optional<glm::dmat3> toObserver_;
  std::shared_ptr<QuadratureTableCache> tables_;
};

}  // namespace

// With one wavelength node per primary the node wavelengths depend on the panel only, so the
// sensor enters through ChannelResponse::channelRgb alone.
bool sensorSwapIsExact(const ViewSettings& vs) {
  return vs.panelEstimator == PanelEstimator::Quadrature && vs.wavelengthNodes == 1;
}

glm::dmat3 sensorSwap(const PanelEmitter& panel, const CameraSensor& from, const CameraSensor& to) {
  const ChannelResponse a(from, panel, false, SpectralSampling::Primaries), b(to, panel, false, SpectralSampling::Primaries);
  glm::dmat3 A, B;
  for (int c = 0; c < kNumPrimaries; ++c) A[c] = a.channelRgb(c), B[c] = b.channelRgb(c);
  return B * glm::inverse(A);
}

Image transformedRgb(const Image& img, const glm::dmat3& m) {
  Image out = img;
  const int n = out.numChannels();
  for (size_t i = 0; i < size_t(out.width) * size_t(out.height); ++i) {
    float* p = &out.data[i * size_t(n)];
    const Vec3d v = m * Vec3d(p[0], p[1], p[2]);
    p[0] = float(v.x), p[1] = float(v.y), p[2] = float(v.z);
  }
  return out;
}

std::vector<BudgetRung> budgetRungs(const Display* display) {
  std::vector<BudgetRung> ladder = {rung("ideal", "ideal display", false, false, false, false),
                                    rung("+subpixels", "+ subpixels", true, false, false, false),
                                    rung("+real_mla", "+ real MLA", true, true, false, false),
                                    rung("+cover_glass", "+ cover glass", true, true, true, false),
                                    rung("+colour_chain", "+ colour chain (full)", true, true, true, true),
                                    rung("+calibration", "+ calibration", true, true, true, true, true)};
  std::vector<BudgetRung> removals = {rung("-subpixels", "full - subpixels", false, true, true, true),
                                      rung("-real_mla", "full - real MLA", true, false, true, true),
                                      rung("-cover_glass", "full - cover glass", true, true, false, true),
                                      rung("-colour_chain", "full - colour chain", true, true, true, false)};
  const bool apertures = display && hasLayer(*display, StackLayer::Kind::Apertures);
  const bool barriers = display && hasLayer(*display, StackLayer::Kind::Barriers);
  if (!apertures && !barriers) {
    ladder.insert(ladder.end(), removals.begin(), removals.end());
    return ladder;
  }
  // The stack's sheets and walls, one kind per rung, after its refracting layers.
  ladder[2].label = "+ real MLA (lens arrays, plates)";
  ladder[2].apertures = !apertures, ladder[2].barriers = !barriers;
  auto at = ladder.begin() + 3;
  if (apertures) {
    at = ladder.insert(at, rung("+apertures", "+ aperture sheets", true, true, false, false)) + 1;
    at[-1].barriers = !barriers;
    removals.push_back(rung("-apertures", "full - aperture sheets", true, true, true, true));
    removals.back().apertures = false;
  }
  if (barriers) {
    ladder.insert(at, rung("+barriers", "+ barrier walls", true, true, false, false));
    removals.push_back(rung("-barriers", "full - barrier walls", true, true, true, true));
    removals.back().barriers = false;
  }
  ladder.insert(ladder.end(), removals.begin(), removals.end());
  return ladder;
}

BudgetRung fullChainRung() { return rung("full", "full chain", true, true, true, true); }

std::vector<RungPanel> fullChainCompanions(const BudgetScene& s, const std::vector<BudgetRung>& rungs, double gapMm,
                                           std::shared_ptr<const std::vector<float>> drive) {
  std::vector<RungPanel> out;
  const std::string full = geometryKey(fullChainRung());
  for (const BudgetRung& r : rungs) {
    if (!r.realMla || !r.coverGlass || !r.colourChain || geometryKey(r) == full || !skipReason(s, r).empty()) continue;
    if (std::any_of(out.begin(), out.end(), [&](const RungPanel& o) { return geometryKey(o.rung) == geometryKey(r); }))
      continue;
    out.push_back({r, std::make_unique<PanelEmitter>(rungDescription(s, r).panel, *s.layout, rungEia(s, r), "(EIA)",
                                                     gapMm, rungEmitter(r, r.calibrated ? nullptr : drive))});
  }
  return out;
}

std::vector<BudgetRung> selectRungs(const std::vector<std::string>& names, const Display* display) {
  const std::vector<BudgetRung> all = budgetRungs(display);
  // The names any display may have (a stack's rungs are named before its display is loaded).
  std::vector<std::string> valid;
  for (const BudgetRung& r : budgetRungs()) valid.push_back(r.name);
  valid.insert(valid.end(), {"+apertures", "+barriers", "-apertures", "-barriers"});
  std::vector<BudgetRung> out;
  for (const std::string& n : names)
    if (std::find(valid.begin(), valid.end(), n) == valid.end()) {
      std::string list;
      for (const std::string& v : valid) list += (list.empty() ? "" : ", ") + v;
      throw InputError("", "budget_rungs", "\"" + n + "\"", "one of " + list);
    }
  for (const BudgetRung& r : all)
    if (std::find(names.begin(), names.end(), r.name) != names.end()) out.push_back(r);
  return out;
}

PoseBudget poseBudget(const BudgetScene& s, const CameraModel& camera, const Image& reference,
                      const Image& secondReference, double exposure, const PixelMask& mask,
                      const std::vector<BudgetRung>& rungs, const std::vector<MadeRungView>& made,
                      const Image* bandLimitedReference, std::shared_ptr<QuadratureTableCache> tables) {
  const CameraSensor& sensor = s.camera->sensor;
  const Image refSrgb = cameraRgbToSrgb(reference, sensor);
  CompareOptions copt;
  copt.spaceA = copt.spaceB = "srgb";
  PoseBudget b;
  b.noiseFloor = compareImages(refSrgb, cameraRgbToSrgb(secondReference, sensor), copt, &mask, "reference",
                               "reference (another seed)");
  std::optional<Image> limitedSrgb;
  if (bandLimitedReference) limitedSrgb = cameraRgbToSrgb(*bandLimitedReference, sensor);
  RungRenders renders(s, camera, made, std::move(tables));
  std::vector<BudgetRung> rendered;
  for (const BudgetRung& r : rungs)
    if (skipReason(s, r).empty()) rendered.push_back(r);
  renders.prepare(rendered);
  std::map<std::string, RungResult> sameConfiguration;  // "+cover_glass" is "-colour_chain"
  auto run = [&](const BudgetRung& r) {
    RungResult out;
    out.rung = r;
    out.note = skipReason(s, r);
    if (!out.note.empty()) return out.skipped = true, out;
    const auto t0 = std::chrono::steady_clock::now();
    const std::string key = geometryKey(r) + (r.colourChain ? "+" : "-");
    if (auto it = sameConfiguration.find(key); it != sameConfiguration.end()) {
      out = it->second;
      out.rung = r;
      out.seconds = 0.0;
      return out;
    }
    double renderSeconds = 0.0;
    const Image view = renders.view(r, out.note, renderSeconds);
    out.srgb = cameraRgbToSrgb(scaledImage(view, exposure), sensor);
    out.metrics = compareImages(refSrgb, out.srgb, copt, &mask, "reference", r.name);
    if (limitedSrgb)
      out.bandLimited = compareImages(*limitedSrgb, out.srgb, copt, &mask, "band-limited reference", r.name);
    out.seconds = renderSeconds + std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    sameConfiguration[key] = out;
    return out;
  };
  for (const BudgetRung& r : rungs) (r.removal ? b.removeOne : b.ladder).push_back(run(r));
  return b;
}

namespace {

Json rungJson(const RungResult& r, const RungResult* against) {
  Json j{{"rung", r.rung.name}, {"label", r.rung.label}, {"skipped", r.skipped}};
  if (r.skipped) return j["note"] = r.note, j;
  j["metrics"] = metricsJson(r.metrics);
  if (r.bandLimited) j["metrics_band_limited"] = metricsJson(*r.bandLimited);
  j["seconds"] = r.seconds;
  if (!r.note.empty()) j["note"] = r.note;
  if (against && !against->skipped)
    j["increment"] = {{"psnr_db", r.metrics.psnrDb - against->metrics.psnrDb},
                      {"ssim", r.metrics.ssim - against->metrics.ssim},
                      {"de2000_mean", r.metrics.deltaE.mean - against->metrics.deltaE.mean},
                      {"de2000_p95", r.metrics.deltaE.p95 - against->metrics.deltaE.p95}};
  return j;
}

const RungResult* fullChain(const PoseBudget& b) {
  for (const RungResult& r : b.ladder)
    if (isFullChain(r.rung)) return &r;
  return nullptr;
}

// The rung before r in the ladder that was not skipped.
const RungResult* previous(const PoseBudget& b, size_t i) {
  for (size_t k = i; k-- > 0;)
    if (!b.ladder[k].skipped) return &b.ladder[k];
  return nullptr;
}

}  // namespace

std::string budgetLine(const PoseBudget& b) {
  std::string s = "noise floor dE " + formatNumber(b.noiseFloor.deltaE.mean, "%.3f") + ";";
  for (const RungResult& r : b.ladder)
    if (!r.skipped) s += " " + r.rung.name + " " + formatNumber(r.metrics.deltaE.mean, "%.3f") + ";";
  if (const auto ok = idealWithinFloorOfFullChain(b)) s += std::string(" ideal <= full + floor: ") + (*ok ? "yes" : "NO");
  return s;
}

std::optional<bool> idealWithinFloorOfFullChain(const PoseBudget& b) {
  const RungResult* full = fullChain(b);
  for (const RungResult& r : b.ladder)
    if (r.rung.name == "ideal" && !r.skipped && full)
      return r.metrics.deltaE.mean <= full->metrics.deltaE.mean + b.noiseFloor.deltaE.mean;
  return std::nullopt;
}

Json poseBudgetJson(const PoseBudget& b) {
  Json j{{"noise_floor", metricsJson(b.noiseFloor)}, {"ladder", Json::array()}, {"remove_one", Json::array()}};
  if (const auto ok = idealWithinFloorOfFullChain(b)) j["ideal_within_noise_floor_of_full_chain"] = *ok;
  for (size_t i = 0; i < b.ladder.size(); ++i) j["ladder"].push_back(rungJson(b.ladder[i], previous(b, i)));
  for (const RungResult& r : b.removeOne) j["remove_one"].push_back(rungJson(r, fullChain(b)));
  return j;
}

std::vector<std::string> budgetCsvHeader() {
  return {"pose",      "kind",          "rung",          "psnr_db",
          "ssim",      "de2000_mean",   "de2000_p95",    "d_psnr_db",
          "d_de2000_mean", "band_limited_psnr_db", "band_limited_de2000_mean", "note"};
}

std::vector<std::vector<std::string>> budgetCsvRows(const PoseBudget& b) {
  auto f = [](double v) { return formatNumber(v, "%.4f"); };
  std::vector<std::vector<std::string>> rows;
  const ImageMetrics& n = b.noiseFloor;
  rows.push_back({b.pose, "floor", "noise_floor", f(n.psnrDb), f(n.ssim), f(n.deltaE.mean), f(n.deltaE.p95), "", "", "", "", ""});
  auto add = [&](const char* kind, const RungResult& r, const RungResult* against) {
    if (r.skipped) return rows.push_back({b.pose, kind, r.rung.name, "", "", "", "", "", "", "", "", r.note});
    const ImageMetrics& m = r.metrics;
    const bool inc = against && !against->skipped;
    rows.push_back({b.pose, kind, r.rung.name, f(m.psnrDb), f(m.ssim), f(m.deltaE.mean), f(m.deltaE.p95),
                    inc ? f(m.psnrDb - against->metrics.psnrDb) : "",
                    inc ? f(m.deltaE.mean - against->metrics.deltaE.mean) : "",
                    r.bandLimited ? f(r.bandLimited->psnrDb) : "", r.bandLimited ? f(r.bandLimited->deltaE.mean) : "",
                    r.note});
  };
  for (size_t i = 0; i < b.ladder.size(); ++i) add("ladder", b.ladder[i], previous(b, i));
  for (const RungResult& r : b.removeOne) add("remove", r, fullChain(b));
  return rows;
}

void writeBudgetPlot(const std::vector<PoseBudget>& budgets, const std::vector<std::string>& labels,
                     const std::string& path) {
  if (budgets.empty()) return;
  Plot p;
  p.width = 900, p.height = 520;
  p.title = "Error budget: mean CIEDE2000 against the reference, rung by rung (" + labels[0] + " bars)";
  p.y.title = "CIEDE2000 mean";
  const PoseBudget& first = budgets[0];
  double level = 0.0;
  for (size_t i = 0; i < first.ladder.size(); ++i) {
    p.x.categories.push_back(first.ladder[i].rung.label);
    const RungResult& r = first.ladder[i];
    if (r.skipped) continue;
    const double v = r.metrics.deltaE.mean, base = i == 0 ? 0.0 : level;
    // Light tints, so that the other poses' markers (their colours in depth_error.png) stand out.
    const Vec3 colour = i == 0 ? Vec3(0.72f) : v >= base ? Vec3(0.96f, 0.62f, 0.60f) : Vec3(0.62f, 0.85f, 0.60f);
    PlotBars bar{"", {double(i)}, {v}, 0.6, base, colour};
    p.bars.push_back(bar);
    level = v;
  }
  for (size_t k = 1; k < budgets.size(); ++k) {
    PlotSeries s{labels[k], {}, {}};
    s.color = plotPalette(int(k));  // pose k's colour in depth_error.png (0 is the bars here)
    s.line = false;
    s.markerRadius = 5.0;
    for (size_t i = 0; i < budgets[k].ladder.size(); ++i)
      if (!budgets[k].ladder[i].skipped) s.x.push_back(double(i)), s.y.push_back(budgets[k].ladder[i].metrics.deltaE.mean);
    p.series.push_back(s);
  }
  p.hMarkers.push_back({first.noiseFloor.deltaE.mean, "noise floor (" + labels[0] + ")", Vec3(0.3f), 6.0});
  p.y.min = 0.0;
  writePlot(p, path);
}

}  // namespace inim
