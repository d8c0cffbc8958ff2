#include "cli/image_text.h"

#include <cctype>

namespace crowdbake::cli {
namespace {

// Rows top to bottom, 3 columns each, '#' lit.
struct Glyph {
  char c;
  const char* rows;  // 15 characters
};

constexpr Glyph kGlyphs[] = {
    {'0', "####.##.##.####"}, {'1', ".#.##..#..#.###"}, {'2', "###..#####..###"},
    {'3', "###..####..####"}, {'4', "#.##.####..#..#"}, {'5', "####..###..####"},
    {'6', "####..####.####"}, {'7', "###..#.#..#..#."}, {'8', "####.#####.####"},
    {'9', "####.####..####"}, {'A', ".#.#.#####.##.#"}, {'B', "##.#.###.#.###."},
    {'C', ".###..#..#...##"}, {'D', "##.#.##.##.###."}, {'E', "####..##.#..###"},
    {'F', "####..##.#..#.."}, {'G', ".###..#.##.#.##"}, {'H', "#.##.####.##.##"},
    {'I', "###.#..#..#.###"}, {'J', "..#..#..##.#.#."}, {'K', "#.##.###.#.##.#"},
    {'L', "#..#..#..#..###"}, {'M', "#.#####.##.##.#"}, {'N', "##.#.##.##.##.#"},
    {'O', ".#.#.##.##.#.#."}, {'P', "##.#.###.#..#.."}, {'Q', ".#.#.##.###..##"},
    {'R', "##.#.###.#.##.#"}, {'S', ".###...#...###."}, {'T', "###.#..#..#..#."},
    {'U', "#.##.##.##.####"}, {'V', "#.##.##.##.#.#."}, {'W', "#.##.########.#"},
    {'X', "#.##.#.#.#.##.#"}, {'Y', "#.##.#.#..#..#."}, {'Z', "###..#.#.#..###"},
    {' ', "..............."}, {'.', ".............#."}, {',', "..........#.#.."},
    {':', "....#.....#...."}, {'-', "......###......"}, {'_', "............###"},
    {'%', "#.#..#.#.#..#.#"}, {'/', "..#..#.#.#..#.."}, {'(', "..#.#..#..#...#"},
    {')', "#...#..#..#.#.."}, {'+', "....#.###.#...."}, {'=', "...###...###..."},
    {'#', "#.#####.#####.#"}, {'|', ".#..#..#..#..#."}, {'?', "###..#.#.....#."},
};

const char* rows_of(char c) {
  const char upper = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  for (const Glyph& g : kGlyphs)
    if (g.c == upper) return g.rows;
  return rows_of('?');
}

void blend(RgbaImage& image, int32_t x, int32_t y, const std::array<uint8_t, 4>& c) {
  if (x < 0 || y < 0 || x >= static_cast<int32_t>(image.width) ||
      y >= static_cast<int32_t>(image.height))
    return;
  uint8_t* p = &image.rgba[(static_cast<size_t>(y) * image.width + static_cast<size_t>(x)) * 4];
  const uint32_t a = c[3];
  for (int k = 0; k < 3; ++k)
    p[k] = static_cast<uint8_t>((c[k] * a + p[k] * (255 - a) + 127) / 255);
}

}  // namespace

uint32_t text_width(const std::string& text, const TextStyle& style) {
  // note: 4 font pixels per glyph (3 + a gap), the last gap dropped, one pixel of box each side.
  const uint32_t glyphs = static_cast<uint32_t>(text.size());
  return style.scale * (glyphs == 0 ? 2 : 4 * glyphs + 1);
}

uint32_t text_height(const TextStyle& style) { return style.scale * 7; }

void draw_text(RgbaImage& image, int32_t x, int32_t y, const std::string& text,
               const TextStyle& style) {
  const int32_t s = static_cast<int32_t>(style.scale);
  if (style.box[3] > 0) {
    const int32_t w = static_cast<int32_t>(text_width(text, style));
    const int32_t h = static_cast<int32_t>(text_height(style));
    for (int32_t j = 0; j < h; ++j)
      for (int32_t i = 0; i < w; ++i) blend(image, x + i, y + j, style.box);
  }
  for (size_t g = 0; g < text.size(); ++g) {
    const char* rows = rows_of(text[g]);
    const int32_t left = x + s * (1 + 4 * static_cast<int32_t>(g));
    for (int32_t r = 0; r < 5; ++r)
      for (int32_t c = 0; c < 3; ++c) {
        if (rows[3 * r + c] != '#') continue;
        for (int32_t j = 0; j < s; ++j)
          for (int32_t i = 0; i < s; ++i)
            blend(image, left + s * c + i, y + s * (1 + r) + j, style.color);
      }
  }
}

}  // namespace crowdbake::cli
