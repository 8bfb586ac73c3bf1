#include "report/Report.h"

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
#include "report/ReportSections.h"
#include "scene/Scene.h"
#include "shaders/shared/FalseColour.h"
#include "util/Error.h"
#include "util/TextEncoding.h"

namespace candela {

using namespace report_detail;

namespace {

/// The luminaire bodies in plain words for a client.
std::string housingText(const Scene& scene) {
    size_t bodies = scene.bodyCount();
    if (bodies == 0) return "none modelled";
    return std::to_string(bodies) + (bodies > 1 ? " luminaires'" : " luminaire's") +
           " housings block the light of the others and reflected light (black)";
}

// ---------------------------------------------------------------------------------------------
// Sections

/// What the scene's geometry is, in words: "1 room, 3 pieces of furniture, 2 other objects".
std::string geometryText(const Scene& scene) {
    int rooms = 0, furniture = 0, other = 0;
    for (const GeometryItem& item : scene.geometry) {
        if (item.source.contains("room"))
            ++rooms;
        else if (item.source.contains("furniture"))
            ++furniture;
        else
            ++other;
    }
    auto count = [](int n, const char* one, const char* many) {
        return std::to_string(n) + " " + (n == 1 ? one : many);
    };
    std::string out;
    if (rooms > 0) out = count(rooms, "room", "rooms");
    if (furniture > 0)
        out += (out.empty() ? "" : ", ") +
               count(furniture, "piece of furniture", "pieces of furniture");
    if (other > 0)
        out += (out.empty() ? "" : ", ") +
               count(other, rooms + furniture > 0 ? "other object" : "surface or object",
                     rooms + furniture > 0 ? "other objects" : "surfaces and objects");
    return out.empty() ? "nothing: no room, furniture or other objects" : out;
}

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
        // A surface the room leaves no points of says so, in the words of every output.
        if (s.points.empty()) {
            summary.push_back({s.name, "-", "", verdictText(s.verdict)});
            continue;
        }
        summary.push_back({s.name, fmt("%.4g ", s.summary.eAvg) + unit, fmt("%.3f", s.summary.u0),
                           verdictText(s.verdict)});
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
        {"Overall size", bounds},
        {"Modelled", geometryText(scene)},
        {"Luminaires", std::to_string(scene.luminaires.size())},
        {"Illuminance", in.evaluation},
    };
    pdf.table({"Design", ""}, rows, {120, kWidth - 120}, {0, 0}, 8.5);
}

/// A product picture's side in the schedule, points.
constexpr double kThumbnail = 36.0;

/// "Product, variant", or the variant alone where its name already holds the product's (as
/// manufacturers often name variants), so that the name is not printed twice.
std::string productAndVariant(const std::string& product, const std::string& variant) {
    if (variant.empty()) return product;
    if (product.empty() || variant.find(product) != std::string::npos) return variant;
    return product + ", " + variant;
}

void scheduleSection(Pdf& pdf, const ReportInput& in) {
    const Scene& scene = *in.scene;
    pdf.section("Luminaire schedule");
    std::vector<ScheduleRow> schedule = luminaireSchedule(scene, true);
    const char* fluxUnit = scene.units().photometric ? "lm" : "W";
    std::vector<std::vector<std::string>> rows;
    std::vector<double> minHeights;
    double totalFlux = 0.0, totalPower = 0.0;
    int count = 0;
    bool anyPicture = false;
    for (const ScheduleRow& r : schedule) {
        rows.push_back({std::to_string(r.count), r.names, "",
                        r.manufacturer.empty() ? "-" : r.manufacturer,
                        r.product.empty() ? shortPath(r.file) : r.product,
                        r.articleNumber.empty() ? "-" : r.articleNumber, fmt("%.5g", r.flux),
                        r.power > 0.0 ? fmt("%.4g", r.power) : "-",
                        r.power > 0.0 ? fmt("%.1f", r.flux / r.power) : "-",
                        fmt("%.3g", r.maintenanceFactor)});
        minHeights.push_back(r.picture ? kThumbnail + 4.0 : 0.0);
        anyPicture = anyPicture || r.picture.has_value();
        totalFlux += r.flux * r.count;
        totalPower += r.power * r.count;
        count += r.count;
    }
    const std::vector<double> widths = {30, 106, 40, 62, 76, 48, 38, 32, 30, 33};
    // Each row's picture in its cell, scaled to fit kThumbnail square.
    auto picture = [&](size_t row, double top) {
        const std::optional<GldfImage>& p = schedule[row].picture;
        if (!p) return;
        double s = kThumbnail / double(std::max(p->width, p->height));
        double w = p->width * s, h = p->height * s;
        double x = kLeft + widths[0] + widths[1] + (widths[2] - w) / 2;
        pdf.image(p->rgb, p->width, p->height, x, top + 2, w, h);
    };
    pdf.table({"Count", "Luminaires", "Picture", "Manufacturer", "Product", "Article no.",
               std::string("Flux [") + fluxUnit + "]", "Power [W]", "lm/W", "MF"},
              rows, widths, {1, 0, 0, 0, 0, 0, 1, 1, 1, 1}, 7.5, minHeights, picture);
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
    if (!anyPicture) pdf.paragraph("Pictures: none of the products' data holds a picture.", 8);
    for (const ScheduleRow& r : schedule)
        if (!r.pictureNotes.empty())
            pdf.paragraph("The picture of " + (r.product.empty() ? r.names : r.product) +
                              " could not be read from the product's data and is left out.",
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

double luminaireInputPower(const Luminaire& luminaire) {
    const PhotometricLuminaire* p = photometricModel(luminaire);
    if (!p || !p->data) return 0.0;
    if (p->gldf)
        if (const GldfLightEmitter* e = p->gldfLightEmitter(); e && e->ratedPower > 0.0)
            return e->ratedPower;
    return p->data->inputWatts > 0.0 ? p->data->inputWatts : 0.0;
}

DatasheetFigures datasheetFigures(const PhotometricData& data) {
    DatasheetFigures f;
    f.flux = data.fluxFromTable();
    // Absolute photometry (the luminaire measured as a whole) states no lamp flux: the ratio of
    // the luminaire's flux to its lamps' does not exist, so it is not shown as a number.
    const bool absolute = !data.keyword({"absolute photometry"}).empty() || !(data.lampFlux > 0.0);
    if (!absolute) {
        f.lampFlux = data.lampFlux;
        f.lightOutputRatio = f.flux / data.lampFlux;
    }
    if (data.declaresLightOutputRatio && data.lightOutputRatio > 0.0)
        f.statedLightOutputRatio = data.lightOutputRatio;
    return f;
}

std::vector<ScheduleRow> luminaireSchedule(const Scene& scene, bool pictures) {
    std::vector<ScheduleRow> rows;
    std::map<std::string, size_t> index;
    UnitSystem units = scene.units();  // once: it looks at every luminaire
    for (size_t k = 0; k < scene.luminaires.size(); ++k) {
        const Luminaire* l = scene.luminaires[k].get();
        ScheduleRow r;
        r.maintenanceFactor = scene.maintenanceFactorOf(*l);
        glm::dvec3 power = l->power() * scene.unitScale(*l, units);
        r.flux = (power.x + power.y + power.z) / 3.0;
        r.kind = std::string(kindName(l->kind()));
        r.power = luminaireInputPower(*l);
        const PhotometricLuminaire* p = photometricModel(*l);
        if (p && p->data) {
            const PhotometricData& d = *p->data;
            r.file = p->file;
            r.flux = d.fluxFromTable() * p->scale;
            r.manufacturer = d.keyword({"MANUFAC", "company", "Manufacturer"});
            r.product = d.name;
            r.articleNumber = d.keyword({"LUMCAT", "CatalogNumber", "luminaire number"});
            if (p->gldf) {
                const GldfProductInfo info = gldfProductInfo(*p->gldf, p->gldfVariant);
                r.kind = "GLDF";
                r.manufacturer = info.manufacturer;
                r.product = productAndVariant(info.product, info.variant);
                r.articleNumber = info.articleNumber;
                r.description = info.description;
            }
        }
        std::string key = describe(*l) + "|" + fmt("%.9g", r.maintenanceFactor) + "|" + r.kind;
        auto it = index.find(key);
        if (it == index.end()) {
            if (pictures && p && p->gldf) {
                const GldfProductInfo info = gldfProductInfo(*p->gldf, p->gldfVariant);
                if (info.picture) {
                    try {
                        r.picture = gldfPicture(readGldfBytes(p->gldf->path), *p->gldf, info,
                                                r.pictureNotes);
                    } catch (const InputError& e) {  // the container is gone since it loaded
                        r.pictureNotes.push_back(e.what());
                    }
                }
            }
            r.names = l->name;
            r.count = 1;
            r.members = {k};
            index[key] = rows.size();
            rows.push_back(r);
        } else {
            ScheduleRow& row = rows[it->second];
            ++row.count;
            row.members.push_back(k);
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
        roomSections(pdf, in);
        scheduleSection(pdf, in);
        datasheetSections(pdf, in);
        surfacesSection(pdf, in);
        powerDensitySection(pdf, in);
        glareSection(pdf, in);
        methodSection(pdf, in);
        if (pass == 1) return pdf.finish();
        contents = pdf.sections;
        pdf.finish();
    }
}

}  // namespace candela
