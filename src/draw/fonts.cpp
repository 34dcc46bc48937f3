#include "draw/fonts.h"

#include <fontconfig/fontconfig.h>
#include <pango/pangofc-fontmap.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <vector>

namespace inim::draw {

namespace {

constexpr const char* kFamily = "DejaVu Sans";
constexpr const char* kFiles[] = {"DejaVuSans.ttf", "DejaVuSans-Bold.ttf"};

// Where the system's fontconfig has the DejaVu Sans files (a non-Debian layout).
std::vector<std::string> filesFromFontconfig() {
  std::vector<std::string> found;
  FcConfig* sys = FcInitLoadConfigAndFonts();
  if (!sys) return found;
  FcPattern* pat = FcPatternCreate();
  FcPatternAddString(pat, FC_FAMILY, reinterpret_cast<const FcChar8*>(kFamily));
  FcObjectSet* os = FcObjectSetBuild(FC_FILE, nullptr);
  if (FcFontSet* fs = FcFontList(sys, pat, os)) {
    for (const char* name : kFiles)
      for (int i = 0; i < fs->nfont; ++i) {
        FcChar8* file = nullptr;
        if (FcPatternGetString(fs->fonts[i], FC_FILE, 0, &file) == FcResultMatch &&
            std::filesystem::path(reinterpret_cast<const char*>(file)).filename() == name) {
          found.push_back(reinterpret_cast<const char*>(file));
          break;
        }
      }
    FcFontSetDestroy(fs);
  }
  FcObjectSetDestroy(os);
  FcPatternDestroy(pat);
  FcConfigDestroy(sys);
  return found;
}

std::vector<std::string> findFontFiles() {
  // Debian's place first (fonts-dejavu-core); the system's font configuration otherwise.
  std::vector<std::string> files;
  for (const char* name : kFiles) {
    const std::filesystem::path p = std::filesystem::path("/usr/share/fonts/truetype/dejavu") / name;
    if (std::filesystem::exists(p)) files.push_back(p.string());
  }
  if (files.empty()) files = filesFromFontconfig();
  if (files.empty() || std::filesystem::path(files[0]).filename() != kFiles[0])
    throw std::runtime_error("the font DejaVu Sans (DejaVuSans.ttf) is not installed: install the Debian package "
                             "fonts-dejavu-core (scripts/setup.sh does)");
  return files;
}

// A font map over a private fontconfig configuration holding only the DejaVu Sans files.
PangoFontMap* makeFontMap() {
  FcConfig* config = FcConfigCreate();
  for (const std::string& f : fontFiles())
    if (!FcConfigAppFontAddFile(config, reinterpret_cast<const FcChar8*>(f.c_str())))
      throw std::runtime_error("cannot load the font file " + f);
  PangoFontMap* map = pango_cairo_font_map_new_for_font_type(CAIRO_FONT_TYPE_FT);
  if (!map) throw std::runtime_error("Pango has no FreeType font map");
  pango_fc_font_map_set_config(PANGO_FC_FONT_MAP(map), config);
  FcConfigDestroy(config);  // the font map keeps its own reference
  return map;
}

// Fixed rendering: greyscale antialiasing, slight (vertical-only) hinting, whole-pixel advances.
cairo_font_options_t* makeFontOptions() {
  cairo_font_options_t* o = cairo_font_options_create();
  cairo_font_options_set_antialias(o, CAIRO_ANTIALIAS_GRAY);
  cairo_font_options_set_subpixel_order(o, CAIRO_SUBPIXEL_ORDER_DEFAULT);
  cairo_font_options_set_hint_style(o, CAIRO_HINT_STYLE_SLIGHT);
  cairo_font_options_set_hint_metrics(o, CAIRO_HINT_METRICS_ON);
  return o;
}

// Both live for the whole program (never freed: text may be drawn until exit).
PangoFontMap* fontMap() {
  static PangoFontMap* map = makeFontMap();
  return map;
}
const cairo_font_options_t* fontOptions() {
  static cairo_font_options_t* o = makeFontOptions();
  return o;
}

}  // namespace

const std::vector<std::string>& fontFiles() {
  static const std::vector<std::string> files = findFontFiles();
  return files;
}

namespace detail {

std::unique_lock<std::mutex> textLock() {
  static std::mutex m;
  return std::unique_lock<std::mutex>(m);
}

PangoLayout* makeLayout(cairo_t* cr, const std::string& utf8, const Font& font) {
  PangoContext* ctx = pango_font_map_create_context(fontMap());
  pango_cairo_context_set_font_options(ctx, fontOptions());
  pango_context_set_language(ctx, pango_language_from_string("en"));
  pango_context_set_base_dir(ctx, PANGO_DIRECTION_LTR);
  if (cr) pango_cairo_update_context(cr, ctx);
  PangoLayout* layout = pango_layout_new(ctx);
  g_object_unref(ctx);  // the layout holds it

  PangoFontDescription* desc = pango_font_description_new();
  pango_font_description_set_family_static(desc, kFamily);
  pango_font_description_set_weight(desc, font.bold ? PANGO_WEIGHT_BOLD : PANGO_WEIGHT_NORMAL);
  pango_font_description_set_absolute_size(desc, std::max(font.size, 1.0) * PANGO_SCALE);
  pango_layout_set_font_description(layout, desc);
  pango_font_description_free(desc);

  gchar* valid = g_utf8_make_valid(utf8.data(), gssize(utf8.size()));  // bad bytes become U+FFFD
  pango_layout_set_text(layout, valid, -1);
  g_free(valid);
  return layout;
}

TextSize layoutSize(PangoLayout* layout) {
  PangoRectangle logical;
  pango_layout_get_extents(layout, nullptr, &logical);
  TextSize s;
  s.width = double(logical.width) / PANGO_SCALE;
  s.height = double(logical.height) / PANGO_SCALE;
  s.baseline = double(pango_layout_get_baseline(layout)) / PANGO_SCALE;
  s.missingGlyphs = pango_layout_get_unknown_glyphs_count(layout);
  return s;
}

}  // namespace detail
}  // namespace inim::draw
