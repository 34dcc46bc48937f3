#pragma once
// Option groups that several commands share, declared once: run options (seed, threads),
// the display and its EI layout, placement, real-lens rays; the rule "an option
// given on the command line, else the run file's value, else the default"; and the table that
// names a library setting by its flag when an error is printed.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <map>
#include <optional>
#include <string>

#include "core/error.h"
#include "field/placement.h"
#include "mla_optics/real_lens_rays.h"
#include "display/layout_override.h"
#include "runs/run_file.h"

namespace inim::cli {

// --seed and --threads. `body` is the command: it runs with the thread limit in force.
struct RunOptions {
  std::optional<uint64_t> seed;  // absent: the run file's, else the library's default
  int threads = 0;               // 0 = all cores
  // The seed given, over `seed` (a library setting at its default).
  void applySeed(uint64_t& target) const { resolveSetting(target, std::nullopt, seed); }
};
void addRunOptions(CLI::App* cmd, RunOptions& opts, std::function<void()> body);

// An option's value as given on the command line; none when it was not.
template <class T>
std::optional<T> givenValue(const CLI::Option* option, const T& value) {
  return option && option->count() ? std::optional<T>(value) : std::nullopt;
}

// An option that names one of `values` by the library's own name for it (nameOf), written
// into `target` (an enum, or an optional one); --help lists the names.
template <class E, class Target>
CLI::Option* addChoiceOption(CLI::App* cmd, const std::string& flag, Target& target, std::initializer_list<E> values,
                             const char* (*nameOf)(E), const std::string& help) {
  std::map<std::string, E> byName;
  std::string names;
  for (E v : values) byName[nameOf(v)] = v, names += std::string(names.empty() ? "" : ", ") + nameOf(v);
  return cmd->add_option(flag, target, help + " (" + names + ")")
      ->transform(CLI::CheckedTransformer(byName).description(""));
}

// --display, --layout, --viewing-distance-mm.
struct DisplayArgs {
  std::string display, layout;
  double viewingDistanceMm = 0.0;
  CLI::Option *displayOpt = nullptr, *layoutOpt = nullptr, *distanceOpt = nullptr;
};
void addDisplayOptions(CLI::App* cmd, DisplayArgs& a);
// The layout options given on the command line, else the run file's.
LayoutOverride layoutOverride(const DisplayArgs& a, const RunFile* run = nullptr);

// --scale, --rotate-deg, --translate-mm.
struct PlacementArgs {
  std::string scale, rotate, translate;
};
void addPlacementOptions(CLI::App* cmd, PlacementArgs& a);
PlacementOverride placementOverride(const PlacementArgs& a);

// --real-lens, --real-lens-ray, --wavelength-nm.
struct RealLensArgs {
  bool on = false;
  std::string model = "centroid";
  double wavelengthNm = kLambdaDNm;
  CLI::Option *onOpt = nullptr, *modelOpt = nullptr, *wavelengthOpt = nullptr;
};
void addRealLensOptions(CLI::App* cmd, RealLensArgs& a, const std::string& help);
// The options checked (InputError naming the option when one is given without --real-lens).
RealLensRayOptions realLensRayOptions(const RealLensArgs& a);

// Wall-clock seconds since `start`, for the times the commands print.
inline double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The flag that sets a library setting ("spp" -> "--spp", "vcp_mm" -> "--vcp-mm"); a key that
// no flag sets is returned as it is.
std::string flagForSetting(const std::string& key);
// The error as the command line reports it: a setting named by its flag. Errors about a file
// keep the file's own key, unless the file is the setting's value (an EIA that does not exist).
InputError asCommandLineError(const InputError& e);

}  // namespace inim::cli
