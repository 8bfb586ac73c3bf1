#pragma once
// What the report's pages are drawn with (report/Report.h): an A4 document on cairo with a
// cursor, numbered sections that make the contents, wrapped paragraphs, tables that break across
// pages, pictures, and text typeset as a client reads it (m2 as m², >= as ≥). For the report's
// own files only.

#include <cairo-pdf.h>
#include <cairo.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "util/Error.h"
#include "util/TextEncoding.h"

namespace candela::report_detail {

// A4 in points, and the printable area.
constexpr double kPageW = 595.276, kPageH = 841.89;
constexpr double kLeft = 50.0, kRight = kPageW - 50.0, kTop = 56.0, kBottom = kPageH - 56.0;
constexpr double kWidth = kRight - kLeft;
inline const char* const kFont = "DejaVu Sans";

/// One number by a printf format ("%.3g").
std::string fmt(const char* f, double a);

/// Text as a document prints it: square metres and the like with superscripts ("cd/m2" ->
/// "cd/m²", "m2 sr" -> "m² sr"), log10 with its subscript, >= and <= as one sign. Only a "2" or "3"
/// after "m" that ends a unit (followed by a space, ")", "/", ",", ";", "." or the end) is raised.
std::string typeset(const std::string& s);

/// The file name of a path (a note for the designer, never printed for a client).
std::string shortPath(const std::string& path);
/// A message without the file it names ("lamp.gldf:ldc/a.ldt: the product rates ..." -> "the
/// product rates ..."): a client cannot open the file.
std::string withoutPath(const std::string& note);

/// A document being drawn: the cairo context, the cursor and the page number.
class Pdf {
  public:
    explicit Pdf(const std::string& title) {
        mSurface = cairo_pdf_surface_create_for_stream(&Pdf::write, this, kPageW, kPageH);
        cairo_pdf_surface_set_metadata(mSurface, CAIRO_PDF_METADATA_TITLE, title.c_str());
        cairo_pdf_surface_set_metadata(mSurface, CAIRO_PDF_METADATA_CREATOR, "Candela");
        cr = cairo_create(mSurface);
        mTitle = title;
    }
    ~Pdf() {
        if (cr) cairo_destroy(cr);
        if (mSurface) cairo_surface_destroy(mSurface);
    }
    Pdf(const Pdf&) = delete;
    Pdf& operator=(const Pdf&) = delete;

    cairo_t* cr = nullptr;
    double y = kTop;

    void font(double size, bool bold = false) {
        cairo_select_font_face(cr, kFont, CAIRO_FONT_SLANT_NORMAL,
                               bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
        cairo_set_font_size(cr, size);
    }
    double textWidth(const std::string& s) {
        cairo_text_extents_t e;
        const std::string t = typeset(s);
        cairo_text_extents(cr, t.c_str(), &e);
        return e.x_advance;
    }
    /// Text with its baseline at (x, baseline); align 0 left, 0.5 centre, 1 right of x.
    void text(double x, double baseline, const std::string& s, double align = 0.0) {
        std::string t = typeset(toValidUtf8(s));
        cairo_move_to(cr, x - align * textWidth(t), baseline);
        cairo_show_text(cr, t.c_str());
    }
    void newPage() {
        footer();
        cairo_show_page(cr);
        ++mPage;
        y = kTop;
    }
    /// Starts a new page unless `height` more points fit on this one.
    void need(double height) {
        if (y + height > kBottom) newPage();
    }
    /// A numbered part of the report: a new page, its heading, and its line in the contents.
    void section(const std::string& s) {
        newPage();
        heading(s);
        sections.push_back({s, mPage});
    }
    /// The sections so far, with the page each starts on.
    std::vector<std::pair<std::string, int>> sections;

    void heading(const std::string& s, double size = 14.0) {
        need(size * 3.0);
        y += size * 0.6;
        font(size, true);
        cairo_set_source_rgb(cr, 0.1, 0.1, 0.25);
        text(kLeft, y + size, s);
        y += size * 1.6;
        cairo_set_source_rgb(cr, 0, 0, 0);
    }
    /// Words wrapped to the width, `size` points.
    void paragraph(const std::string& s, double size = 9.0, bool bold = false,
                   double indent = 0.0) {
        font(size, bold);
        std::string line, word;
        auto flush = [&] {
            need(size * 1.4);
            text(kLeft + indent, y + size, line);
            y += size * 1.4;
            line.clear();
        };
        for (size_t i = 0; i <= s.size(); ++i) {
            if (i == s.size() || s[i] == ' ') {
                std::string next = line.empty() ? word : line + " " + word;
                if (!line.empty() && textWidth(next) > kWidth - indent) {
                    flush();
                    line = word;
                } else {
                    line = next;
                }
                word.clear();
            } else {
                word += s[i];
            }
        }
        if (!line.empty()) flush();
        y += size * 0.3;
    }
    /// Words of `s` in lines no wider than `width` at the current font (a word wider than the
    /// line is cut with "~").
    std::vector<std::string> wrap(const std::string& s, double width) {
        std::vector<std::string> lines;
        std::string line, word;
        for (size_t i = 0; i <= s.size(); ++i) {
            if (i < s.size() && s[i] != ' ') {
                word += s[i];
                continue;
            }
            while (word.size() > 1 && textWidth(word) > width)
                word = word.substr(0, word.size() - 2) + "~";
            std::string next = line.empty() ? word : line + " " + word;
            if (!line.empty() && textWidth(next) > width) {
                lines.push_back(line);
                line = word;
            } else {
                line = next;
            }
            word.clear();
        }
        if (!line.empty() || lines.empty()) lines.push_back(line);
        return lines;
    }
    /// A table: a bold header row, then rows; columns at the given widths (points), numbers
    /// (align 1) right-aligned, text wrapped within its column. Rows break across pages with the
    /// header repeated. Row k is at least minHeights[k] points high (where given), and
    /// `drawn(k, top)` draws what else it holds (a picture) once its text is drawn at `top`.
    void table(const std::vector<std::string>& header,
               const std::vector<std::vector<std::string>>& rows, const std::vector<double>& widths,
               const std::vector<double>& align, double size = 8.0,
               const std::vector<double>& minHeights = {},
               const std::function<void(size_t, double)>& drawn = {}) {
        double lineH = size * 1.3, pad = size * 0.3;
        auto layout = [&](const std::vector<std::string>& cells, bool bold) {
            font(size, bold);
            std::vector<std::vector<std::string>> lines;
            for (size_t c = 0; c < cells.size() && c < widths.size(); ++c)
                lines.push_back(wrap(cells[c], widths[c] - 4.0));
            return lines;
        };
        auto height = [&](const std::vector<std::vector<std::string>>& lines) {
            size_t n = 1;
            for (const auto& l : lines) n = std::max(n, l.size());
            return double(n) * lineH + pad;
        };
        auto draw = [&](const std::vector<std::vector<std::string>>& lines, bool bold,
                        double minHeight = 0.0) {
            font(size, bold);
            double x = kLeft;
            for (size_t c = 0; c < lines.size(); ++c) {
                for (size_t k = 0; k < lines[c].size(); ++k)
                    text(x + 2.0 + align[c] * (widths[c] - 4.0), y + size + double(k) * lineH,
                         lines[c][k], align[c]);
                x += widths[c];
            }
            y += std::max(height(lines), minHeight);
            if (bold) {
                cairo_set_line_width(cr, 0.5);
                cairo_move_to(cr, kLeft, y - pad);
                cairo_line_to(cr, x, y - pad);
                cairo_stroke(cr);
            }
        };
        auto head = layout(header, true);
        need(height(head) + lineH);
        draw(head, true);
        for (size_t k = 0; k < rows.size(); ++k) {
            auto lines = layout(rows[k], false);
            const double minHeight = k < minHeights.size() ? minHeights[k] : 0.0;
            if (y + std::max(height(lines), minHeight) > kBottom) {
                newPage();
                draw(head, true);
            }
            const double top = y;
            draw(lines, false, minHeight);
            if (drawn) drawn(k, top);
        }
        y += size * 0.8;
    }
    /// RGB rows top to bottom drawn into the box (x, top, w, h).
    void image(const std::vector<unsigned char>& rgb, int width, int height, double x, double top,
               double w, double h) {
        cairo_surface_t* img = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
        unsigned char* data = cairo_image_surface_get_data(img);
        int stride = cairo_image_surface_get_stride(img);
        cairo_surface_flush(img);
        for (int r = 0; r < height; ++r)
            for (int c = 0; c < width; ++c) {
                const unsigned char* p = &rgb[(size_t(r) * size_t(width) + size_t(c)) * 3];
                uint32_t v = (uint32_t(p[0]) << 16) | (uint32_t(p[1]) << 8) | uint32_t(p[2]);
                std::memcpy(data + size_t(r) * size_t(stride) + size_t(c) * 4, &v, 4);
            }
        cairo_surface_mark_dirty(img);
        cairo_save(cr);
        cairo_translate(cr, x, top);
        cairo_scale(cr, w / width, h / height);
        cairo_set_source_surface(cr, img, 0, 0);
        cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_GOOD);
        cairo_paint(cr);
        cairo_restore(cr);
        cairo_surface_destroy(img);
    }

    std::string finish() {
        footer();
        cairo_show_page(cr);
        cairo_destroy(cr);
        cr = nullptr;
        cairo_surface_finish(mSurface);
        cairo_status_t status = cairo_surface_status(mSurface);
        cairo_surface_destroy(mSurface);
        mSurface = nullptr;
        if (status != CAIRO_STATUS_SUCCESS)
            throw InputError(std::string("the report could not be drawn: ") +
                             cairo_status_to_string(status));
        return mBytes;
    }

  private:
    static cairo_status_t write(void* closure, const unsigned char* data, unsigned int length) {
        static_cast<Pdf*>(closure)->mBytes.append(reinterpret_cast<const char*>(data), length);
        return CAIRO_STATUS_SUCCESS;
    }
    void footer() {
        font(7.5);
        cairo_set_source_rgb(cr, 0.35, 0.35, 0.35);
        text(kLeft, kPageH - 30.0, "Candela lighting report: " + mTitle);
        text(kRight, kPageH - 30.0, "page " + std::to_string(mPage), 1.0);
        cairo_set_source_rgb(cr, 0, 0, 0);
    }

    cairo_surface_t* mSurface = nullptr;
    std::string mBytes, mTitle;
    int mPage = 1;
};
}  // namespace candela::report_detail
