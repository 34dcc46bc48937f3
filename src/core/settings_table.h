#pragma once
// Every setting a user can give, in one table: its key (as run files and the library spell
// it; the command-line flag is "--" + the key with '-' for '_'), the range a number must lie in,
// the names a choice may take, and the one line that --help and docs/settings.md show. The
// defaults stay in the settings structs; this table says what is allowed and what it means.
// The ranges cover every real device by a wide margin: they catch typing slips and values
// (2^63, 1e308, NaN) that no display or camera has, before they reach any computation.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace inim {

// The scope of the keys in the JSON files (displays, cameras, lenses, scenes, run files,
// datasets): JsonObject checks every number it reads against the key's entry.
constexpr std::string_view kFileScope = "file";

struct SettingInfo {
  std::string_view key;
  std::string_view scope;    // "": every command; a command whose meaning differs ("fig11", "triads form"); kFileScope
  double lo, hi;             // numbers: the accepted range, ends included; NaN for text and switches
  std::string_view choices;  // choices: the allowed names, comma separated; else empty
  std::string_view help;
};

// The table, in the order docs/settings.md lists it.
const std::vector<SettingInfo>& settingsTable();
// The entry for `key` as `scope` (a command path) reads it: the scoped entry, else the general
// one; nullptr when the table has none.
const SettingInfo* findSetting(std::string_view key, std::string_view scope = "");
// "--" + key with '-' for '_' ("vcp_mm" -> "--vcp-mm").
std::string settingFlag(std::string_view key);
// Throws InputError(file, name, value, "<range>") when `value` is not a finite number in the
// entry's range. `name` is how the message names the setting (a flag, or a file's key path).
void checkSettingRange(const SettingInfo& info, double value, const std::string& file, const std::string& name);
// "a number in [lo, hi]", as messages and the docs print a range.
std::string rangeText(const SettingInfo& info);
// A value as text (a flag's): one of the entry's choices, or for a number, in its range (text
// that is not a number is left to the caller's conversion). InputError naming `name` otherwise.
void checkSettingText(const SettingInfo& info, const std::string& text, const std::string& name);
// What the entry allows, for --help: "a number in [lo, hi]", "{a,b,c}" or "".
std::string allowedText(const SettingInfo& info);
// The table as Markdown (docs/settings.md is this text; a test keeps them equal).
std::string settingsMarkdown();

}  // namespace inim
