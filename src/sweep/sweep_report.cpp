#include "sweep/sweep_report.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "analysis/plot.h"
#include "core/format.h"
#include "core/output_file.h"
#include "sweep/sweep_point.h"
#include "sweep/sweep_slurm.h"

namespace inim {
namespace fs = std::filesystem;

namespace {

// The metrics plotted against each axis, with their titles.
const std::vector<std::pair<std::string, std::string>> kPlotted = {
    {"de_mean", "CIEDE2000, mean"}, {"de_p95", "CIEDE2000, 95th percentile"}, {"psnr_db", "PSNR (dB)"}, {"ssim", "SSIM"}};

std::optional<double> headline(const SweepTable& t, const SweepPoint& p, const std::string& metric = kSweepHeadlineMetric) {
  const SweepRow* r = t.row(p, t.firstPose);
  const int m = t.metric(metric);
  return r && m >= 0 ? r->metrics[m] : std::nullopt;
}

// The points that differ from `p` only in axis `a` (p's other values and choices held), by value.
std::vector<const SweepPoint*> alongAxis(const std::vector<SweepPoint>& points, const SweepPoint& p, size_t a) {
  std::vector<const SweepPoint*> line;
  for (const SweepPoint& q : points) {
    bool same = q.choices == p.choices;
    for (size_t k = 0; same && k < p.values.size(); ++k) same = k == a || q.values[k].second == p.values[k].second;
    if (same) line.push_back(&q);
  }
  std::sort(line.begin(), line.end(), [a](const SweepPoint* x, const SweepPoint* y) {
    return x->values[a].second < y->values[a].second;
  });
  return line;
}

std::string shortAxisName(const std::string& path) {
  std::string s;
  for (char c : path) s += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return s;
}

// Everything but axis a, as a label ("gap=4, layout=stripe").
std::string othersLabel(const SweepPoint& p, size_t a) {
  std::string s;
  for (const auto& [name, label] : p.choices) s += (s.empty() ? "" : ", ") + name + "=" + label;
  for (size_t k = 0; k < p.values.size(); ++k)
    if (k != a) s += (s.empty() ? "" : ", ") + p.values[k].first + "=" + formatNumber(p.values[k].second);
  return s;
}

Plot axisPlot(const SweepTable& t, const std::vector<SweepPoint>& points, size_t a, const std::string& metric,
              const std::string& title, const SweepPoint* best) {
  Plot plot;
  plot.title = title + " at " + t.firstPose + " against " + points[0].values[a].first;
  plot.x.title = points[0].values[a].first;
  plot.y.title = title;
  double lo = INFINITY, hi = -INFINITY;
  for (const SweepPoint& p : points) lo = std::min(lo, p.values[a].second), hi = std::max(hi, p.values[a].second);
  if (hi > lo) plot.x.min = lo - 0.05 * (hi - lo), plot.x.max = hi + 0.05 * (hi - lo);  // end markers not cut
  std::map<std::string, PlotSeries> groups;
  std::vector<std::string> order;
  for (const SweepPoint& p : points) {
    const auto v = headline(t, p, metric);
    if (!v) continue;
    const std::string key = othersLabel(p, a);
    if (!groups.count(key)) order.push_back(key), groups[key].name = key;
    groups[key].x.push_back(p.values[a].second);
    groups[key].y.push_back(*v);
  }
  for (const std::string& k : order) {
    PlotSeries s = groups[k];
    if (order.size() > 8 || s.name.empty()) s.name = "";
    plot.series.push_back(std::move(s));
  }
  if (best && headline(t, *best, metric)) {
    PlotSeries b;
    b.name = "best (" + std::string(kSweepHeadlineMetric) + ")";
    b.x = {best->values[a].second};
    b.y = {*headline(t, *best, metric)};
    b.line = false;
    b.marker = MarkerShape::Cross;
    b.markerRadius = 8;
    b.color = Vec3(0.8f, 0.1f, 0.1f);
    plot.series.push_back(std::move(b));
  }
  return plot;
}

// Uniform cell edges around sorted values (the heat map's cells are evenly spaced).
std::pair<double, double> cellRange(const std::vector<double>& v) {
  const double step = v.size() > 1 ? (v.back() - v.front()) / double(v.size() - 1) : 1.0;
  return {v.front() - step / 2, v.back() + step / 2};
}

std::optional<Plot> heatMapPlot(const SweepTable& t, const std::vector<SweepPoint>& points, const SweepPlan& plan,
                                const SweepPoint* best) {
  if (plan.zip || plan.axes.size() < 2 || !best) return std::nullopt;
  std::vector<double> xs = plan.axes[0].values, ys = plan.axes[1].values;
  std::sort(xs.begin(), xs.end());
  std::sort(ys.begin(), ys.end());
  Plot plot;
  plot.title = "CIEDE2000 mean at " + t.firstPose + " (other parameters as the best point's)";
  plot.x.title = plan.axes[0].path;
  plot.y.title = plan.axes[1].path;
  plot.legend = false;
  plot.grid = false;
  PlotHeatMap h;
  h.cols = int(xs.size());
  h.rows = int(ys.size());
  h.values.assign(size_t(h.cols) * h.rows, NAN);
  std::tie(h.x0, h.x1) = cellRange(xs);
  std::tie(h.y0, h.y1) = cellRange(ys);
  h.label = "CIEDE2000";
  for (const SweepPoint& p : points) {
    bool slice = p.choices == best->choices;
    for (size_t k = 2; slice && k < p.values.size(); ++k) slice = p.values[k].second == best->values[k].second;
    const auto v = headline(t, p);
    if (!slice || !v) continue;
    const int c = int(std::find(xs.begin(), xs.end(), p.values[0].second) - xs.begin());
    const int r = int(std::find(ys.begin(), ys.end(), p.values[1].second) - ys.begin());
    h.values[size_t(r) * h.cols + c] = *v;
    const double x = h.x0 + (c + 0.5) * (h.x1 - h.x0) / h.cols, y = h.y0 + (r + 0.5) * (h.y1 - h.y0) / h.rows;
    plot.texts.push_back({x, y, formatNumber(*v, "%.2f") + (&p == best ? " best" : ""),
                          &p == best ? Vec3(1.0f, 0.2f, 0.2f) : Vec3(1.0f, 1.0f, 1.0f), TextAnchorPoint::Centre});
  }
  plot.x.min = h.x0, plot.x.max = h.x1, plot.y.min = h.y0, plot.y.max = h.y1;
  plot.heatMap = std::move(h);
  return plot;
}

std::string numberCell(const std::optional<double>& v, const char* format = "%.3f") {
  return v ? formatNumber(*v, format) : "–";
}

std::string rankingSection(const SweepTable& t, const std::vector<SweepPoint>& points, const SweepPoint* best) {
  std::vector<const SweepPoint*> ranked;
  for (const SweepPoint& p : points)
    if (headline(t, p)) ranked.push_back(&p);
  std::stable_sort(ranked.begin(), ranked.end(),
                   [&](const SweepPoint* a, const SweepPoint* b) { return *headline(t, *a) < *headline(t, *b); });
  std::string s = "## Points, best first\n\nCIEDE2000 mean at " + t.firstPose + "; \"Δ best\" is the difference to the best ";
  s += t.noiseFloor ? "point, *not significant* when it is below the references' noise floor (" +
                          formatNumber(*t.noiseFloor, "%.2f") + ").\n\n"
                    : "point (the noise floor is unknown: run the sweep with \"budget\": true to measure it).\n\n";
  s += "| rank | point |";
  for (const auto& [name, label] : points[0].choices) s += " " + name + " |";
  for (const auto& [path, v] : points[0].values) s += " `" + path + "` |";
  s += " CIEDE2000 | p95 | PSNR | Δ best |\n|---|---|";
  for (size_t i = 0; i < points[0].choices.size() + points[0].values.size() + 4; ++i) s += "---|";
  s += "\n";
  const size_t shown = std::min<size_t>(ranked.size(), 20);
  for (size_t i = 0; i < shown; ++i) {
    const SweepPoint& p = *ranked[i];
    s += "| " + std::to_string(i + 1) + " | `" + p.id + "` |";
    for (const auto& [name, label] : p.choices) s += " " + label + " |";
    for (const auto& [path, v] : p.values) s += " " + formatNumber(v) + " |";
    const double d = *headline(t, p) - *headline(t, *best);
    s += " " + numberCell(headline(t, p)) + " | " + numberCell(headline(t, p, "de_p95")) + " | " +
         numberCell(headline(t, p, "psnr_db"), "%.2f") + " | " +
         (&p == best ? std::string("best")
                     : "+" + formatNumber(d, "%.3f") + (t.noiseFloor && d < *t.noiseFloor ? " (not significant)" : "")) +
         " |\n";
  }
  if (ranked.size() > shown) s += "\n" + std::to_string(ranked.size() - shown) + " more in results.csv.\n";
  return s + "\n";
}

std::string sensitivitySection(const std::vector<AxisSensitivity>& sens, const SweepTable& t) {
  if (sens.empty()) return "";
  std::string s = "## Sensitivity at the best point\n\nAlong each axis through the best point (the other parameters "
                  "held): the slope of the CIEDE2000 mean from the neighbouring points, and the range of the axis within "
                  "which it stays within " + formatNumber(kSweepToleranceDe) +
                  " CIEDE2000 of the best, the tolerance a build must hold. A range that reaches the sweep's end "
                  "(≥, ≤) may be wider.\n\n| axis | slope (CIEDE2000 per unit) | within 1 CIEDE2000 |\n|---|---|---|\n";
  for (const AxisSensitivity& a : sens) {
    const bool significant = !t.noiseFloor || std::abs(a.change) >= *t.noiseFloor;
    s += "| `" + a.axis + "` | " +
         (a.slopeKnown ? formatNumber(a.slope, "%.3g") + (significant ? "" : " (not significant)") : std::string("– (one value)")) +
         " | " +
         (a.loAtEnd ? "≤ " : "") + formatNumber(a.lo) + " to " + (a.hiAtEnd ? "≥ " : "") + formatNumber(a.hi) + " |\n";
  }
  if (t.noiseFloor)
    s += "\nA slope is *not significant* when the metric changes less than the noise floor (" +
         formatNumber(*t.noiseFloor, "%.2f") +
         ") between the points it is taken from. The floor is a conservative bound: points compared with the same "
         "references (here, those that share them) differ by less noise than two references do.\n";
  return s + "\n";
}

}  // namespace

const SweepPoint* bestSweepPoint(const SweepTable& t, const std::vector<SweepPoint>& points) {
  const SweepPoint* best = nullptr;
  for (const SweepPoint& p : points) {
    const auto v = headline(t, p);
    if (v && (!best || *v < *headline(t, *best))) best = &p;
  }
  return best;
}

std::vector<AxisSensitivity> sweepSensitivity(const SweepTable& t, const std::vector<SweepPoint>& points,
                                              const SweepPlan& plan) {
  std::vector<AxisSensitivity> out;
  const SweepPoint* best = bestSweepPoint(t, points);
  if (!best || plan.zip) return out;
  const double bestValue = *headline(t, *best);
  for (size_t a = 0; a < plan.axes.size(); ++a) {
    std::vector<const SweepPoint*> line;
    for (const SweepPoint* p : alongAxis(points, *best, a))
      if (headline(t, *p)) line.push_back(p);
    const size_t i = size_t(std::find(line.begin(), line.end(), best) - line.begin());
    AxisSensitivity s;
    s.axis = plan.axes[a].path;
    auto x = [&](size_t k) { return line[k]->values[a].second; };
    auto y = [&](size_t k) { return *headline(t, *line[k]); };
    if (line.size() > 1) {
      const size_t lo = i > 0 ? i - 1 : i, hi = i + 1 < line.size() ? i + 1 : i;
      s.slope = (y(hi) - y(lo)) / (x(hi) - x(lo));
      s.change = y(hi) - y(lo);
      s.slopeKnown = true;
    }
    size_t lo = i, hi = i;
    while (lo > 0 && y(lo - 1) - bestValue <= kSweepToleranceDe) --lo;
    while (hi + 1 < line.size() && y(hi + 1) - bestValue <= kSweepToleranceDe) ++hi;
    s.lo = x(lo), s.hi = x(hi);
    s.loAtEnd = lo == 0, s.hiAtEnd = hi + 1 == line.size();
    out.push_back(s);
  }
  return out;
}

void writeSweepReport(const std::string& sweepDir, const SweepPlan& plan, const std::vector<SweepPoint>& points,
                      const SweepTable& t, const std::string& program) {
  const fs::path dir(sweepDir);
  OutputSet out;
  writeTextFile(out.add((dir / "results.csv").string()), sweepTableCsv(t, points));
  writeTextFile(out.add((dir / "results.json").string()), sweepTableJson(t).dump(2) + "\n");
  const SweepPoint* best = bestSweepPoint(t, points);
  std::string figures;
  if (best) {
    for (size_t a = 0; a < plan.axes.size(); ++a)
      for (const auto& [metric, title] : kPlotted) {
        const std::string name = "plots/" + metric + "_vs_" + shortAxisName(plan.axes[a].path) + ".png";
        writePlot(axisPlot(t, points, a, metric, title, best), out.add((dir / name).string()));
        figures += "- [" + title + " against `" + plan.axes[a].path + "`](" + name + ")\n";
      }
    if (const auto heat = heatMapPlot(t, points, plan, best)) {
      writePlot(*heat, out.add((dir / "plots/heatmap.png").string()));
      figures = "- [Heat map: CIEDE2000 over `" + plan.axes[0].path + "` × `" + plan.axes[1].path +
                "`](plots/heatmap.png)\n" + figures;
    }
  }
  int ok = 0, failed = 0, missing = 0;
  std::vector<double> seconds;
  for (const SweepPointStatus& p : t.points) {
    ok += p.status == "ok", failed += p.status == "failed", missing += p.status == "missing";
    if (p.status == "ok") seconds.push_back(p.seconds);
  }
  std::sort(seconds.begin(), seconds.end());
  std::string r = "# Sweep report\n\n";
  r += std::to_string(points.size()) + " points (" + std::to_string(ok) + " ok, " + std::to_string(failed) + " failed, " +
       std::to_string(missing) + " not run), poses from " + (t.firstPose.empty() ? "–" : t.firstPose) +
       "; table: [results.csv](results.csv), [results.json](results.json); plan: [plan.json](plan.json).\n\n";
  const int refs = t.cached + t.rendered;
  if (!seconds.empty())
    r += "Per point: median " + formatNumber(seconds[seconds.size() / 2], "%.1f") + " s of wall time. References: " +
         std::to_string(t.rendered) + " rendered, " + std::to_string(t.cached) + " read from the sweep's cache (hit rate " +
         (refs ? formatNumber(100.0 * t.cached / refs, "%.0f") : std::string("–")) + " %).\n\n";
  std::string shared, own;
  for (const SweepAxis& a : plan.axes) (keyPathChangesReferences(a.path) ? own : shared) += " `" + a.path + "`";
  for (const SweepAlternative& a : plan.alternatives) {
    bool changes = false;
    for (const SweepOption& o : a.options) {
      changes = changes || !o.field.empty() || !o.camera.empty();
      for (const auto& [k, v] : o.set) changes = changes || keyPathChangesReferences(k);
    }
    (changes ? own : shared) += " " + a.name;
  }
  r += "Which parameters change the references (the scene itself through the camera): " +
       (own.empty() ? std::string("none;") : own + ";") + " shared by every value of:" +
       (shared.empty() ? std::string(" none") : shared) + ".\n\n";
  r += "Noise floor of the references (CIEDE2000 between two seeds at " + (t.firstPose.empty() ? "–" : t.firstPose) +
       "): " + (t.noiseFloor ? formatNumber(*t.noiseFloor, "%.2f") : std::string("not measured (no budget)")) + ".\n\n";
  if (best) {
    r += "## Best point\n\n`" + best->id + "`: " + othersLabel(*best, size_t(-1)) + ", CIEDE2000 mean " +
         numberCell(headline(t, *best)) + ". Re-run it alone: `" + sweepPointCommand(program, sweepDir, best->id) +
         "`.\n\n";
    r += rankingSection(t, points, best);
    r += sensitivitySection(sweepSensitivity(t, points, plan), t);
  }
  if (!figures.empty()) r += "## Figures\n\n" + figures + "\n";
  if (failed + missing > 0) {
    r += "## Points without results\n\n| point | status | error | log |\n|---|---|---|---|\n";
    for (const SweepPointStatus& p : t.points) {
      if (p.status == "ok") continue;
      std::string log = slurmLogOf(sweepDir, p.point->id);
      if (log.empty()) log = (fs::path(sweepPointDir(sweepDir, p.point->id)) / "log.txt").string();
      std::string err = p.error;
      std::replace(err.begin(), err.end(), '\n', ' ');
      std::replace(err.begin(), err.end(), '|', '/');
      r += "| `" + p.point->id + "` | " + p.status + " | " + err + " | " + log + " |\n";
    }
    r += "\n";
  }
  writeTextFile(out.add((dir / "report.md").string()), r);
  out.commit();
}

}  // namespace inim
