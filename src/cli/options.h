#pragma once
// Option groups that several commands share, declared once: run options (seed, threads),
// the display and its EI layout, placement, real-lens rays; the rule "an option
// given on the command line, else the run file's value, else the default"; and the table that
// names a library setting by its flag when an error is printed.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "core/error.h"
#include "core/progress.h"
#include "core/settings_table.h"
#include "field/placement.h"
#include "runs/display_rays.h"
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

// The settings-table entry for `key` as this command reads it (std::logic_error when the table
// has none: every option is documented there).
const SettingInfo& settingFor(const CLI::App* cmd, std::string_view key);
// The entry's checks on an option: a number's range, a name's choices (each element of a list).
CLI::Option* withSettingChecks(CLI::Option* option, const SettingInfo& info);

template <class T> struct SettingType { static constexpr bool optional = false, list = false; };
template <class T> struct SettingType<std::optional<T>> { static constexpr bool optional = true, list = false; };
template <class T> struct SettingType<std::vector<T>> { static constexpr bool optional = false, list = true; };

// The option of the library setting `key`, written into `target`: its flag, help, range and
// choices from the settings table; a switch for a bool; a comma-separated list for a vector;
// the default shown from `target` unless the help says what it is. `alias` is a first flag
// name that the option also answers to (as --scene for --field).
template <class T>
CLI::Option* addSetting(CLI::App* cmd, std::string_view key, T& target, const std::string& alias = "") {
  const SettingInfo& info = settingFor(cmd, key);
  const std::string names = (alias.empty() ? "" : alias + ",") + settingFlag(key);
  if constexpr (std::is_same_v<T, bool>) {
    return cmd->add_flag(names, target, std::string(info.help));
  } else {
    using Type = SettingType<T>;
    CLI::Option* option = cmd->add_option(names, target, std::string(info.help));
    if constexpr (Type::list) option->delimiter(',');
    if (!Type::optional && info.help.find("default") == std::string_view::npos) option->capture_default_str();
    return withSettingChecks(option, info);
  }
}

// The option of setting `key` (flag and help from the settings table) that names one of
// `values` by the library's own name for it (nameOf), written into `target` (an enum, or an
// optional one: then absent means the library's choice); --help lists the names.
template <class E, class Target>
CLI::Option* addChoiceSetting(CLI::App* cmd, std::string_view key, Target& target, std::initializer_list<E> values,
                              const char* (*nameOf)(E)) {
  std::map<std::string, E> byName;
  std::string names;
  for (E v : values) byName[nameOf(v)] = v, names += std::string(names.empty() ? "" : ", ") + nameOf(v);
  CLI::Option* option = cmd->add_option(settingFlag(key), target, std::string(settingFor(cmd, key).help) + " (" +
                                                                      names + ")");
  if constexpr (std::is_same_v<Target, E>) option->default_str(nameOf(target));
  return option->transform(CLI::CheckedTransformer(byName).description(""));
}

// --display, --layout, --viewing-distance-mm.
using DisplayArgs = DisplayGiven;
void addDisplayOptions(CLI::App* cmd, DisplayArgs& a);
// The layout options given, over the run file's (resolveLayout).
inline LayoutOverride layoutOverride(const DisplayArgs& a, const RunFile* run = nullptr) {
  return resolveLayout(run, a.layout, a.viewingDistanceMm);
}

// --scale, --rotate-deg, --translate-mm.
struct PlacementArgs {
  std::string scale, rotate, translate;
};
void addPlacementOptions(CLI::App* cmd, PlacementArgs& a);
inline PlacementOverride placementOverride(const PlacementArgs& a) {
  return parsePlacementOverride(a.scale, a.rotate, a.translate);
}

// --chief-rays, --real-lens, --real-lens-ray, --wavelength-nm: resolveDisplayRays's arguments.
struct RealLensArgs {
  bool on = false;
  std::optional<std::string> chiefRays, model;
  std::optional<double> wavelengthNm;
  DisplayRayChoice resolve() const { return resolveDisplayRays(chiefRays, on, model, wavelengthNm); }
};
void addRealLensOptions(CLI::App* cmd, RealLensArgs& a);

// The flag that sets a library setting ("spp" -> "--spp", "vcp_mm" -> "--vcp-mm"); a key that
// no flag sets is returned as it is.
std::string flagForSetting(const std::string& key);
// The error as the command line reports it: a setting named by its flag. Errors about a file
// keep the file's own key, unless the file is the setting's value (an EIA that does not exist).
InputError asCommandLineError(const InputError& e);

}  // namespace inim::cli
