// Ticks, tick labels and the default palette of plots.
#include "analysis/plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "analysis/plot_internal.h"

namespace inim {

double niceStep(double lo, double hi, int maxTicks) {
  const double span = hi - lo;
  if (!(span > 0.0) || !std::isfinite(span)) return 1.0;
  const double raw = span / std::max(maxTicks, 1);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * mag >= raw * (1.0 - 1e-12)) return m * mag;
  return 10.0 * mag;
}

std::vector<double> niceTicks(double lo, double hi, int maxTicks) {
  std::vector<double> t;
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) return t;
  const double step = niceStep(lo, hi, maxTicks);
  const double k0 = std::ceil(lo / step - 1e-9), k1 = std::floor(hi / step + 1e-9);
  for (double k = k0; k <= k1 && t.size() < 1000; k += 1.0) {
    double v = k * step;
    if (std::abs(v) < step * 1e-9) v = 0.0;
    t.push_back(v);
  }
  return t;
}

std::vector<double> logTicks(double lo, double hi) {
  std::vector<double> t;
  if (!(lo > 0.0) || !(hi > lo) || !std::isfinite(hi)) return t;
  const int d0 = int(std::ceil(std::log10(lo) - 1e-9)), d1 = int(std::floor(std::log10(hi) + 1e-9));
  if (d1 - d0 >= 2) {
    const int every = std::max(1, (d1 - d0 + 9) / 10);  // at most ~10 labelled decades
    for (int d = d0; d <= d1; d += every) t.push_back(std::pow(10.0, d));
    return t;
  }
  // Less than two decades: 1, 2, 5 x 10^k.
  for (int d = int(std::floor(std::log10(lo))) ; d <= int(std::ceil(std::log10(hi))); ++d)
    for (double m : {1.0, 2.0, 5.0}) {
      const double v = m * std::pow(10.0, d);
      if (v >= lo * (1.0 - 1e-9) && v <= hi * (1.0 + 1e-9)) t.push_back(v);
    }
  return t;
}

std::string formatTick(double v, double step) {
  char buf[48];
  if (v == 0.0) return "0";
  const double a = std::abs(v);
  if (a >= 1e6 || a < 1e-4) {
    std::snprintf(buf, sizeof buf, "%.3g", v);
    return buf;
  }
  int decimals = 0;
  step = std::abs(step);
  if (step > 0.0 && step < 1.0) decimals = std::min(6, int(std::ceil(-std::log10(step) - 1e-9)));
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

Vec3 plotPalette(int i) {
  static const Vec3 kTab10[] = {{0.122f, 0.467f, 0.706f}, {1.000f, 0.498f, 0.055f}, {0.173f, 0.627f, 0.173f},
                                {0.839f, 0.153f, 0.157f}, {0.580f, 0.404f, 0.741f}, {0.549f, 0.337f, 0.294f},
                                {0.890f, 0.467f, 0.761f}, {0.498f, 0.498f, 0.498f}, {0.737f, 0.741f, 0.133f},
                                {0.090f, 0.745f, 0.812f}};
  return kTab10[((i % 10) + 10) % 10];
}

namespace plotimpl {
std::string tickLabel(const std::vector<double>& ticks, bool log, double t) {
  return formatTick(t, log ? t : ticks.size() >= 2 ? ticks[1] - ticks[0] : 1.0);
}
std::string xTickLabel(const Plot& p, const PlotFrame& f, double t) {
  if (p.x.categories.empty()) return tickLabel(f.xTicks, f.logX, t);
  const long i = std::lround(t);
  return i >= 0 && size_t(i) < p.x.categories.size() ? p.x.categories[size_t(i)] : std::string();
}
}  // namespace plotimpl

}  // namespace inim
