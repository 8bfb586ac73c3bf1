#include "report/Report.h"

#include <cairo-pdf.h>
#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <map>

#include "calculation/Plausibility.h"
#include "formats/Gldf.h"
#include "luminaires/photometric/PhotometricLuminaire.h"
#include "renderer/passes/TonemapPass.h"
#include "report/PolarDiagram.h"
#include "scene/Scene.h"
#include "shaders/shared/FalseColour.h"
#include "util/Error.h"
#include "util/TextEncoding.h"

namespace candela {

namespace {

// A4 in points, and the printable area.
constexpr double kPageW = 595.276, kPageH = 841.89;
constexpr double kLeft = 50.0, kRight = kPageW - 50.0, kTop = 56.0, kBottom = kPageH - 56.0;
constexpr double kWidth = kRight - kLeft;
const char* kFont = "DejaVu Sans";

std::string fmt(const char* f, double a) {
    char buf[64];
    std::snprintf(buf, sizeof buf, f, a);
    return buf;
}

/// A document being drawn: the cairo context, the cursor and the page number.
/// Text as a document prints it: square metres and the like with superscripts ("cd/m2" ->
/// "cd/m²", "m2 sr" -> "m² sr"), log10 with its subscript, >= and <= as one sign. Only a "2" or "3"
/// after "m" that ends a unit (followed by a space, ")", "/", ",", ";", "." or the end) is raised.
std::string typeset(const std::string& s) {
    std::string out;
    out.reserve(s.size());
    for (size_t i = 0; i < s.size(); ++i) {
        const char c = s[i];
        const bool unitEnd = i + 1 >= s.size() || std::strchr(" )/,;.]", s[i + 1]) != nullptr;
        const bool afterM = i > 0 && s[i - 1] == 'm' &&
                            (i < 2 || !std::isalpha(static_cast<unsigned char>(s[i - 2])) ||
                             s[i - 2] == 'c' || s[i - 2] == 'k');
        if ((c == '2' || c == '3') && afterM && unitEnd) {
            out += c == '2' ? "\u00b2" : "\u00b3";
            continue;
        }
        if (s.compare(i, 2, ">=") == 0 || s.compare(i, 2, "<=") == 0) {
            out += c == '>' ? "\u2265" : "\u2264";
            ++i;
            continue;
        }
        if (s.compare(i, 5, "log10") == 0) {
            out += "log\u2081\u2080";
            i += 4;
            continue;
        }
        out += c;
    }
    return out;
}

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
    /// header repeated.
    void table(const std::vector<std::string>& header,
               const std::vector<std::vector<std::string>>& rows, const std::vector<double>& widths,
               const std::vector<double>& align, double size = 8.0) {
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
        auto draw = [&](const std::vector<std::vector<std::string>>& lines, bool bold) {
            font(size, bold);
            double x = kLeft;
            for (size_t c = 0; c < lines.size(); ++c) {
                for (size_t k = 0; k < lines[c].size(); ++k)
                    text(x + 2.0 + align[c] * (widths[c] - 4.0), y + size + double(k) * lineH,
                         lines[c][k], align[c]);
                x += widths[c];
            }
            y += height(lines);
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
        for (const auto& r : rows) {
            auto lines = layout(r, false);
            if (y + height(lines) > kBottom) {
                newPage();
                draw(head, true);
            }
            draw(lines, false);
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

/// The luminaire bodies in plain words for a client.
std::string housingText(const Scene& scene) {
    size_t bodies = scene.bodyCount();
    if (bodies == 0) return "none modelled";
    return std::to_string(bodies) + (bodies > 1 ? " luminaires'" : " luminaire's") +
           " housings block the light of the others and reflected light (black)";
}

std::string shortPath(const std::string& path) {
    size_t slash = path.find_last_of("/\\");
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

// ---------------------------------------------------------------------------------------------
// Sections

/// Page 1: the project, who it is for and by whom, and the rendered view.
void coverPage(Pdf& pdf, const ReportInput& in) {
    const ProjectInfo& project = in.scene->project;
    cairo_t* cr = pdf.cr;
    pdf.y += 40;
    pdf.font(28, true);
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.25);
    pdf.text(kLeft, pdf.y + 28, "Lighting report");
    pdf.y += 50;
    pdf.font(17);
    pdf.text(kLeft, pdf.y + 17, in.title);
    cairo_set_source_rgb(cr, 0, 0, 0);
    pdf.y += 40;
    std::vector<std::vector<std::string>> rows;
    if (!project.client.empty()) rows.push_back({"Client", project.client});
    if (!project.designer.empty()) rows.push_back({"Lighting designer", project.designer});
    rows.push_back({"Date", in.date});
    if (!project.description.empty()) rows.push_back({"Description", project.description});
    pdf.table({"Project", in.title}, rows, {120, kWidth - 120}, {0, 0}, 9.5);
    pdf.y += 20;
    if (in.view.empty()) {
        pdf.paragraph("No rendered view: " + in.viewNote + ".", 8);
        return;
    }
    double w = kWidth, h = w * in.viewHeight / double(in.viewWidth);
    pdf.need(h + 30);
    pdf.image(in.view, in.viewWidth, in.viewHeight, kLeft, pdf.y, w, h);
    pdf.y += h + 6;
    pdf.paragraph("Rendered view from the scene's camera: " + in.viewNote + ".", 7.5);
}

/// Page 2: the contents (the sections' pages, from a first drawing of the report) and the
/// results at a glance.
void contentsPage(Pdf& pdf, const ReportInput& in,
                  const std::vector<std::pair<std::string, int>>& contents) {
    pdf.newPage();
    pdf.heading("Contents");
    pdf.font(10);
    for (const auto& [title, page] : contents) {
        pdf.text(kLeft + 10, pdf.y + 10, title);
        pdf.text(kRight, pdf.y + 10, std::to_string(page), 1.0);
        pdf.y += 16;
    }
    pdf.heading("Summary", 12);
    std::vector<std::vector<std::string>> summary;
    const char* unit = in.surfaces.units.irradiance();
    for (const SurfaceResult& s : in.surfaces.surfaces) {
        if (s.points.empty()) continue;
        std::string verdict = !s.required.any() ? "no requirement" : (s.passes ? "PASS" : "FAIL");
        summary.push_back(
            {s.name, fmt("%.4g ", s.summary.eAvg) + unit, fmt("%.3f", s.summary.u0), verdict});
    }
    for (const PointResult& p : in.surfaces.points)
        summary.push_back(
            {p.point.name + " (point)", fmt("%.4g ", p.E) + unit, "",
             p.point.requiredLux > 0.0 ? (p.passes ? "PASS" : "FAIL") : "no requirement"});
    if (in.glare)
        for (const GlareResult& g : in.glare->observers)
            summary.push_back({g.observer.name + " (UGR)", fmt("UGR %.1f", g.ugr), "",
                               g.observer.limit > 0.0 ? (g.passes ? "PASS" : "FAIL") : "no limit"});
    if (summary.empty())
        pdf.paragraph("The design has no calculation surfaces, points or glare observers.");
    else
        pdf.table({"Result", "Mean", "U0", "Verdict"}, summary, {230, 95, 70, 100}, {0, 1, 1, 0},
                  8.5);
}

/// The design's data: units, maintenance, the room, its surfaces and luminaires, and how the
/// light was computed.
void projectSection(Pdf& pdf, const ReportInput& in) {
    const Scene& scene = *in.scene;
    pdf.section("Project data");
    UnitSystem units = scene.units();
    glm::vec3 lo = scene.boundsMin(), hi = scene.boundsMax();
    char bounds[200];
    std::snprintf(bounds, sizeof bounds,
                  "%.2f m x %.2f m, %.2f m high (x %.2f..%.2f m, z %.2f..%.2f m)", hi.x - lo.x,
                  hi.z - lo.z, hi.y - lo.y, lo.x, hi.x, lo.z, hi.z);
    std::vector<std::vector<std::string>> rows = {
        {"Date", in.date},
        {"Made with", "Candela"},
        {"Units", units.photometric ? std::string("photometric: lm, cd, cd/m2, lx")
                                    : std::string("radiometric: W, W/sr, W/(m2 sr), W/m2")},
        {"Maintenance", scene.maintenanceNote()},
        {"Luminaire housings", housingText(scene)},
        {"Room (its overall size)", bounds},
        {"Surfaces", std::to_string(scene.geometry.size()) + " (walls, floors, furniture and "
                                                             "other objects)"},
        {"Luminaires", std::to_string(scene.luminaires.size())},
        {"Illuminance", in.evaluation},
    };
    pdf.table({"Design", ""}, rows, {120, kWidth - 120}, {0, 0}, 8.5);
}

/// A message without the file it names ("lamp.gldf:ldc/a.ldt: the product rates ..." -> "the
/// product rates ..."): a client cannot open the file.
std::string withoutPath(const std::string& note) {
    size_t colon = note.find(": ");
    if (colon == std::string::npos || note.substr(0, colon).find(' ') != std::string::npos)
        return note;
    return note.substr(colon + 2);
}

/// The factor from a photometry's candela to cd/klm: per 1000 lm of its lamps' flux, or of the
/// luminaire's own for absolute photometry (no lamp flux stated).
double perKilolumen(const PhotometricData& d, double scale) {
    double basis = d.lampFlux > 0.0 ? d.lampFlux * scale : d.fluxFromTable() * scale;
    return basis > 0.0 ? 1000.0 / basis : 0.0;
}

/// The polar diagram of one photometry in the square (x, top, size): C0-C180 solid, C90-C270
/// dashed, gamma 0 (the aim) at the bottom, rings in cd.
void polarDiagram(Pdf& pdf, const PhotometricData& data, double scale, double x, double top,
                  double size) {
    cairo_t* cr = pdf.cr;
    PolarCurves curves = polarCurves(data, 1.0);
    for (std::vector<double>* c : {&curves.c0, &curves.c180, &curves.c90, &curves.c270})
        for (double& v : *c) v *= scale;
    curves.peak *= scale;
    std::vector<double> rings = polarRings(curves.peak);
    double outer = rings.empty() ? 1.0 : rings.back();
    double cx = x + size / 2, cy = top + size / 2, radius = size / 2 - 14;
    cairo_set_line_width(cr, 0.4);
    cairo_set_source_rgb(cr, 0.6, 0.6, 0.6);
    pdf.font(6);
    for (double r : rings) {
        cairo_new_sub_path(cr);
        cairo_arc(cr, cx, cy, radius * r / outer, 0, 2 * M_PI);
        cairo_stroke(cr);
        pdf.text(cx + 2, cy - radius * r / outer - 1.5, fmt("%g cd/klm", r));
    }
    for (int a = 0; a < 360; a += 30) {
        double t = a * M_PI / 180.0;
        cairo_move_to(cr, cx, cy);
        cairo_line_to(cr, cx + radius * std::sin(t), cy + radius * std::cos(t));
        cairo_stroke(cr);
        int label = a <= 180 ? a : 360 - a;
        pdf.text(cx + (radius + 7) * std::sin(t), cy + (radius + 7) * std::cos(t) + 2,
                 std::to_string(label), 0.5);
    }
    auto curve = [&](const std::vector<double>& v, double side) {
        for (size_t k = 0; k < curves.gamma.size(); ++k) {
            double g = curves.gamma[k] * M_PI / 180.0, r = radius * v[k] / outer;
            double px = cx + side * r * std::sin(g), py = cy + r * std::cos(g);
            if (k == 0)
                cairo_move_to(cr, px, py);
            else
                cairo_line_to(cr, px, py);
        }
    };
    cairo_set_line_width(cr, 1.1);
    cairo_set_source_rgb(cr, 0.85, 0.35, 0.05);
    curve(curves.c0, 1.0);
    cairo_stroke(cr);
    curve(curves.c180, -1.0);
    cairo_stroke(cr);
    double dash[] = {3.0, 2.0};
    cairo_set_dash(cr, dash, 2, 0);
    cairo_set_source_rgb(cr, 0.1, 0.3, 0.8);
    curve(curves.c90, 1.0);
    cairo_stroke(cr);
    curve(curves.c270, -1.0);
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0);
    cairo_set_source_rgb(cr, 0, 0, 0);
}

void scheduleSection(Pdf& pdf, const ReportInput& in) {
    const Scene& scene = *in.scene;
    pdf.section("Luminaire schedule");
    std::vector<ScheduleRow> schedule = luminaireSchedule(scene);
    const char* fluxUnit = scene.units().photometric ? "lm" : "W";
    std::vector<std::vector<std::string>> rows;
    double totalFlux = 0.0, totalPower = 0.0;
    int count = 0;
    for (const ScheduleRow& r : schedule) {
        rows.push_back({std::to_string(r.count), r.names,
                        r.manufacturer.empty() ? "-" : r.manufacturer,
                        r.product.empty() ? shortPath(r.file) : r.product, fmt("%.5g", r.flux),
                        r.power > 0.0 ? fmt("%.4g", r.power) : "-",
                        r.power > 0.0 ? fmt("%.1f", r.flux / r.power) : "-",
                        fmt("%.3g", r.maintenanceFactor)});
        totalFlux += r.flux * r.count;
        totalPower += r.power * r.count;
        count += r.count;
    }
    pdf.table({"Count", "Luminaires", "Manufacturer", "Product",
               std::string("Flux [") + fluxUnit + "]", "Power [W]", "lm/W", "MF"},
              rows, {32, 104, 78, 116, 50, 48, 36, 31}, {1, 0, 0, 0, 1, 1, 1, 1}, 7.5);
    char total[200];
    std::snprintf(total, sizeof total,
                  "%d luminaire%s, %.5g %s in all from the tables (flux per luminaire: the exact "
                  "integral of its intensity table, dimming applied)%s",
                  count, count == 1 ? "" : "s", totalFlux, fluxUnit,
                  totalPower > 0.0 ? "" : "; no input power stated");
    pdf.paragraph(total, 8);
    if (totalPower > 0.0)
        pdf.paragraph(fmt("Input power %.4g W in all", totalPower) +
                          fmt(" (%.1f lm/W)", totalFlux / totalPower) +
                          "; MF: the maintenance factor each luminaire's light is scaled by.",
                      8);
    // Where a product's own figures disagree (calculation/Plausibility.h): one line per photometry.
    std::vector<std::pair<const void*, const void*>> checked;
    for (const auto& l : scene.luminaires) {
        const PhotometricLuminaire* p = photometricModel(*l);
        if (!p || !p->data) continue;
        std::pair<const void*, const void*> key(p->data.get(),
                                                p->gldf ? p->gldfLightEmitter() : nullptr);
        if (std::find(checked.begin(), checked.end(), key) != checked.end()) continue;
        checked.push_back(key);
        for (const std::string& note : plausibilityNotes(*p))
            pdf.paragraph("Data check: " + withoutPath(note) + ".", 8);
    }

    // One polar diagram per distinct photometry, two to a row.
    std::vector<const PhotometricLuminaire*> distinct;
    for (const auto& l : scene.luminaires) {
        const PhotometricLuminaire* p = photometricModel(*l);
        if (!p || !p->data) continue;
        bool seen = std::any_of(distinct.begin(), distinct.end(), [&](const auto* q) {
            return q->data == p->data && q->scale == p->scale;
        });
        if (!seen) distinct.push_back(p);
    }
    if (distinct.empty()) return;
    pdf.heading("Polar diagrams", 12);
    pdf.paragraph(
        "Luminous intensity in cd/klm (candela per 1000 lm of the luminaire's lamps), "
        "straight down at the bottom: the C0-C180 plane solid (orange), the C90-C270 plane "
        "dashed (blue).",
        8);
    const double size = 230.0, gap = kWidth - 2 * size;
    for (size_t k = 0; k < distinct.size(); ++k) {
        const PhotometricLuminaire& p = *distinct[k];
        double x = kLeft + (k % 2) * (size + gap);
        if (k % 2 == 0) pdf.need(size + 30);
        double top = pdf.y;
        pdf.font(8, true);
        std::string caption = p.data->name.empty() ? shortPath(p.file) : p.data->name;
        pdf.text(x, top + 8, caption.substr(0, 60));
        pdf.font(7);
        pdf.text(x, top + 18,
                 fmt("peak %.5g cd", p.data->maxIntensity() * p.scale) +
                     fmt(" (%.4g cd/klm)",
                         p.data->maxIntensity() * p.scale * perKilolumen(*p.data, p.scale)) +
                     fmt(", flux %.5g lm", p.data->fluxFromTable() * p.scale));
        polarDiagram(pdf, *p.data, p.scale * perKilolumen(*p.data, p.scale), x, top + 22, size);
        if (k % 2 == 1 || k + 1 == distinct.size()) pdf.y = top + size + 30;
    }
}

/// The grid's values as a matrix of cells (NaN where the surface has no point).
struct CellGrid {
    int nx = 0, ny = 0;
    std::vector<double> v;
    double at(int i, int j) const { return v[size_t(j) * size_t(nx) + size_t(i)]; }
};

CellGrid cells(const SurfaceResult& s) {
    CellGrid g;
    g.nx = std::max(s.cells.x, 1);
    g.ny = std::max(s.cells.y, 1);
    g.v.assign(size_t(g.nx) * size_t(g.ny), std::nan(""));
    for (size_t k = 0; k < s.points.size(); ++k) {
        int i = int(std::floor((s.points[k].x - s.lo.x) / s.spacing.x));
        int j = int(std::floor((s.points[k].y - s.lo.y) / s.spacing.y));
        if (i >= 0 && i < g.nx && j >= 0 && j < g.ny)
            g.v[size_t(j) * size_t(g.nx) + size_t(i)] = s.E[k];
    }
    return g;
}

/// The value at fractional cell coordinates (cell centres at integer + 0.5): bilinear among the
/// four nearest cell centres that hold a point, weights renormalised; NaN where none does.
double sampleCells(const CellGrid& g, double fx, double fy) {
    double x = fx - 0.5, y = fy - 0.5;
    int i0 = int(std::floor(x)), j0 = int(std::floor(y));
    double tx = x - i0, ty = y - j0;
    double sum = 0.0, weight = 0.0;
    for (int dj = 0; dj <= 1; ++dj)
        for (int di = 0; di <= 1; ++di) {
            int i = std::clamp(i0 + di, 0, g.nx - 1), j = std::clamp(j0 + dj, 0, g.ny - 1);
            double v = g.at(i, j);
            if (std::isnan(v)) continue;
            double w = (di ? tx : 1 - tx) * (dj ? ty : 1 - ty);
            sum += w * v;
            weight += w;
        }
    // Inside the cell of a point the picture keeps its colour even where neighbours are missing.
    if (weight <= 1e-9) {
        int i = std::clamp(int(std::floor(fx)), 0, g.nx - 1),
            j = std::clamp(int(std::floor(fy)), 0, g.ny - 1);
        return g.at(i, j);
    }
    return sum / weight;
}

/// The false-colour picture of a surface with its isolux lines and legend, at the cursor.
void surfacePicture(Pdf& pdf, const SurfaceResult& s, const char* unit) {
    cairo_t* cr = pdf.cr;
    CellGrid g = cells(s);
    double extentU = s.hi.x - s.lo.x, extentV = s.hi.y - s.lo.y;
    double w = 320.0, h = w * extentV / extentU;
    if (h > 240.0) {
        h = 240.0;
        w = h * extentU / extentV;
    }
    pdf.need(h + 40);
    // A horizontal plane is a plan seen from above: x to the right, z down the page (y up is
    // towards the reader). Any other plane keeps its v axis up.
    const bool plan = s.plane.axis == 1;
    double x0 = kLeft + 30, top = pdf.y + 6;
    double peak = 0.0;
    for (double e : s.E) peak = std::max(peak, e);
    FalseColourLegend legend;
    fitLegend(legend, float(peak));
    legend = sanitizedLegend(legend);
    // The picture: 8 pixels per cell side at least, bilinear between the points.
    int px = std::max(8 * g.nx, 160), py = std::max(1, int(std::lround(px * h / w)));
    std::vector<unsigned char> rgb(size_t(px) * size_t(py) * 3);
    std::vector<double> field(size_t(px) * size_t(py));
    for (int r = 0; r < py; ++r)
        for (int c = 0; c < px; ++c) {
            double fx = (c + 0.5) / px * g.nx;
            double fy = (plan ? (r + 0.5) / py : 1.0 - (r + 0.5) / py) * g.ny;
            double v = sampleCells(g, fx, fy);
            field[size_t(r) * size_t(px) + size_t(c)] = v;
            glm::vec3 col =
                std::isnan(v)
                    ? glm::vec3(1.0f)
                    : gpu::falseColour(gpu::legendPosition(float(v), legend.min, legend.max, 0));
            unsigned char* p = &rgb[(size_t(r) * size_t(px) + size_t(c)) * 3];
            for (int k = 0; k < 3; ++k) p[k] = (unsigned char)std::lround(255.0f * col[k]);
        }
    pdf.image(rgb, px, py, x0, top, w, h);
    // Isolux lines: marching squares on the picture's field, one segment per crossed pixel cell.
    std::vector<float> levels = contourLevels(legend);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 0.6);
    auto at = [&](int c, int r) { return field[size_t(r) * size_t(px) + size_t(c)]; };
    auto pos = [&](double c, double r) {
        return glm::dvec2(x0 + (c + 0.5) / px * w, top + (r + 0.5) / py * h);
    };
    std::vector<std::vector<glm::dvec2>> labelAt(levels.size());  // segment midpoints per level
    for (size_t l = 0; l < levels.size(); ++l) {
        const float level = levels[l];
        for (int r = 0; r + 1 < py; ++r)
            for (int c = 0; c + 1 < px; ++c) {
                double v[4] = {at(c, r), at(c + 1, r), at(c + 1, r + 1), at(c, r + 1)};
                if (std::isnan(v[0]) || std::isnan(v[1]) || std::isnan(v[2]) || std::isnan(v[3]))
                    continue;
                const int corner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
                std::vector<glm::dvec2> cross;
                for (int e = 0; e < 4; ++e) {
                    double a = v[e] - level, b = v[(e + 1) % 4] - level;
                    if ((a < 0) == (b < 0)) continue;
                    double t = a / (a - b);
                    const int* p0 = corner[e];
                    const int* p1 = corner[(e + 1) % 4];
                    cross.push_back(
                        pos(c + p0[0] + t * (p1[0] - p0[0]), r + p0[1] + t * (p1[1] - p0[1])));
                }
                for (size_t k = 0; k + 1 < cross.size(); k += 2) {
                    cairo_move_to(cr, cross[k].x, cross[k].y);
                    cairo_line_to(cr, cross[k + 1].x, cross[k + 1].y);
                    labelAt[l].push_back(0.5 * (cross[k] + cross[k + 1]));
                }
            }
    }
    cairo_stroke(cr);
    // Each line's value, at up to three points of it spread apart (the first nearest the
    // picture's middle, then each farthest from those taken), on a white patch, never closer
    // than kLabelGap to another label.
    constexpr double kLabelGap = 36.0;  // points
    const glm::dvec2 middle(x0 + w / 2, top + h / 2);
    std::vector<glm::dvec2> placed;
    pdf.font(6);
    for (size_t l = 0; l < levels.size(); ++l) {
        const std::string label = fmt("%g", levels[l]);
        for (int n = 0; n < 3 && !labelAt[l].empty(); ++n) {
            const glm::dvec2* best = nullptr;
            double bestScore = -1.0;
            for (const glm::dvec2& m : labelAt[l]) {
                double gap = 1e30;
                for (const glm::dvec2& q : placed) gap = std::min(gap, glm::distance(m, q));
                if (gap < kLabelGap) continue;
                const double score = n == 0 ? 1.0 / (1.0 + glm::distance(m, middle)) : gap;
                if (score > bestScore) {
                    bestScore = score;
                    best = &m;
                }
            }
            if (!best) break;
            const glm::dvec2 at = *best;
            placed.push_back(at);
            const double tw = pdf.textWidth(label);
            cairo_set_source_rgb(cr, 1, 1, 1);
            cairo_rectangle(cr, at.x - tw / 2 - 1, at.y - 3.5, tw + 2, 7);
            cairo_fill(cr);
            cairo_set_source_rgb(cr, 0, 0, 0);
            pdf.text(at.x, at.y + 2.2, label, 0.5);
        }
    }
    cairo_rectangle(cr, x0, top, w, h);
    cairo_set_line_width(cr, 0.5);
    cairo_stroke(cr);
    // Axes: the plane's in-plane coordinates at the corners.
    pdf.font(6.5);
    pdf.text(x0, top + h + 9, fmt("%.2f", s.lo.x), 0.5);
    pdf.text(x0 + w, top + h + 9, fmt("%.2f", s.hi.x), 0.5);
    pdf.text(x0 + w / 2, top + h + 9, s.plane.uName() + " [m]", 0.5);
    pdf.text(x0 - 3, top + h, fmt("%.2f", plan ? s.hi.y : s.lo.y), 1.0);
    pdf.text(x0 - 3, top + 6, fmt("%.2f", plan ? s.lo.y : s.hi.y), 1.0);
    pdf.text(x0 - 3, top + h / 2, s.plane.vName() + " [m]", 1.0);
    // Legend: the scale, its ticks and the isolux levels.
    double lx = x0 + w + 24, lw = 12;
    int steps = 64;
    for (int k = 0; k < steps; ++k) {
        glm::vec3 col = gpu::falseColour((k + 0.5f) / steps);
        cairo_set_source_rgb(cr, col.x, col.y, col.z);
        cairo_rectangle(cr, lx, top + h - (k + 1) * h / steps, lw, h / steps + 0.3);
        cairo_fill(cr);
    }
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_rectangle(cr, lx, top, lw, h);
    cairo_set_line_width(cr, 0.5);
    cairo_stroke(cr);
    pdf.font(6.5);
    for (float t : legendTicks(legend)) {
        double yy = top + h - h * gpu::legendPosition(t, legend.min, legend.max, 0);
        pdf.text(lx + lw + 3, yy + 2.2, fmt("%g", t) + " " + unit);
    }
    for (float level : levels) {
        double yy = top + h - h * gpu::legendPosition(level, legend.min, legend.max, 0);
        cairo_move_to(cr, lx - 3, yy);
        cairo_line_to(cr, lx + lw, yy);
    }
    cairo_stroke(cr);
    pdf.y = top + h + 16;
    std::string isolux;
    for (float level : levels) isolux += (isolux.empty() ? "" : ", ") + fmt("%g", level);
    pdf.paragraph(std::string("False colour ") + fmt("%g", legend.min) + ".." +
                      fmt("%g ", legend.max) + unit + " (linear), isolux lines at " +
                      (isolux.empty() ? std::string("none") : isolux + " " + unit) +
                      ", each labelled with its value; white: not part of the surface" +
                      (plan ? "; seen from above, x to the right and z down the page." : "."),
                  7);
}

/// Every value of the grid, laid out as the picture, columns in blocks that fit the page.
void valueTable(Pdf& pdf, const SurfaceResult& s, const char* unit) {
    CellGrid g = cells(s);
    const int perBlock = 13;
    for (int c0 = 0; c0 < g.nx; c0 += perBlock) {
        int c1 = std::min(g.nx, c0 + perBlock);
        std::vector<std::string> header = {s.plane.vName() + " \\ " + s.plane.uName() + " [m]"};
        std::vector<double> widths = {60}, align = {0};
        for (int i = c0; i < c1; ++i) {
            header.push_back(fmt("%.2f", s.lo.x + (i + 0.5) * s.spacing.x));
            widths.push_back(34);
            align.push_back(1);
        }
        std::vector<std::vector<std::string>> rows;
        // As the picture: a plan's rows from the smallest z down, another plane's from the top.
        const bool plan = s.plane.axis == 1;
        for (int k = 0; k < g.ny; ++k) {
            const int j = plan ? k : g.ny - 1 - k;
            std::vector<std::string> row = {fmt("%.2f", s.lo.y + (j + 0.5) * s.spacing.y)};
            for (int i = c0; i < c1; ++i) {
                double v = g.at(i, j);
                row.push_back(std::isnan(v) ? "" : fmt(v >= 10.0 ? "%.0f" : "%.1f", v));
            }
            rows.push_back(row);
        }
        pdf.table(header, rows, widths, align, 6.5);
    }
    pdf.paragraph(std::string("Values in ") + unit + " at the points (cell centres).", 7);
}

std::string requirementText(const Requirement& r, bool cylindrical, const char* unit) {
    if (!r.any()) return "no requirement";
    std::string out;
    if (r.em > 0.0) out = std::string(cylindrical ? "Ezm" : "Em") + fmt(" >= %g ", r.em) + unit;
    if (r.u0 > 0.0) out += std::string(out.empty() ? "" : ", ") + fmt("U0 >= %.2f", r.u0);
    return out;
}

void surfacesSection(Pdf& pdf, const ReportInput& in) {
    const SurfaceReport& r = in.surfaces;
    const char* unit = r.units.irradiance();
    pdf.section("Calculation surfaces (EN 12464-1)");
    pdf.paragraph(
        "Maintained illuminance on each task area, its immediate surrounding and its "
        "background, on the standard's grids; " +
            r.maintenance + "; light: " + in.evaluation + ".",
        8);
    if (r.surfaces.empty()) pdf.paragraph("The scene has no task areas.");
    for (const SurfaceResult& s : r.surfaces) {
        // The heading, its summary and the picture on one page.
        double extentU = s.hi.x - s.lo.x, extentV = s.hi.y - s.lo.y;
        double pictureH = std::min(240.0, 320.0 * extentV / std::max(extentU, 1e-9));
        pdf.need(pictureH + 130);
        bool named = s.name.find(s.role) != std::string::npos;  // "Desk: background"
        pdf.heading(named ? s.name : s.name + " (" + s.role + ")", 11);
        char line[320];
        std::snprintf(line, sizeof line,
                      "Plane %s, area %s %.3f..%.3f m, %s %.3f..%.3f m; grid %d x %d cells of "
                      "%.3f x %.3f m, %zu points",
                      planeText(s.plane).c_str(), s.plane.uName().c_str(), s.lo.x, s.hi.x,
                      s.plane.vName().c_str(), s.lo.y, s.hi.y, s.cells.x, s.cells.y, s.spacing.x,
                      s.spacing.y, s.points.size());
        pdf.paragraph(line, 8);
        if (s.points.empty() || !(s.spacing.x > 0.0) || !(s.spacing.y > 0.0)) {
            pdf.paragraph("No points: the room leaves no " + s.role + ".", 8);
            continue;
        }
        const char* e = s.cylindrical ? "Ez" : "E";
        std::snprintf(line, sizeof line, "%sm %.4g %s, U0 %.3f, %smin %.4g %s, %smax %.4g %s", e,
                      s.summary.eAvg, unit, s.summary.u0, e, s.summary.eMin, unit, e,
                      s.summary.eMax, unit);
        pdf.paragraph(line, 9.5, true);
        pdf.paragraph("Required: " + requirementText(s.required, s.cylindrical, unit) + ": " +
                          (!s.required.any() ? "-" : (s.passes ? "PASS" : "FAIL")),
                      9);
        surfacePicture(pdf, s, unit);
        valueTable(pdf, s, unit);
    }
    if (r.points.empty()) return;
    pdf.heading("Calculation points", 12);
    std::vector<std::vector<std::string>> rows;
    for (const PointResult& p : r.points) {
        const CalcPoint& c = p.point;
        char where[96], kind[96];
        std::snprintf(where, sizeof where, "(%.2f, %.2f, %.2f)", c.position.x, c.position.y,
                      c.position.z);
        if (c.cylindrical)
            std::snprintf(kind, sizeof kind, "cylindrical Ez");
        else
            std::snprintf(kind, sizeof kind, "E, normal (%.2f, %.2f, %.2f)", c.normal.x, c.normal.y,
                          c.normal.z);
        rows.push_back({c.name, where, kind, fmt("%.4g ", p.E) + unit,
                        c.requiredLux > 0.0 ? fmt("%g ", c.requiredLux) + unit : "-",
                        c.requiredLux > 0.0 ? (p.passes ? "PASS" : "FAIL") : "-"});
    }
    pdf.table({"Point", "Position [m]", "Quantity", "Value", "Required", "Verdict"}, rows,
              {120, 90, 120, 60, 60, 45}, {0, 0, 0, 1, 1, 0});
}

void glareSection(Pdf& pdf, const ReportInput& in) {
    pdf.section("Glare: UGR (CIE 117)");
    if (!in.glare) {
        pdf.paragraph(in.glareNote, 8);
        return;
    }
    pdf.paragraph(
        "The Unified Glare Rating at each observer, UGR = 8 log10(0.25 / Lb \u00d7 "
        "\u03a3 L\u00b2\u03c9 / p\u00b2): L is the luminance of each luminaire's opening "
        "towards the eye, \u03c9 the solid angle it fills, p its position index (Guth), and "
        "Lb the background luminance (the reflected light reaching the eye, over \u03c0, "
        "unless given). Openings smaller than 0.005 m2 are rated by CIE 147's rule for small "
        "sources. Lower is better: 19 is the usual limit for offices and classrooms. " +
            in.glare->maintenance + ".",
        8);
    std::vector<std::vector<std::string>> rows;
    for (const GlareResult& g : in.glare->observers) {
        const GlareObserver& o = g.observer;
        char where[96], view[64];
        std::snprintf(where, sizeof where, "(%.2f, %.2f, %.2f)", o.position.x, o.position.y,
                      o.position.z);
        // + 0.0 turns -0 into 0 (IEEE 754 round to nearest), so no "-0.00" is printed.
        std::snprintf(view, sizeof view, "(%.2f, %.2f, %.2f)", o.view.x + 0.0, o.view.y + 0.0,
                      o.view.z + 0.0);
        rows.push_back({o.name, where, view,
                        fmt("%.4g", g.background) + (g.backgroundFromIndirect ? "" : " (given)"),
                        fmt("%.1f", g.ugr), o.limit > 0.0 ? fmt("%g", o.limit) : "-",
                        o.limit > 0.0 ? (g.passes ? "PASS" : "FAIL") : "-"});
    }
    pdf.table({"Observer", "Eye [m]", "View", "Lb [cd/m2]", "UGR", "UGR_L", "Verdict"}, rows,
              {120, 84, 84, 66, 40, 40, 45}, {0, 0, 0, 1, 1, 1, 0});
}

void methodSection(Pdf& pdf, const ReportInput& in) {
    pdf.section("How this was computed");
    pdf.paragraph(
        "Illuminance: " + in.evaluation +
            ". The calculation points lie on the grid EN 12464-1 prescribes for each area's "
            "size (0.2 m apart on a 1 m task, 1 m apart on a 10 m room) unless another "
            "spacing was chosen. Em is the mean illuminance, Emin and Emax the lowest and "
            "highest, and the uniformity U0 = Emin / Em.",
        8);
    pdf.paragraph(
        "Rendered view: " + (in.view.empty() ? "none (" + in.viewNote + ")" : in.viewNote) + ".",
        8);
}

}  // namespace

std::vector<unsigned char> withFalseColourLegend(const std::vector<unsigned char>& rgb, int& width,
                                                 int height, const FalseColourLegend& given,
                                                 const std::string& unit) {
    FalseColourLegend legend = sanitizedLegend(given);
    double fontSize = std::clamp(height / 24.0, 8.0, 14.0);
    int strip = int(std::lround(fontSize * 9.0));
    int total = width + strip;
    cairo_surface_t* img = cairo_image_surface_create(CAIRO_FORMAT_RGB24, total, height);
    unsigned char* data = cairo_image_surface_get_data(img);
    int stride = cairo_image_surface_get_stride(img);
    cairo_surface_flush(img);
    for (int r = 0; r < height; ++r)
        for (int c = 0; c < total; ++c) {
            uint32_t v = 0xFFFFFF;  // the strip's white background
            if (c < width) {
                const unsigned char* p = &rgb[(size_t(r) * size_t(width) + size_t(c)) * 3];
                v = (uint32_t(p[0]) << 16) | (uint32_t(p[1]) << 8) | uint32_t(p[2]);
            }
            std::memcpy(data + size_t(r) * size_t(stride) + size_t(c) * 4, &v, 4);
        }
    cairo_surface_mark_dirty(img);
    cairo_t* cr = cairo_create(img);
    double top = height * 0.08, bottom = height * 0.92, barX = width + fontSize,
           barW = fontSize * 1.2;
    auto yOf = [&](float v) {
        double t = gpu::legendPosition(v, legend.min, legend.max, legend.logScale ? 1 : 0);
        return bottom - (bottom - top) * std::clamp(t, 0.0, 1.0);
    };
    int steps = std::max(2, int(bottom - top));
    for (int k = 0; k < steps; ++k) {
        glm::vec3 col = gpu::falseColour((k + 0.5f) / steps);
        cairo_set_source_rgb(cr, col.x, col.y, col.z);
        double y0 = bottom - (k + 1) * (bottom - top) / steps;
        cairo_rectangle(cr, barX, y0, barW, (bottom - top) / steps + 0.5);
        cairo_fill(cr);
    }
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1.0);
    cairo_rectangle(cr, barX, top, barW, bottom - top);
    cairo_stroke(cr);
    cairo_select_font_face(cr, kFont, CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, fontSize);
    for (float t : legendTicks(legend)) {
        double y = yOf(t);
        cairo_move_to(cr, barX + barW, y);
        cairo_line_to(cr, barX + barW + 3, y);
        cairo_stroke(cr);
        std::string label = toValidUtf8(fmt("%g", t) + " " + unit);
        cairo_move_to(cr, barX + barW + 5, y + fontSize * 0.35);
        cairo_show_text(cr, label.c_str());
    }
    for (float level : contourLevels(legend)) {  // isolux levels: a line across the bar
        double y = yOf(level);
        cairo_move_to(cr, barX - 3, y);
        cairo_line_to(cr, barX + barW, y);
        cairo_stroke(cr);
    }
    cairo_destroy(cr);
    cairo_surface_flush(img);
    std::vector<unsigned char> out(size_t(total) * size_t(height) * 3);
    for (int r = 0; r < height; ++r)
        for (int c = 0; c < total; ++c) {
            uint32_t v;
            std::memcpy(&v, data + size_t(r) * size_t(stride) + size_t(c) * 4, 4);
            unsigned char* p = &out[(size_t(r) * size_t(total) + size_t(c)) * 3];
            p[0] = (unsigned char)(v >> 16), p[1] = (unsigned char)(v >> 8),
            p[2] = (unsigned char)v;
        }
    cairo_surface_destroy(img);
    width = total;
    return out;
}

std::vector<ScheduleRow> luminaireSchedule(const Scene& scene) {
    std::vector<ScheduleRow> rows;
    std::map<std::string, size_t> index;
    UnitSystem units = scene.units();  // once: it looks at every luminaire
    for (const auto& l : scene.luminaires) {
        ScheduleRow r;
        r.maintenanceFactor = scene.maintenanceFactorOf(*l);
        glm::dvec3 power = l->power() * scene.unitScale(*l, units);
        r.flux = (power.x + power.y + power.z) / 3.0;
        r.kind = std::string(kindName(l->kind()));
        if (const PhotometricLuminaire* p = photometricModel(*l); p && p->data) {
            const PhotometricData& d = *p->data;
            r.file = p->file;
            r.flux = d.fluxFromTable() * p->scale;
            r.power = d.inputWatts;
            r.manufacturer = d.keyword({"MANUFAC", "company", "Manufacturer"});
            r.product = d.name;
            if (p->gldf) {
                r.kind = "GLDF";
                r.manufacturer = p->gldf->manufacturer;
                r.product = p->gldf->productName;
                if (const GldfVariant* v = p->gldf->variant(p->gldfVariant); v && !v->name.empty())
                    r.product += ", " + v->name;
                if (const GldfLightEmitter* e = p->gldfLightEmitter(); e && e->ratedPower > 0.0)
                    r.power = e->ratedPower;
            }
        }
        std::string key = describe(*l) + "|" + fmt("%.9g", r.maintenanceFactor) + "|" + r.kind;
        auto it = index.find(key);
        if (it == index.end()) {
            r.names = l->name;
            r.count = 1;
            index[key] = rows.size();
            rows.push_back(r);
        } else {
            ScheduleRow& row = rows[it->second];
            ++row.count;
            size_t dots = row.names.find(" .. ");
            row.names = (dots == std::string::npos ? row.names : row.names.substr(0, dots)) +
                        " .. " + l->name;
        }
    }
    return rows;
}

/// What `how` computed on `scene`, as the report states it to a client.
std::string reportEvaluationText(const Scene& scene, const GridSpec& how, size_t patches) {
    std::string out = lightStatement(scene, how);
    out += how.technique.empty() ? "; each luminaire's light from its own measured photometry"
                                 : "; every luminaire's light by technique " + how.technique;
    if (how.indirect && patches > 0)
        out += "; interreflected light from " + std::to_string(patches) +
               " surface patches, traced point by point where the patches are not accurate "
               "enough";
    return out;
}

std::string todayUtc() {
    std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    char buf[16];
    std::strftime(buf, sizeof buf, "%Y-%m-%d", &utc);
    return buf;
}

void computeReportContents(ReportInput& in, const Scene& scene, const std::string& title,
                           const GridSpec& how,
                           const std::function<void(const std::string&)>& status) {
    in.scene = &scene;
    in.title = title;
    in.date = scene.project.date.empty() ? todayUtc() : scene.project.date;
    if (!scene.taskAreas.empty() || !scene.calcPoints.empty()) {
        in.surfaces = computeSurfaces(scene, how, status);
    } else {
        in.surfaces.units = scene.units();
        in.surfaces.maintenance = scene.maintenanceNote();
        in.surfaces.light = lightStatement(scene, how);
    }
    in.evaluation = reportEvaluationText(scene, how, in.surfaces.patches);
    if (!scene.glareObservers.empty())
        in.glare = computeGlare(scene, how, {}, status);
    else
        in.glareNote = "No glare observers were placed in the design, so no UGR was rated.";
}

std::string reportPdf(const ReportInput& in) {
    // Drawn twice: the first drawing finds the page each section starts on, which the second
    // lists on its contents page (a page of its own, so the pages after it do not move).
    std::vector<std::pair<std::string, int>> contents;
    for (int pass = 0;; ++pass) {
        Pdf pdf(in.title);
        coverPage(pdf, in);
        contentsPage(pdf, in, contents);
        projectSection(pdf, in);
        scheduleSection(pdf, in);
        surfacesSection(pdf, in);
        glareSection(pdf, in);
        methodSection(pdf, in);
        if (pass == 1) return pdf.finish();
        contents = pdf.sections;
        pdf.finish();
    }
}

}  // namespace candela
