// A tiny built-in bitmap font (3×5 cells a character) laid out as filled rectangles, for the
// window's status line and the film's HUD: the renderer has no text, and this needs no texture
// or shader.
#pragma once

#include <string_view>
#include <vector>

#include "render/rect.h"

namespace render {

/// Character cells a glyph spans: kGlyphColumns wide plus one blank column before the next.
inline constexpr int kGlyphColumns = 3;
inline constexpr int kGlyphRows = 5;

/// The rectangles that spell `text` with its top-left corner at (x, y), each cell `cell` pixels
/// square. Digits, A–Z (lower case is drawn as upper case), space and . : - / % ( ); any other
/// character is drawn as "?". Lit cells of a glyph row merge into one rectangle.
std::vector<FilledRect> LayoutText(std::string_view text, int x, int y, int cell, Color color);

/// The width in pixels LayoutText covers for `text` (no trailing gap).
int TextWidth(std::string_view text, int cell);

/// The panel colours of the window's status line and the film's HUD: light text on the dark of
/// the letterbox bars.
inline constexpr Color kPanelBackdrop{0x20, 0x23, 0x28};
inline constexpr Color kPanelText{0xf4, 0xf1, 0xea};

/// A line of text on a backdrop in the top-left corner, two cells in from the edges: the
/// backdrop first, then the glyphs.
std::vector<FilledRect> TextPanel(std::string_view text, int cell, Color backdrop, Color ink);

}  // namespace render
