// A 5×7 bitmap font for the labels of the `stex compare` figure: printable ASCII, drawn by hand
// for this project (one glyph per character, 7 rows of 5 bits, the high bit the left column).
#pragma once

#include <stochtex/image.h>

#include <array>
#include <string>

namespace stex_cli {

constexpr int kGlyphWidth = 5, kGlyphHeight = 7;

/// Width in pixels of `text` drawn at `scale` (each glyph kGlyphWidth + 1 columns, times scale).
int text_width(const std::string& text, int scale);

/// Draws `text` with its top-left corner at (x, y), each font pixel a scale×scale square
/// (clipped to the image). Characters outside printable ASCII draw as '?'.
void draw_text(stochtex::Image& image, int x, int y, const std::string& text, const std::array<float, 3>& colour,
               int scale);

/// The same, turned 90° anticlockwise (reading bottom to top), its top-left corner at (x, y)
/// after turning: for a vertical axis's label.
void draw_text_vertical(stochtex::Image& image, int x, int y, const std::string& text,
                        const std::array<float, 3>& colour, int scale);

}  // namespace stex_cli
