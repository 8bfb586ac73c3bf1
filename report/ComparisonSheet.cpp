#include "report/ComparisonSheet.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <system_error>

#include "renderer/ImageFile.h"
#include "report/Screenshot.h"
#include "util/Error.h"
#include "util/FileOutput.h"

namespace candela {

namespace fs = std::filesystem;

namespace {

/// Font size, pixels (Dear ImGui's size: ascent minus descent).
constexpr float kFontPixels = 15.0f;
constexpr const char* kDejaVuSans = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

/// Margin around and between cells, pixels.
constexpr int kMargin = 8;
/// Gap between a tile and its first label line, pixels.
constexpr int kLabelGap = 4;

constexpr glm::u8vec3 kBackground{24, 24, 28};
constexpr glm::u8vec3 kTitleColour{240, 240, 244};
constexpr glm::u8vec3 kLabelColour{208, 208, 214};

/// Code point ranges rasterized into the atlas (inclusive pairs, zero-terminated): Latin-1 and
/// Latin Extended-A, Greek, general punctuation, arrows and mathematical operators. Dear ImGui
/// 1.86 has no GetGlyphRangesGreek(), hence our own list; the atlas keeps a pointer to it.
constexpr ImWchar kGlyphRanges[] = {0x0020, 0x017F, 0x0370, 0x03FF, 0x2010, 0x205E,
                                    0x2190, 0x21FF, 0x2200, 0x22FF, 0};

/// ASCII stand-ins for characters the fallback font lacks (ProggyClean has no Greek).
constexpr struct {
    unsigned from;
    ImWchar to;
} kSubstitutes[] = {{0x0394, 'd'},  {0x03B4, 'd'},  {0x03BC, 'u'}, {0x03C3, 's'}, {0x03C0, 'p'},
                    {0x03BB, 'l'},  {0x00B7, '.'},  {0x2013, '-'}, {0x2014, '-'}, {0x2212, '-'},
                    {0x2018, '\''}, {0x2019, '\''}, {0x201C, '"'}, {0x201D, '"'}};

constexpr unsigned kReplacementChar = 0xFFFD;

/// Decodes the code point that starts at utf8[i] and moves i past it. A malformed sequence
/// (truncated, overlong, a surrogate, beyond U+10FFFF) gives U+FFFD and skips one byte.
unsigned decodeUtf8(const std::string& utf8, size_t& i) {
    auto byte = [&](size_t k) { return static_cast<unsigned char>(utf8[k]); };
    unsigned lead = byte(i);
    if (lead < 0x80) {
        ++i;
        return lead;
    }
    size_t extra = 0;
    unsigned cp = 0, smallest = 0;
    if ((lead & 0xE0) == 0xC0) {
        extra = 1, cp = lead & 0x1F, smallest = 0x80;
    } else if ((lead & 0xF0) == 0xE0) {
        extra = 2, cp = lead & 0x0F, smallest = 0x800;
    } else if ((lead & 0xF8) == 0xF0) {
        extra = 3, cp = lead & 0x07, smallest = 0x10000;
    } else {
        ++i;
        return kReplacementChar;
    }
    for (size_t k = 1; k <= extra; ++k) {
        if (i + k >= utf8.size() || (byte(i + k) & 0xC0) != 0x80) {
            ++i;
            return kReplacementChar;
        }
        cp = (cp << 6) | (byte(i + k) & 0x3F);
    }
    if (cp < smallest || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) {
        ++i;
        return kReplacementChar;
    }
    i += extra + 1;
    return cp;
}

/// The bytes of a TrueType/OpenType file, or nothing when it is missing, unreadable or does not
/// start like a font (Dear ImGui asserts on data that is not a font, so it never sees such data).
std::vector<unsigned char> readFontFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return {};
    std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                     std::istreambuf_iterator<char>());
    if (bytes.size() < 1024) return {};
    std::string tag(bytes.begin(), bytes.begin() + 4);
    bool font = tag == std::string("\0\1\0\0", 4) || tag == "true" || tag == "OTTO";
    return font ? bytes : std::vector<unsigned char>{};
}

/// A glyph placed on a line: its pen position relative to the text's origin, pixels.
struct PlacedGlyph {
    const ImFontGlyph* glyph;
    int penX;
};

/// Glyphs of a line of text, and the horizontal extent of their ink and advances.
struct TextLayout {
    std::vector<PlacedGlyph> glyphs;
    int originX = 0;  ///< Pen start from the left edge of the text box, pixels (ink may overhang).
    int width = 0;    ///< Width of the text box, pixels.
};

}  // namespace

struct SheetFont::Atlas {
    std::vector<unsigned char> ttf;  ///< Font file, owned here (the atlas only points at it).
    ImFontAtlas atlas;
    ImFont* font = nullptr;
    bool fallback = false;
    const unsigned char* pixels = nullptr;  ///< Coverage, texWidth x texHeight, 8 bits.
    int texWidth = 0, texHeight = 0;
    int top = 0;         ///< Added to glyph Y so that no glyph starts above the line, pixels.
    int lineHeight = 0;  ///< Pixels.

    /// Glyph for a code point: the font's own, else an ASCII stand-in, else '?'.
    const ImFontGlyph* glyphFor(unsigned cp) const {
        if (cp <= 0xFFFF)
            if (const ImFontGlyph* g = font->FindGlyphNoFallback(static_cast<ImWchar>(cp)))
                return g;
        for (const auto& s : kSubstitutes)
            if (s.from == cp)
                if (const ImFontGlyph* g = font->FindGlyphNoFallback(s.to)) return g;
        return font->FindGlyph('?');
    }

    TextLayout layout(const std::string& utf8) const {
        TextLayout out;
        float pen = 0.0f, left = 0.0f, right = 0.0f;
        for (size_t i = 0; i < utf8.size();) {
            unsigned cp = decodeUtf8(utf8, i);
            if (cp == '\t') cp = ' ';
            if (cp < 0x20 || cp == 0x7F) continue;  // other control characters draw nothing
            const ImFontGlyph* g = glyphFor(cp);
            if (!g) continue;
            int penX = static_cast<int>(std::lround(pen));
            if (g->Visible) {
                out.glyphs.push_back({g, penX});
                left = std::min(left, float(penX) + g->X0);
                right = std::max(right, float(penX) + g->X1);
            }
            pen += g->AdvanceX;
            right = std::max(right, pen);
        }
        out.originX = -static_cast<int>(std::floor(left));
        out.width = static_cast<int>(std::ceil(right)) + out.originX;
        return out;
    }

    /// Alpha-blends one glyph with its pen at (penX, lineY) (lineY: top of the line box).
    void blit(std::vector<unsigned char>& rgb, int width, int height, int penX, int lineY,
              const ImFontGlyph& g, glm::u8vec3 colour) const {
        float x0 = float(penX) + g.X0, x1 = float(penX) + g.X1;
        float y0 = float(lineY + top) + g.Y0, y1 = float(lineY + top) + g.Y1;
        if (x1 <= x0 || y1 <= y0) return;
        // Atlas texels of the glyph; the quad maps onto them linearly (one texel per pixel with
        // the oversampling of 1 we ask for, but any scale works).
        int u0 = int(std::lround(g.U0 * float(texWidth))),
            u1 = int(std::lround(g.U1 * float(texWidth)));
        int v0 = int(std::lround(g.V0 * float(texHeight))),
            v1 = int(std::lround(g.V1 * float(texHeight)));
        int px0 = std::max(0, int(std::floor(x0))), px1 = std::min(width, int(std::ceil(x1)));
        int py0 = std::max(0, int(std::floor(y0))), py1 = std::min(height, int(std::ceil(y1)));
        for (int py = py0; py < py1; ++py) {
            float fy = (float(py) + 0.5f - y0) / (y1 - y0);
            if (fy < 0.0f || fy >= 1.0f) continue;
            int ty = std::clamp(v0 + int(fy * float(v1 - v0)), 0, texHeight - 1);
            for (int px = px0; px < px1; ++px) {
                float fx = (float(px) + 0.5f - x0) / (x1 - x0);
                if (fx < 0.0f || fx >= 1.0f) continue;
                int tx = std::clamp(u0 + int(fx * float(u1 - u0)), 0, texWidth - 1);
                unsigned a = pixels[size_t(ty) * size_t(texWidth) + size_t(tx)];
                if (a == 0) continue;
                unsigned char* dst = &rgb[(size_t(py) * size_t(width) + size_t(px)) * 3];
                for (int c = 0; c < 3; ++c)
                    dst[c] = static_cast<unsigned char>((dst[c] * (255 - a) + colour[c] * a + 127) /
                                                        255);
            }
        }
    }
};

SheetFont::SheetFont(const fs::path& ttfPath) : mAtlas(std::make_unique<Atlas>()) {
    Atlas& a = *mAtlas;
    a.atlas.Flags |= ImFontAtlasFlags_NoMouseCursors | ImFontAtlasFlags_NoBakedLines;
    a.ttf = readFontFile(ttfPath);
    if (!a.ttf.empty()) {
        ImFontConfig config;
        config.FontDataOwnedByAtlas = false;
        config.OversampleH = config.OversampleV = 1;  // one atlas texel per image pixel
        config.PixelSnapH = true;                     // whole-pixel advances
        a.font = a.atlas.AddFontFromMemoryTTF(a.ttf.data(), int(a.ttf.size()), kFontPixels, &config,
                                              kGlyphRanges);
    }
    if (!a.font || !a.atlas.Build()) {
        a.atlas.Clear();
        a.font = a.atlas.AddFontDefault();  // ProggyClean, 13 px, ASCII and Latin-1
        a.fallback = true;
        a.atlas.Build();
    }
    unsigned char* pixels = nullptr;
    a.atlas.GetTexDataAsAlpha8(&pixels, &a.texWidth, &a.texHeight);
    a.pixels = pixels;
    // The line box holds every glyph of the font, so text never spills out of it.
    float minY = 0.0f, maxY = a.font->FontSize;
    for (const ImFontGlyph& g : a.font->Glyphs)
        if (g.Visible) {
            minY = std::min(minY, g.Y0);
            maxY = std::max(maxY, g.Y1);
        }
    a.top = -static_cast<int>(std::floor(minY));
    a.lineHeight = static_cast<int>(std::ceil(maxY)) + a.top;
}

SheetFont::~SheetFont() = default;

const SheetFont& SheetFont::standard() {
    static const SheetFont font(kDejaVuSans);
    return font;
}

bool SheetFont::isFallback() const {
    return mAtlas->fallback;
}

int SheetFont::lineHeight() const {
    return mAtlas->lineHeight;
}

int SheetFont::textWidth(const std::string& utf8) const {
    return mAtlas->layout(utf8).width;
}

void SheetFont::drawText(std::vector<unsigned char>& rgb, int width, int height, int x, int y,
                         const std::string& utf8, glm::u8vec3 colour) const {
    if (width <= 0 || height <= 0 || rgb.size() < size_t(width) * size_t(height) * 3) return;
    TextLayout text = mAtlas->layout(utf8);
    for (const PlacedGlyph& p : text.glyphs)
        mAtlas->blit(rgb, width, height, x + text.originX + p.penX, y, *p.glyph, colour);
}

int sheetLineHeight() {
    return SheetFont::standard().lineHeight();
}

int sheetTextWidth(const std::string& utf8) {
    return SheetFont::standard().textWidth(utf8);
}

void drawSheetText(std::vector<unsigned char>& rgb, int width, int height, int x, int y,
                   const std::string& utf8, glm::u8vec3 colour) {
    SheetFont::standard().drawText(rgb, width, height, x, y, utf8, colour);
}

namespace {

void checkTiles(const std::vector<SheetTile>& tiles, int columns) {
    if (tiles.empty()) throw InputError("comparison sheet: no tiles to compose");
    if (columns < 1)
        throw InputError("comparison sheet: columns must be at least 1, got " +
                         std::to_string(columns));
    for (size_t i = 0; i < tiles.size(); ++i) {
        const SheetTile& t = tiles[i];
        std::string name = "comparison sheet: tile " + std::to_string(i);
        if (t.width <= 0 || t.height <= 0)
            throw InputError(name + ": size " + std::to_string(t.width) + "x" +
                             std::to_string(t.height) + ", expected a positive width and height");
        size_t expected = size_t(t.width) * size_t(t.height) * 3;
        if (t.display.size() != expected)
            throw InputError(name + ": display buffer holds " + std::to_string(t.display.size()) +
                             " values, expected " + std::to_string(expected));
        if (!t.linear.empty() && t.linear.size() != expected)
            throw InputError(name + ": linear buffer holds " + std::to_string(t.linear.size()) +
                             " values, expected " + std::to_string(expected) + " or none");
    }
}

/// Copies a tile's pixels into the sheet at (x, y).
void placeTile(SheetImage& sheet, const SheetTile& tile, int x, int y) {
    for (int row = 0; row < tile.height; ++row) {
        size_t src = size_t(row) * size_t(tile.width) * 3;
        size_t dst = (size_t(y + row) * size_t(sheet.width) + size_t(x)) * 3;
        size_t count = size_t(tile.width) * 3;
        std::copy_n(tile.display.begin() + ptrdiff_t(src), count,
                    sheet.display.begin() + ptrdiff_t(dst));
        if (!tile.linear.empty())
            std::copy_n(tile.linear.begin() + ptrdiff_t(src), count,
                        sheet.linear.begin() + ptrdiff_t(dst));
    }
}

}  // namespace

SheetImage composeSheet(const std::vector<SheetTile>& tiles, int columns,
                        const std::string& title) {
    checkTiles(tiles, columns);
    const SheetFont& font = SheetFont::standard();
    int lineHeight = font.lineHeight();

    int cols = std::min(columns, int(tiles.size()));
    int rows = (int(tiles.size()) + cols - 1) / cols;
    int cellWidth = 0, cellHeight = 0, labelLines = 0;
    for (const SheetTile& t : tiles) {
        cellWidth = std::max(cellWidth, t.width);
        cellHeight = std::max(cellHeight, t.height);
        labelLines = std::max(labelLines, int(t.lines.size()));
        for (const std::string& line : t.lines)
            cellWidth = std::max(cellWidth, font.textWidth(line));
    }
    int stripHeight = labelLines > 0 ? kLabelGap + labelLines * lineHeight : 0;
    int titleHeight = title.empty() ? 0 : lineHeight + kMargin;
    int gridWidth = kMargin + cols * (cellWidth + kMargin);

    SheetImage sheet;
    sheet.width = std::max(gridWidth, title.empty() ? 0 : font.textWidth(title) + 2 * kMargin);
    sheet.height = kMargin + titleHeight + rows * (cellHeight + stripHeight + kMargin);
    size_t values = size_t(sheet.width) * size_t(sheet.height) * 3;
    sheet.display.resize(values);
    for (size_t i = 0; i < values; ++i) sheet.display[i] = kBackground[int(i % 3)];
    sheet.linear.assign(values, 0.0f);

    if (!title.empty())
        font.drawText(sheet.display, sheet.width, sheet.height, kMargin, kMargin, title,
                      kTitleColour);
    int gridX = (sheet.width - gridWidth) / 2;
    for (size_t i = 0; i < tiles.size(); ++i) {
        const SheetTile& t = tiles[i];
        int cellX = gridX + kMargin + int(i % size_t(cols)) * (cellWidth + kMargin);
        int cellY =
            kMargin + titleHeight + int(i / size_t(cols)) * (cellHeight + stripHeight + kMargin);
        // Centred horizontally, resting on the label strip.
        int x = cellX + (cellWidth - t.width) / 2, y = cellY + cellHeight - t.height;
        placeTile(sheet, t, x, y);
        sheet.tileRects.emplace_back(x, y, t.width, t.height);
        for (size_t k = 0; k < t.lines.size(); ++k) {
            int lineX = cellX + (cellWidth - font.textWidth(t.lines[k])) / 2;
            int lineY = cellY + cellHeight + kLabelGap + int(k) * lineHeight;
            font.drawText(sheet.display, sheet.width, sheet.height, lineX, lineY, t.lines[k],
                          kLabelColour);
        }
    }
    return sheet;
}

SheetFiles writeSheet(const fs::path& dir, const SheetImage& sheet, const nlohmann::json& sidecar) {
    size_t expected = size_t(std::max(sheet.width, 0)) * size_t(std::max(sheet.height, 0)) * 3;
    if (sheet.width <= 0 || sheet.height <= 0 || sheet.display.size() != expected ||
        sheet.linear.size() != expected)
        throw InputError(dir.string() + ": comparison sheet " + std::to_string(sheet.width) + "x" +
                         std::to_string(sheet.height) + " does not match its pixel buffers");
    if (!sidecar.is_null() && !sidecar.is_object())
        throw InputError(dir.string() + ": comparison sheet sidecar must be a JSON object");

    SheetFiles files;
    try {
        std::error_code ec;
        fs::create_directories(dir, ec);
        if (ec) throw InputError(dir.string() + ": cannot create folder (" + ec.message() + ")");
        fs::path stem = nextFreeStem(dir, "sheet");
        files.png = stem.string() + ".png";
        files.exr = stem.string() + ".exr";
        files.json = stem.string() + ".json";
    } catch (const fs::filesystem_error& e) {
        throw InputError(dir.string() + ": " + e.what());
    }
    // Whole or none: a sheet whose sidecar (or EXR) could not be written takes back what was
    // written, so that no half sheet stays and the next one takes its number.
    try {
        writeImage8(files.png, sheet.width, sheet.height, sheet.display);
        writeImageFloat(files.exr, sheet.width, sheet.height, sheet.linear);

        nlohmann::json out = sidecar.is_null() ? nlohmann::json::object() : sidecar;
        out["png"] = files.png;
        out["exr"] = files.exr;
        out["sheet_size"] = {sheet.width, sheet.height};
        nlohmann::json rects = nlohmann::json::array();
        for (const glm::ivec4& r : sheet.tileRects) rects.push_back({r.x, r.y, r.z, r.w});
        out["tile_rects"] = std::move(rects);
        // Invalid UTF-8 in caller-supplied strings is replaced rather than thrown on.
        writeFileAtomically(
            files.json, out.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
    } catch (...) {
        std::error_code ignored;
        for (const std::string& f : {files.png, files.exr, files.json}) fs::remove(f, ignored);
        throw;
    }
    return files;
}

}  // namespace candela
