#pragma once
// Comparison sheets: several rendered tiles (e.g. one per technique or setting) composed into one
// labelled image on a dark background, with a title line at the top and label lines under each
// tile, written as sheet-NNN.png (tone-mapped), sheet-NNN.exr (the tiles' linear values) and a
// sheet-NNN.json sidecar.
//
// Why the text is drawn through Dear ImGui's font atlas: a sheet needs a few lines of readable
// text on the CPU, without a GL context. Dear ImGui, which the editor already links, rasterizes
// TrueType fonts into an 8-bit coverage atlas (stb_truetype inside ImFontAtlas) and needs no
// ImGui context for that, so the sheet uses the atlas standalone and only copies glyph rectangles
// out of it: no font code of our own and no new dependency. The font is DejaVu Sans (Debian's
// fonts-dejavu-core), which covers Latin-1 and Greek ("ΔE", "·"); without it the sheet falls back
// to ImGui's built-in ProggyClean (ASCII and Latin-1), with "Δ" written as "d" and other missing
// characters as "?".

#include <filesystem>
#include <glm/ext/vector_int4.hpp>
#include <glm/ext/vector_uint3_sized.hpp>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

namespace candela {

struct SheetTile {
    int width = 0, height = 0;
    std::vector<unsigned char> display;  ///< sRGB8 RGB, rows top to bottom (tone-mapped).
    std::vector<float> linear;  ///< RGB float, rows top to bottom, W/(m2 sr); may be empty (zeros).
    std::vector<std::string> lines;  ///< Label lines drawn under the tile (UTF-8).
};

struct SheetImage {
    int width = 0, height = 0;
    std::vector<unsigned char> display;  ///< RGB8 sheet: background, title, tiles, labels.
    std::vector<float> linear;           ///< Same layout, tiles' linear values, 0 elsewhere.
    std::vector<glm::ivec4> tileRects;   ///< x, y, width, height of each tile, pixels, y down.
};

/// A font rasterized into a Dear ImGui atlas, drawn into RGB8 images on the CPU. Most code uses
/// the free functions below, which use standard(); tests build one from another file to exercise
/// the fallback.
class SheetFont {
  public:
    /// Loads the TrueType file at ttfPath at about 15 px; when it is missing or not a font, uses
    /// Dear ImGui's built-in font instead (isFallback()).
    explicit SheetFont(const std::filesystem::path& ttfPath);
    ~SheetFont();
    SheetFont(const SheetFont&) = delete;
    SheetFont& operator=(const SheetFont&) = delete;

    /// DejaVu Sans from fonts-dejavu-core, built on first use.
    static const SheetFont& standard();

    /// Whether the TrueType file could not be used and the built-in font stands in for it.
    bool isFallback() const;
    /// Height of a line of text, pixels: every glyph of the font lies within it.
    int lineHeight() const;
    /// Width of the text's ink and advance, pixels.
    int textWidth(const std::string& utf8) const;
    /// Draws UTF-8 text with its top-left at (x, y) into an RGB8 image (clipped to the image).
    void drawText(std::vector<unsigned char>& rgb, int width, int height, int x, int y,
                  const std::string& utf8, glm::u8vec3 colour) const;

  private:
    struct Atlas;
    std::unique_ptr<Atlas> mAtlas;
};

/// Text metrics of the sheet's font (SheetFont::standard()), pixels.
int sheetLineHeight();
int sheetTextWidth(const std::string& utf8);
/// Draws UTF-8 text with its top-left at (x, y) into an RGB8 image (clipped to the image).
void drawSheetText(std::vector<unsigned char>& rgb, int width, int height, int x, int y,
                   const std::string& utf8, glm::u8vec3 colour);

/// Tiles in `columns` columns, row-major, each followed by its label strip (as many lines as the
/// tile with the most lines), with an 8 px margin around and between cells, a title line at the
/// top (none when empty), dark grey background and light text. Tiles of different sizes are
/// placed in cells of the largest size (widened to the widest label), centred horizontally and
/// resting on their labels. Throws InputError when there are no tiles, columns < 1, or a tile's
/// buffers do not match its size.
SheetImage composeSheet(const std::vector<SheetTile>& tiles, int columns, const std::string& title);

struct SheetFiles {
    std::string png;   ///< Tone-mapped 8-bit sRGB.
    std::string exr;   ///< Linear values, W/(m2 sr).
    std::string json;  ///< Sidecar, written last (its presence means the other two are complete).
};

/// Writes the next free DIR/sheet-NNN.{png,exr,json} (dir created if needed): the PNG of display,
/// the EXR of linear, then the JSON sidecar (atomically): a copy of `sidecar` (an object or null)
/// with "png", "exr", "sheet_size" [w, h] and "tile_rects" [[x, y, w, h], ...] added. Throws
/// InputError naming the file or folder on any failure.
SheetFiles writeSheet(const std::filesystem::path& dir, const SheetImage& sheet,
                      const nlohmann::json& sidecar);

}  // namespace candela
