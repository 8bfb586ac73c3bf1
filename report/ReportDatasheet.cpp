// The report's datasheets (report/Report.h): one per distinct photometry, as a catalogue prints
// it: the product (manufacturer, name, article number, description, picture), its figures
// (luminaire and lamp flux, input power, efficacy, light output ratio), its polar diagram in
// cd/klm and its standard UGR table (calculation/UgrTable.h, the table `candela glare --table`
// prints).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "calculation/UgrTable.h"
#include "luminaires/photometric/PhotometricLuminaire.h"
#include "report/PolarDiagram.h"
#include "report/ReportSections.h"
#include "scene/Scene.h"

namespace candela::report_detail {

double perKilolumen(const PhotometricData& d, double scale) {
    double basis = d.lampFlux > 0.0 ? d.lampFlux * scale : d.fluxFromTable() * scale;
    return basis > 0.0 ? 1000.0 / basis : 0.0;
}

namespace {

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
/// A UGR value as catalogues print it: one decimal, "-" where no luminaire in view emits towards
/// the eye.
std::string ugrText(double ugr) {
    return std::isfinite(ugr) ? fmt("%.1f", ugr) : "-";
}

/// The standard UGR table of `data` (CIE 190 tabular method), rows of room sizes, crosswise and
/// endwise under the five reflectance sets.
void ugrTable(Pdf& pdf, const PhotometricData& data) {
    UgrTable t;
    try {
        t = computeUgrTable(data);
    } catch (const InputError& e) {
        pdf.heading("UGR table", 11);
        pdf.paragraph("No UGR table: " + withoutPath(e.what()) + ".", 8);
        return;
    }
    pdf.need(19 * 10.4 + 110);
    pdf.heading("UGR table (CIE 190 tabular method)", 11);
    pdf.paragraph(
        "The Unified Glare Rating (no unit) in the standard rooms catalogues tabulate: an observer "
        "at the middle of one wall looking across the room, luminaires every " +
            fmt("%g", t.options.spacing) +
            " H over the ceiling (H: their height above the eye), room X across and Y along the "
            "line of sight in units of H, reflectances of ceiling, walls and floor in %. "
            "Crosswise the luminaire's C0 plane faces the observer, endwise its C90 plane. At " +
            fmt("%.6g lm", t.flux) + " (" + t.fluxNote + "); at another flux F add 8 log10(F / " +
            fmt("%.6g lm", t.flux) + ").",
        7.5);
    pdf.font(7, true);
    const double first = 2 * 30.0, half = (kWidth - first) / 2;
    pdf.text(kLeft + first + half / 2, pdf.y + 7, "Crosswise", 0.5);
    pdf.text(kLeft + first + half * 1.5, pdf.y + 7, "Endwise", 0.5);
    pdf.y += 10;
    std::vector<std::string> header = {"X", "Y"};
    std::vector<double> widths = {30, 30}, align = {1, 1};
    for (int view = 0; view < 2; ++view)
        for (const UgrReflectances& r : kUgrReflectances) {
            header.push_back(std::to_string(r.ceiling) + "/" + std::to_string(r.walls) + "/" +
                             std::to_string(r.floor));
            widths.push_back(half / kUgrReflectanceCount);
            align.push_back(1);
        }
    std::vector<std::vector<std::string>> rows;
    for (const UgrRoomResult& r : t.rooms) {
        std::vector<std::string> row = {std::to_string(r.size.x) + "H",
                                        std::to_string(r.size.y) + "H"};
        for (double v : r.crosswise) row.push_back(ugrText(v));
        for (double v : r.endwise) row.push_back(ugrText(v));
        rows.push_back(std::move(row));
    }
    pdf.table(header, rows, widths, align, 7);
    for (const UgrRoomResult& r : t.rooms)
        if (r.size.x == 4 && r.size.y == 8)
            pdf.paragraph("Reference room 4H x 8H, reflectances 70/50/20 %: UGR " +
                              ugrText(r.crosswise[0]) + " crosswise, " + ugrText(r.endwise[0]) +
                              " endwise.",
                          8);
}

/// "93.2 %", from a ratio.
std::string percent(double ratio) {
    return fmt("%.1f %%", 100.0 * ratio);
}

/// One datasheet: the product, its figures, its polar diagram and its UGR table.
void datasheet(Pdf& pdf, const ScheduleRow& row, const PhotometricLuminaire& p) {
    const PhotometricData& d = *p.data;
    std::string title = !row.product.empty() ? row.product : !d.name.empty() ? d.name : "luminaire";
    pdf.section("Datasheet: " + title);
    const DatasheetFigures f = datasheetFigures(d);
    const double flux = f.flux * p.scale;
    std::vector<std::vector<std::string>> rows;
    auto add = [&rows](const std::string& what, const std::string& value) {
        if (!value.empty()) rows.push_back({what, value});
    };
    add("Manufacturer", row.manufacturer.empty() ? "not stated" : row.manufacturer);
    add("Product", title);
    add("Article number", row.articleNumber.empty() ? "not stated" : row.articleNumber);
    add("Description", row.description);
    add("Used in this design", std::to_string(row.count) + " (" + row.names + ")");
    add("Luminaire flux",
        fmt("%.5g lm", flux) +
            (p.scale != 1.0
                 ? fmt(" (dimmed to %.3g of the file's ", p.scale) + fmt("%.5g lm)", f.flux)
                 : std::string(" (the integral of its intensity table)")));
    if (f.lightOutputRatio >= 0.0) {
        add("Lamp flux", fmt("%.5g lm", f.lampFlux) + " (rated, as the file states it)");
        std::string lor = percent(f.lightOutputRatio) + " (luminaire flux " +
                          fmt("%.5g lm", f.flux) + " / lamp flux " + fmt("%.5g lm", f.lampFlux) +
                          ")";
        if (f.statedLightOutputRatio > 0.0)
            lor += "; the file states " + percent(f.statedLightOutputRatio);
        add("Light output ratio", lor);
    } else {
        add("Lamp flux", "none: absolute photometry");
        add("Light output ratio",
            "not applicable: the luminaire was measured as a whole (absolute photometry), so "
            "there is no separate lamp flux to compare its output with");
    }
    add("Input power", row.power > 0.0 ? fmt("%.4g W", row.power) : "not stated");
    add("Efficacy",
        row.power > 0.0 ? fmt("%.1f lm/W", flux / row.power) : "not known (no input power stated)");
    add("Peak intensity",
        fmt("%.5g cd", d.maxIntensity() * p.scale) +
            fmt(" (%.4g cd/klm)", d.maxIntensity() * p.scale * perKilolumen(d, p.scale)));
    // The picture beside the figures, the table narrower to leave it room.
    const double pictureBox = row.picture ? 110.0 : 0.0;
    const double top = pdf.y;
    pdf.table({"Figure", "Value"}, rows,
              {100, kWidth - 100 - pictureBox - (pictureBox > 0 ? 10 : 0)}, {0, 0}, 8);
    if (row.picture) {
        const GldfImage& image = *row.picture;
        double s = pictureBox / double(std::max(image.width, image.height));
        pdf.image(image.rgb, image.width, image.height, kRight - image.width * s, top,
                  image.width * s, image.height * s);
        pdf.y = std::max(pdf.y, top + image.height * s + 8);
    }
    const double size = 250.0;
    pdf.need(size + 60);
    pdf.heading("Polar diagram", 11);
    pdf.paragraph(
        "Luminous intensity in cd/klm (candela per 1000 lm of the luminaire's lamps, or of the "
        "luminaire for absolute photometry), straight down at the bottom: the C0-C180 plane solid "
        "(orange), the C90-C270 plane dashed (blue).",
        7.5);
    const double y0 = pdf.y;
    polarDiagram(pdf, d, p.scale * perKilolumen(d, p.scale), kLeft + (kWidth - size) / 2, y0, size);
    pdf.y = y0 + size + 8;
    ugrTable(pdf, d);
}

}  // namespace

void datasheetSections(Pdf& pdf, const ReportInput& in) {
    const Scene& scene = *in.scene;
    const std::vector<ScheduleRow> schedule = luminaireSchedule(scene, true);
    // One per distinct photometry (file and dimming), with the first schedule row that uses it.
    std::vector<const PhotometricLuminaire*> distinct;
    for (const ScheduleRow& row : schedule) {
        const PhotometricLuminaire* p = photometricModel(*scene.luminaires[row.members.front()]);
        if (!p || !p->data) continue;
        bool seen = std::any_of(distinct.begin(), distinct.end(), [&](const auto* q) {
            return q->data == p->data && q->scale == p->scale;
        });
        if (seen) continue;
        distinct.push_back(p);
        datasheet(pdf, row, *p);
    }
}

}  // namespace candela::report_detail
