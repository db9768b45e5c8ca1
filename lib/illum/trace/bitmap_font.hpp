#pragma once
// A 5 × 7 pixel font for the few words drawn into images (the ray-tree
// overlay's legend). Drawn from a table written here rather than from a font
// file, so that an image with text is the same on every machine and needs no
// font library. It has the lowercase letters, the digits, the space and
// ( ) : , . - = / + ? ; an uppercase letter is drawn as its lowercase one and
// any other character (a byte of a UTF-8 sequence included) as '?'.
#include <string_view>

#include "illum/core/image.hpp"

namespace illum {

inline constexpr int glyph_width = 5, glyph_height = 7, glyph_advance = 6;

// The width in pixels of `text` at `scale` (each font pixel a scale × scale
// square), without the gap after the last glyph.
int text_width(std::string_view text, int scale = 1);

// Draws `text` with its top-left corner at (x, y) (pixels, y down), clipped
// to the image. Throws std::invalid_argument for a scale below 1.
void draw_text(Image& image, int x, int y, std::string_view text, const Color& colour, int scale = 1);

}  // namespace illum
