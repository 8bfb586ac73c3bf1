// The report's calculation surfaces (report/Report.h): each surface's summary against its
// requirement, its false-colour picture with the legend and labelled isolux lines, and the table
// of its values; then the calculation points.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "renderer/passes/TonemapPass.h"
#include "report/ReportSections.h"
#include "shaders/shared/FalseColour.h"

namespace candela::report_detail {

namespace {

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

}  // namespace

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
                          (!s.required.any() ? "-" : verdictText(s.verdict)),
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
}  // namespace candela::report_detail
