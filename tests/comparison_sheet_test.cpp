// Comparison sheets: tile placement (every pixel copied exactly), text drawn through Dear ImGui's
// font atlas (inside its box, under the right tile, Greek or its fallback), bad input, and the
// files written (names, PNG/EXR/JSON read back).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "renderer/ImageFile.h"
#include "report/ComparisonSheet.h"
#include "tests/TestUtil.h"
#include "util/Error.h"

namespace candela::ui {
namespace {

namespace fs = std::filesystem;

constexpr const char* kDejaVuSans = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

using test::inputError;

#define EXPECT_CONTAINS(text, part) \
    EXPECT_NE(std::string(text).find(part), std::string::npos) << "in: " << (text)

/// A solid tile: every pixel the same display and linear colour.
SheetTile solidTile(int w, int h, glm::u8vec3 display, glm::vec3 linear) {
    SheetTile t;
    t.width = w, t.height = h;
    for (int i = 0; i < w * h; ++i)
        for (int c = 0; c < 3; ++c) {
            t.display.push_back(display[c]);
            t.linear.push_back(linear[c]);
        }
    return t;
}

/// A tile whose every pixel differs from its neighbours (catches transposed or shifted copies).
SheetTile gradientTile(int w, int h) {
    SheetTile t;
    t.width = w, t.height = h;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            t.display.insert(t.display.end(), {static_cast<unsigned char>(x * 9),
                                               static_cast<unsigned char>(y * 5), 77});
            t.linear.insert(t.linear.end(), {0.1f * float(x), 0.01f * float(y) + 1e-3f, 7.25f});
        }
    return t;
}

bool inside(const glm::ivec4& r, int x, int y) {
    return x >= r.x && x < r.x + r.z && y >= r.y && y < r.y + r.w;
}

/// Checks rects (inside the sheet, disjoint, tile-sized) and every pixel of the sheet: display
/// and linear equal the tile's inside its rect (exact: a copy), linear is 0 outside all rects.
void expectTilesPlaced(const SheetImage& sheet, const std::vector<SheetTile>& tiles) {
    ASSERT_EQ(sheet.tileRects.size(), tiles.size());
    ASSERT_EQ(sheet.display.size(), size_t(sheet.width) * size_t(sheet.height) * 3);
    ASSERT_EQ(sheet.linear.size(), sheet.display.size());
    for (size_t i = 0; i < tiles.size(); ++i) {
        const glm::ivec4& r = sheet.tileRects[i];
        EXPECT_EQ(r.z, tiles[i].width);
        EXPECT_EQ(r.w, tiles[i].height);
        EXPECT_GE(r.x, 0);
        EXPECT_GE(r.y, 0);
        EXPECT_LE(r.x + r.z, sheet.width);
        EXPECT_LE(r.y + r.w, sheet.height);
        for (size_t j = 0; j < i; ++j) {
            const glm::ivec4& s = sheet.tileRects[j];
            bool disjoint =
                r.x + r.z <= s.x || s.x + s.z <= r.x || r.y + r.w <= s.y || s.y + s.w <= r.y;
            EXPECT_TRUE(disjoint) << "tiles " << j << " and " << i << " overlap";
        }
    }
    int wrong = 0;
    for (int y = 0; y < sheet.height; ++y)
        for (int x = 0; x < sheet.width; ++x) {
            size_t at = (size_t(y) * size_t(sheet.width) + size_t(x)) * 3;
            int tile = -1;
            for (size_t i = 0; i < tiles.size(); ++i)
                if (inside(sheet.tileRects[i], x, y)) tile = int(i);
            for (int c = 0; c < 3; ++c) {
                if (tile < 0) {
                    wrong += sheet.linear[at + size_t(c)] != 0.0f;
                    continue;
                }
                const SheetTile& t = tiles[size_t(tile)];
                const glm::ivec4& r = sheet.tileRects[size_t(tile)];
                size_t from = (size_t(y - r.y) * size_t(t.width) + size_t(x - r.x)) * 3 + size_t(c);
                wrong += sheet.display[at + size_t(c)] != t.display[from];
                wrong += sheet.linear[at + size_t(c)] != t.linear[from];
            }
        }
    EXPECT_EQ(wrong, 0) << "sheet values that differ from the tiles (or linear != 0 outside)";
}

std::vector<SheetTile> twoTiles() {
    std::vector<SheetTile> tiles = {solidTile(40, 30, {200, 30, 60}, {1.5f, 0.25f, 3.0f}),
                                    gradientTile(24, 50)};
    tiles[0].lines = {"Rasterized", "ΔE 0.52 · 3.1 ms"};
    tiles[1].lines = {"Reference"};
    return tiles;
}

TEST(ComparisonSheet, TwoColumnsPlaceTilesSideBySideExactly) {
    std::vector<SheetTile> tiles = twoTiles();
    SheetImage sheet = composeSheet(tiles, 2, "Comparison");
    expectTilesPlaced(sheet, tiles);
    const glm::ivec4 &a = sheet.tileRects[0], &b = sheet.tileRects[1];
    EXPECT_GE(b.x, a.x + a.z + 8) << "side by side with a margin";
    EXPECT_EQ(a.y + a.w, b.y + b.w) << "tiles of one row rest on the same label line";
}

TEST(ComparisonSheet, OneColumnStacksTilesExactly) {
    std::vector<SheetTile> tiles = twoTiles();
    tiles[1].linear.clear();  // no linear values: zeros in the sheet
    SheetImage sheet = composeSheet(tiles, 1, "");
    tiles[1].linear.assign(tiles[1].display.size(), 0.0f);
    expectTilesPlaced(sheet, tiles);
    const glm::ivec4 &a = sheet.tileRects[0], &b = sheet.tileRects[1];
    // The second row starts below the first tile's two label lines.
    EXPECT_GE(b.y, a.y + a.w + 2 * sheetLineHeight());
    // More columns than tiles: one row of two cells, like two columns.
    SheetImage wide = composeSheet(tiles, 5, "");
    EXPECT_EQ(wide.tileRects[0].y + wide.tileRects[0].w, wide.tileRects[1].y + wide.tileRects[1].w);
    EXPECT_EQ(wide.width, composeSheet(tiles, 2, "").width);
}

TEST(ComparisonSheet, TextStaysInsideItsBoxAndDrawsSomething) {
    const int w = 220, h = 60, x = 13, y = 17;
    std::vector<unsigned char> image(size_t(w) * h * 3, 0);
    const std::string text = "Technique";
    int textWidth = sheetTextWidth(text), lineHeight = sheetLineHeight();
    ASSERT_GT(textWidth, 0);
    ASSERT_GT(lineHeight, 0);
    ASSERT_LE(x + textWidth, w);
    drawSheetText(image, w, h, x, y, text, {255, 255, 255});
    int changedInside = 0, changedOutside = 0;
    for (int py = 0; py < h; ++py)
        for (int px = 0; px < w; ++px) {
            size_t at = (size_t(py) * w + size_t(px)) * 3;
            bool changed = image[at] || image[at + 1] || image[at + 2];
            bool inBox = px >= x && px < x + textWidth && py >= y && py < y + lineHeight;
            (inBox ? changedInside : changedOutside) += changed;
        }
    EXPECT_EQ(changedOutside, 0);
    // Nine glyphs at ~15 px cover well over 50 pixels; zero would mean nothing was drawn.
    EXPECT_GT(changedInside, 50);

    EXPECT_GT(sheetTextWidth("W"), 0);
    EXPECT_GT(sheetTextWidth("WW"), sheetTextWidth("W"));
    EXPECT_EQ(sheetTextWidth(""), 0);
    EXPECT_GT(sheetTextWidth("\xff"), 0) << "malformed UTF-8 draws a stand-in, not nothing";
}

TEST(ComparisonSheet, TextIsClippedToTheImage) {
    const int w = 30, h = 10;
    std::vector<unsigned char> image(size_t(w) * h * 3, 0);
    drawSheetText(image, w, h, -7, -4, "Clipped text", {255, 255, 255});
    drawSheetText(image, w, h, 25, 6, "Clipped text", {255, 255, 255});
    EXPECT_EQ(image.size(), size_t(w) * h * 3);  // no write past the end (ASan checks the rest)
}

/// Number of pixels in [x0, x1) x [y0, y1) that differ from the background colour.
int countNonBackground(const SheetImage& sheet, int x0, int x1, int y0, int y1,
                       glm::u8vec3 background) {
    int count = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            size_t at = (size_t(y) * size_t(sheet.width) + size_t(x)) * 3;
            count += glm::u8vec3(sheet.display[at], sheet.display[at + 1], sheet.display[at + 2]) !=
                     background;
        }
    return count;
}

TEST(ComparisonSheet, LabelsAndTitleAreDrawnWhereTheyBelong) {
    std::vector<SheetTile> tiles = {solidTile(96, 40, {250, 250, 250}, {1, 1, 1}),
                                    solidTile(96, 40, {250, 250, 250}, {1, 1, 1})};
    tiles[0].lines = {"Rasterized", "ΔE 0.52"};  // tile 1 has no labels
    SheetImage sheet = composeSheet(tiles, 2, "Title");
    glm::u8vec3 background(sheet.display[0], sheet.display[1], sheet.display[2]);
    int strip = 2 * sheetLineHeight() + 8;  // two lines plus a few pixels of gap
    for (int i = 0; i < 2; ++i) {
        const glm::ivec4& r = sheet.tileRects[size_t(i)];
        ASSERT_LE(r.y + r.w + strip, sheet.height);
        int drawn =
            countNonBackground(sheet, r.x, r.x + r.z, r.y + r.w, r.y + r.w + strip, background);
        if (i == 0)
            EXPECT_GT(drawn, 20) << "labels under tile 0";
        else
            EXPECT_EQ(drawn, 0) << "tile 1 has no labels";
    }
    int top = sheet.tileRects[0].y;
    EXPECT_GT(countNonBackground(sheet, 0, sheet.width, 0, top, background), 10) << "title";
    SheetImage untitled = composeSheet(tiles, 2, "");
    EXPECT_EQ(
        countNonBackground(untitled, 0, untitled.width, 0, untitled.tileRects[0].y, background), 0);
    EXPECT_LT(untitled.tileRects[0].y, top);
}

/// Pixels drawn by `text` in white on black, as an image.
std::vector<unsigned char> drawn(const SheetFont& font, const std::string& text) {
    std::vector<unsigned char> image(80 * 30 * 3, 0);
    font.drawText(image, 80, 30, 2, 2, text, {255, 255, 255});
    return image;
}

bool anyDrawn(const std::vector<unsigned char>& image) {
    for (unsigned char v : image)
        if (v) return true;
    return false;
}

TEST(ComparisonSheet, GreekRendersWithEitherFont) {
    const SheetFont& font = SheetFont::standard();
    EXPECT_GT(sheetTextWidth("ΔE"), 0);
    EXPECT_TRUE(anyDrawn(drawn(font, "ΔE")));
    EXPECT_TRUE(anyDrawn(drawn(font, "·")));
    if (fs::exists(kDejaVuSans)) {
        EXPECT_FALSE(font.isFallback());
        // A real Delta, neither the '?' of a missing glyph nor the fallback's 'd'.
        EXPECT_NE(drawn(font, "ΔE"), drawn(font, "?E"));
        EXPECT_NE(drawn(font, "ΔE"), drawn(font, "dE"));
    }

    // Without the font file: Dear ImGui's built-in font, "ΔE" written as "dE".
    SheetFont fallback("/nonexistent/DejaVuSans.ttf");
    EXPECT_TRUE(fallback.isFallback());
    EXPECT_GT(fallback.lineHeight(), 0);
    EXPECT_GT(fallback.textWidth("ΔE"), 0);
    EXPECT_EQ(fallback.textWidth("ΔE"), fallback.textWidth("dE"));
    EXPECT_TRUE(anyDrawn(drawn(fallback, "ΔE")));
    EXPECT_EQ(drawn(fallback, "ΔE"), drawn(fallback, "dE"));
    EXPECT_EQ(drawn(fallback, "ΔE 日"), drawn(fallback, "dE ?")) << "no stand-in: '?'";

    // A file that is not a font also falls back (Dear ImGui would assert on it).
    fs::path notFont =
        fs::temp_directory_path() / ("candela-sheet-notfont-" + std::to_string(getpid()));
    std::ofstream(notFont) << std::string(4096, 'x');
    EXPECT_TRUE(SheetFont(notFont).isFallback());
    fs::remove(notFont);
}

TEST(ComparisonSheet, BadInputThrowsInputError) {
    std::vector<SheetTile> tiles = twoTiles();
    EXPECT_CONTAINS(inputError([] { composeSheet({}, 2, "x"); }), "no tiles");
    EXPECT_CONTAINS(inputError([&] { composeSheet(tiles, 0, "x"); }), "columns");
    std::vector<SheetTile> shortDisplay = tiles;
    shortDisplay[1].display.pop_back();
    EXPECT_CONTAINS(inputError([&] { composeSheet(shortDisplay, 2, "x"); }), "tile 1");
    std::vector<SheetTile> shortLinear = tiles;
    shortLinear[0].linear.resize(3);
    EXPECT_CONTAINS(inputError([&] { composeSheet(shortLinear, 2, "x"); }), "linear");
    std::vector<SheetTile> empty = tiles;
    empty[0].width = 0;
    empty[0].display.clear();
    empty[0].linear.clear();
    EXPECT_CONTAINS(inputError([&] { composeSheet(empty, 2, "x"); }), "tile 0");
}

TEST(ComparisonSheet, WriteSheetWritesNumberedFilesThatReadBack) {
    fs::path dir = fs::temp_directory_path() / ("candela-sheet-test-" + std::to_string(getpid()));
    fs::remove_all(dir);
    SheetImage sheet = composeSheet(twoTiles(), 2, "Write test");
    nlohmann::json sidecar = {{"scene", "demo.json"}, {"techniques", {"a", "b"}}};

    SheetFiles first = writeSheet(dir / "sub", sheet, sidecar);
    SheetFiles second = writeSheet(dir / "sub", sheet, sidecar);
    EXPECT_EQ(fs::path(first.png).filename(), "sheet-000.png");
    EXPECT_EQ(fs::path(first.exr).filename(), "sheet-000.exr");
    EXPECT_EQ(fs::path(first.json).filename(), "sheet-000.json");
    EXPECT_EQ(fs::path(second.png).filename(), "sheet-001.png");
    EXPECT_EQ(fs::path(second.json).filename(), "sheet-001.json");

    int w = 0, h = 0;
    std::vector<float> png = readImageFloat(first.png, w, h);
    ASSERT_EQ(w, sheet.width);
    ASSERT_EQ(h, sheet.height);
    int wrong = 0;
    for (size_t i = 0; i < png.size(); ++i)  // 8-bit PNG: v / 255 back, exact after rounding
        wrong += int(std::lround(png[i] * 255.0f)) != int(sheet.display[i]);
    EXPECT_EQ(wrong, 0);

    std::vector<float> exr = readImageFloat(first.exr, w, h);
    ASSERT_EQ(w, sheet.width);
    ASSERT_EQ(h, sheet.height);
    ASSERT_EQ(exr.size(), sheet.linear.size());
    for (size_t i = 0; i < exr.size(); ++i)  // 32-bit float EXR: within 4 ulp (in fact exact)
        ASSERT_FLOAT_EQ(exr[i], sheet.linear[i]) << "value " << i;

    std::ifstream in(second.json);
    nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_EQ(j["scene"], "demo.json");
    EXPECT_EQ(j["techniques"].size(), 2u);
    EXPECT_EQ(j["png"], second.png);
    EXPECT_EQ(j["exr"], second.exr);
    EXPECT_EQ(j["sheet_size"], nlohmann::json({sheet.width, sheet.height}));
    ASSERT_EQ(j["tile_rects"].size(), sheet.tileRects.size());
    for (size_t i = 0; i < sheet.tileRects.size(); ++i) {
        const glm::ivec4& r = sheet.tileRects[i];
        EXPECT_EQ(j["tile_rects"][i], nlohmann::json({r.x, r.y, r.z, r.w}));
    }
    EXPECT_FALSE(fs::exists(second.json + ".tmp"));
    EXPECT_FALSE(sidecar.contains("png")) << "the caller's sidecar is not modified";

    // A regular file where the folder should be.
    fs::path file = dir / "not-a-folder";
    std::ofstream(file) << "x";
    EXPECT_CONTAINS(inputError([&] { writeSheet(file, sheet, sidecar); }), file.string());
    EXPECT_CONTAINS(inputError([&] { writeSheet(file / "below", sheet, sidecar); }), file.string());
    fs::remove_all(dir);
}

}  // namespace
}  // namespace candela::ui
