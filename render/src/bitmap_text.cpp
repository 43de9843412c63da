// The 3×5 font as rows of '#' and '.', and its layout into merged rectangles.
#include "render/bitmap_text.h"

#include <array>
#include <cctype>

namespace render {
namespace {

struct Glyph {
  char c;
  std::array<const char*, kGlyphRows> rows;
};

constexpr Glyph kFont[] = {
    {'0', {"###", "#.#", "#.#", "#.#", "###"}}, {'1', {".#.", "##.", ".#.", ".#.", "###"}},
    {'2', {"###", "..#", "###", "#..", "###"}}, {'3', {"###", "..#", ".##", "..#", "###"}},
    {'4', {"#.#", "#.#", "###", "..#", "..#"}}, {'5', {"###", "#..", "###", "..#", "###"}},
    {'6', {"###", "#..", "###", "#.#", "###"}}, {'7', {"###", "..#", "..#", ".#.", ".#."}},
    {'8', {"###", "#.#", "###", "#.#", "###"}}, {'9', {"###", "#.#", "###", "..#", "###"}},
    {'A', {".#.", "#.#", "###", "#.#", "#.#"}}, {'B', {"##.", "#.#", "##.", "#.#", "##."}},
    {'C', {".##", "#..", "#..", "#..", ".##"}}, {'D', {"##.", "#.#", "#.#", "#.#", "##."}},
    {'E', {"###", "#..", "##.", "#..", "###"}}, {'F', {"###", "#..", "##.", "#..", "#.."}},
    {'G', {".##", "#..", "#.#", "#.#", ".##"}}, {'H', {"#.#", "#.#", "###", "#.#", "#.#"}},
    {'I', {"###", ".#.", ".#.", ".#.", "###"}}, {'J', {"..#", "..#", "..#", "#.#", ".#."}},
    {'K', {"#.#", "#.#", "##.", "#.#", "#.#"}}, {'L', {"#..", "#..", "#..", "#..", "###"}},
    {'M', {"#.#", "###", "###", "#.#", "#.#"}}, {'N', {"##.", "#.#", "#.#", "#.#", "#.#"}},
    {'O', {".#.", "#.#", "#.#", "#.#", ".#."}}, {'P', {"##.", "#.#", "##.", "#..", "#.."}},
    {'Q', {".#.", "#.#", "#.#", "##.", ".##"}}, {'R', {"##.", "#.#", "##.", "#.#", "#.#"}},
    {'S', {".##", "#..", ".#.", "..#", "##."}}, {'T', {"###", ".#.", ".#.", ".#.", ".#."}},
    {'U', {"#.#", "#.#", "#.#", "#.#", "###"}}, {'V', {"#.#", "#.#", "#.#", "#.#", ".#."}},
    {'W', {"#.#", "#.#", "###", "###", "#.#"}}, {'X', {"#.#", "#.#", ".#.", "#.#", "#.#"}},
    {'Y', {"#.#", "#.#", ".#.", ".#.", ".#."}}, {'Z', {"###", "..#", ".#.", "#..", "###"}},
    {' ', {"...", "...", "...", "...", "..."}}, {'.', {"...", "...", "...", "...", ".#."}},
    {':', {"...", ".#.", "...", ".#.", "..."}}, {'-', {"...", "...", "###", "...", "..."}},
    {'/', {"..#", "..#", ".#.", "#..", "#.."}}, {'%', {"#.#", "..#", ".#.", "#..", "#.#"}},
    {'(', {"..#", ".#.", ".#.", ".#.", "..#"}}, {')', {"#..", ".#.", ".#.", ".#.", "#.."}},
    {'?', {"##.", "..#", ".#.", "...", ".#."}},
};

const Glyph& GlyphFor(char c) {
  const char upper = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  for (const Glyph& glyph : kFont) {
    if (glyph.c == upper) return glyph;
  }
  return kFont[std::size(kFont) - 1];  // '?'
}

}  // namespace

std::vector<FilledRect> LayoutText(std::string_view text, int x, int y, int cell, Color color) {
  std::vector<FilledRect> rects;
  const int advance = (kGlyphColumns + 1) * cell;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const Glyph& glyph = GlyphFor(text[i]);
    const int left = x + static_cast<int>(i) * advance;
    for (int row = 0; row < kGlyphRows; ++row) {
      const char* bits = glyph.rows[row];
      for (int column = 0; column < kGlyphColumns;) {
        if (bits[column] != '#') {
          ++column;
          continue;
        }
        int end = column;
        while (end < kGlyphColumns && bits[end] == '#') ++end;
        rects.push_back({{left + column * cell, y + row * cell, (end - column) * cell, cell}, color});
        column = end;
      }
    }
  }
  return rects;
}

int TextWidth(std::string_view text, int cell) {
  if (text.empty()) return 0;
  return static_cast<int>(text.size()) * (kGlyphColumns + 1) * cell - cell;
}

std::vector<FilledRect> TextPanel(std::string_view text, int cell, Color backdrop, Color ink) {
  const int pad = 2 * cell;
  std::vector<FilledRect> panel;
  panel.push_back({{pad, pad, TextWidth(text, cell) + 2 * pad, kGlyphRows * cell + 2 * pad}, backdrop});
  for (const FilledRect& r : LayoutText(text, 2 * pad, 2 * pad, cell, ink)) panel.push_back(r);
  return panel;
}

}  // namespace render
