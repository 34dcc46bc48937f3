#include "cli/options.h"

#include <algorithm>
#include <charconv>
#include <map>
#include <set>
#include <stdexcept>

#include "core/parallel.h"

namespace inim::cli {

const SettingInfo& settingFor(const CLI::App* cmd, std::string_view key) {
  std::string scope;  // the command path below the program: "eia", "triads form"
  for (const CLI::App* app = cmd; app && app->get_parent(); app = app->get_parent())
    scope = app->get_name() + (scope.empty() ? "" : " " + scope);
  if (const SettingInfo* info = findSetting(key, scope)) return *info;
  throw std::logic_error("no settings-table entry for " + std::string(key) + " (" + scope + ")");
}

CLI::Option* withSettingChecks(CLI::Option* option, const SettingInfo& info) {
  if (!allowedText(info).empty())
    option->check(CLI::Validator(
        [&info, flag = option->get_name()](std::string& text) { return checkSettingText(info, text, flag), std::string(); },
        allowedText(info)));
  return option;
}

void addRunOptions(CLI::App* cmd, RunOptions& opts, std::function<void()> body) {
  addSetting(cmd, "seed", opts.seed)->check(CLI::Validator(
      [](std::string& text) {
        uint64_t v = 0;  // exactly a uint64: "-1" and 2^64 are errors, not wrapped
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
        if (ec != std::errc() || end != text.data() + text.size())
          throw InputError("", "--seed", text, "a whole number in [0, 18446744073709551615]");
        return std::string();
      },
      ""));
  addSetting(cmd, "threads", opts.threads);
  cmd->callback([&opts, body = std::move(body)] {
    ThreadLimit threads(opts.threads);
    body();
  });
}

void addDisplayOptions(CLI::App* cmd, DisplayArgs& a) {
  addSetting(cmd, "display", a.display);
  addSetting(cmd, "layout", a.layout);
  addSetting(cmd, "viewing_distance_mm", a.viewingDistanceMm);
}

void addPlacementOptions(CLI::App* cmd, PlacementArgs& a) {
  addSetting(cmd, "scale", a.scale);
  addSetting(cmd, "rotate_deg", a.rotate);
  addSetting(cmd, "translate_mm", a.translate);
}

void addRealLensOptions(CLI::App* cmd, RealLensArgs& a) {
  addSetting(cmd, "chief_rays", a.chiefRays);
  addSetting(cmd, "real_lens", a.on);
  addSetting(cmd, "real_lens_ray", a.model);
  addSetting(cmd, "wavelength_nm", a.wavelengthNm);
}

std::string flagForSetting(const std::string& key) {
  // Setting keys as the library and run files spell them: those in the settings table are their
  // flag in snake_case ("vcp_mm" -> "--vcp-mm"); the rest are named by flags of other names.
  static const std::map<std::string, std::string> kOtherFlags = {
      {"width/height", "--width/--height"}, {"panel_estimator", "--estimator"}, {"background_y", "--background"},
      {"cos_exponent", "--emission-cos-n"}, {"angle_deg", "--angle"}, {"hfov_deg", "--fov"},
      {"aperture_mm", "--aperture"}, {"focus_distance_mm", "--focus"}};
  if (auto it = kOtherFlags.find(key); it != kOtherFlags.end()) return it->second;
  for (const SettingInfo& s : settingsTable())
    if (s.key == key && s.scope != kFileScope) return settingFlag(key);
  return key;
}

InputError asCommandLineError(const InputError& e) {
  // An error about a file keeps the file's own key, unless the file is the setting's value or
  // the key is a setting that no file holds (how a dataset is split).
  static const std::set<std::string> kSettingsAboutAFile = {"holdout_every"};
  if (!e.file().empty() && e.value() != "\"" + e.file() + "\"" && !kSettingsAboutAFile.count(e.key())) return e;
  const std::string flag = flagForSetting(e.key());
  return flag == e.key() ? e : InputError(e.file(), flag, e.value(), e.expected());
}

}  // namespace inim::cli
