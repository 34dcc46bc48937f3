#pragma once
// Internal to src/draw: the one Pango font map every text of the project goes through.
//
// It holds DejaVu Sans only, from a private fontconfig configuration (no user or system
// rules), with fixed rendering options (greyscale antialiasing, slight hinting, whole-pixel
// metrics) and a fixed language, so that text looks the same on every machine with the same
// library versions, whatever the user's fontconfig says. Pango's font map is shared, so every
// call into Pango holds textLock().
#include <cairo.h>
#include <pango/pangocairo.h>

#include <mutex>
#include <string>

#include "draw/text.h"

namespace inim::draw::detail {

// Held while Pango is used (layouts, measuring, showing).
std::unique_lock<std::mutex> textLock();

// A single-line layout of `utf8` in `font`, for drawing on `cr` (its transformation is taken
// into account), or for measuring when cr is null. The caller owns it (g_object_unref).
PangoLayout* makeLayout(cairo_t* cr, const std::string& utf8, const Font& font);

// The size of a layout, as measureText() reports it.
TextSize layoutSize(PangoLayout* layout);

}  // namespace inim::draw::detail
