// `candela glare --table LAMP`: the standard UGR table of a photometric file (CIE 190 tabular
// method, calculation/UgrTable.h) as catalogues print it, with the 4H x 8H reference values, and
// optionally every cell with its intermediate values as CSV.
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/commands/Commands.h"
#include "calculation/UgrTable.h"
#include "luminaires/photometric/PhotometricLuminaire.h"
#include "util/Error.h"
#include "util/FileOutput.h"

namespace candela {

namespace {

namespace fs = std::filesystem;

/// "12.3", or "-" for a cell without glare (nothing in the field of view emits towards the eye).
std::string oneDecimal(double ugr) {
    if (!std::isfinite(ugr)) return "-";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f", ugr);
    return buf;
}

std::string reflectances(const UgrReflectances& r) {
    return std::to_string(r.ceiling) + "/" + std::to_string(r.walls) + "/" +
           std::to_string(r.floor);
}

std::string describeArea(const UgrLuminousArea& a) {
    using S = UgrLuminousArea::Shape;
    char buf[256];
    const auto& h = a.heights;
    switch (a.shape) {
        case S::Box:
            std::snprintf(buf, sizeof buf,
                          "%.4g m along C0-C180 x %.4g m along C90-C270, side heights "
                          "C0/C90/C180/C270 %.4g/%.4g/%.4g/%.4g m",
                          a.alongC0, a.alongC90, h[0], h[1], h[2], h[3]);
            break;
        case S::Round:
            if (a.alongC0 == a.alongC90)
                std::snprintf(buf, sizeof buf,
                              "round, diameter %.4g m, side heights C0/C90/C180/C270 "
                              "%.4g/%.4g/%.4g/%.4g m",
                              a.alongC0, h[0], h[1], h[2], h[3]);
            else
                std::snprintf(buf, sizeof buf,
                              "elliptical, %.4g m along C0-C180 x %.4g m along C90-C270, side "
                              "height %.4g m",
                              a.alongC0, a.alongC90, h[0]);
            break;
        case S::Ellipsoid:
            std::snprintf(buf, sizeof buf, "spherical, %.4g x %.4g x %.4g m", a.alongC0, a.alongC90,
                          h[0]);
            break;
        case S::CylinderAlongC0:
        case S::CylinderAlongC90: {
            bool x = a.shape == S::CylinderAlongC0;
            std::snprintf(buf, sizeof buf, "lying cylinder along %s, %.4g m long, %.4g m across",
                          x ? "C0-C180" : "C90-C270", x ? a.alongC0 : a.alongC90,
                          x ? a.alongC90 : a.alongC0);
            break;
        }
    }
    return buf;
}

void printTable(const UgrTable& t, const std::string& name) {
    std::printf(
        "UGR table of %s%s: CIE 190 tabular method, UGR = 8 log10(0.25 / Lb x sum L2 "
        "omega / p2) (CIE 117)\n",
        t.path.c_str(), name.c_str());
    std::printf(
        "  flux %.6g lm (%s); light output ratio %.1f %%: %.1f %% downward, %.1f %% "
        "upward\n",
        t.flux, t.fluxNote.c_str(), 100.0 * t.lightOutputRatio, 100.0 * t.rDLO, 100.0 * t.rULO);
    std::printf("  luminous area %s (%.4g m2 seen from below; %s)\n", describeArea(t.area).c_str(),
                t.area.bottom(), t.area.note.c_str());
    std::printf("  luminaires every %g H, half a spacing from the walls (%s)\n", t.options.spacing,
                t.options.spacing == 0.25
                    ? "DIALux and Relux's catalogue convention; CIE 190's own table uses 1 H"
                    : "0.25 H is DIALux and Relux's catalogue convention");
    std::printf(
        "  observer at the middle of a wall, eye H below the luminaires, looking across "
        "the room (the table does not depend on H)\n");
    std::printf("  UGR at %.6g lm; at a flux F add 8 log10(F / %.6g lm) (at 1000 lm: %+.2f)\n\n",
                t.flux, t.flux, -8.0 * std::log10(t.flux / 1000.0));
    std::printf(
        "UGR (no unit). Room X across and Y along the line of sight, in units of H;\n"
        "reflectances ceiling/walls/floor in %%.\n");
    std::printf("%-10s %-46s | %s\n", "", "crosswise (C0 facing the eye)",
                "endwise (C90 facing the eye)");
    std::printf("%4s %5s ", "X", "Y");
    for (int view = 0; view < 2; ++view) {
        for (const UgrReflectances& r : kUgrReflectances)
            std::printf(" %8s", reflectances(r).c_str());
        if (view == 0) std::printf("  |");
    }
    std::printf("\n");
    for (const UgrRoomResult& r : t.rooms) {
        std::printf("%3dH %4dH ", r.size.x, r.size.y);
        for (double v : r.crosswise) std::printf(" %8s", oneDecimal(v).c_str());
        std::printf("  |");
        for (double v : r.endwise) std::printf(" %8s", oneDecimal(v).c_str());
        std::printf("\n");
    }
    for (const UgrRoomResult& r : t.rooms)
        if (r.size.x == 4 && r.size.y == 8)
            std::printf(
                "\nreference room 4H x 8H, reflectances 70/50/20 %%: UGR %s crosswise, "
                "%s endwise\n",
                oneDecimal(r.crosswise[0]).c_str(), oneDecimal(r.endwise[0]).c_str());
}

/// One row per cell (room, view, reflectance set; the printed table's order) with what it is
/// made of.
std::string tableCsv(const UgrTable& t) {
    std::string out =
        "X_H,Y_H,room_index_k,luminaires_N,view,ceiling_pct,walls_pct,floor_pct,counted,"
        "sum_L2_omega_over_p2,F_DF,F_DW,F_DC,F_UWID,Lb_cd_m2,UGR,UGR_unrounded\n";
    char line[512];
    for (const UgrRoomResult& r : t.rooms)
        for (int view = 0; view < 2; ++view)
            for (int s = 0; s < kUgrReflectanceCount; ++s) {
                const UgrReflectances& rho = kUgrReflectances[s];
                double ugr = view == 0 ? r.crosswise[s] : r.endwise[s];
                std::string value = std::isfinite(ugr) ? oneDecimal(ugr) : "";
                char exact[32] = "";
                if (std::isfinite(ugr)) std::snprintf(exact, sizeof exact, "%.4f", ugr);
                std::snprintf(line, sizeof line,
                              "%d,%d,%.4f,%d,%s,%d,%d,%d,%d,%.6g,%.6f,%.6f,%.6f,%.6f,%.6g,%s,%s\n",
                              r.size.x, r.size.y, r.roomIndex, r.luminaires,
                              view == 0 ? "crosswise" : "endwise", rho.ceiling, rho.walls,
                              rho.floor, r.counted[view], r.sum[view], r.fDF, r.fDW, r.fDC,
                              r.fUWID[s], r.background[s], value.c_str(), exact);
                out += line;
            }
    return out;
}

std::string lowerExtension(const std::string& path) {
    std::string e = fs::path(path).extension().string();
    for (char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
    return e;
}

}  // namespace

const char* const kSpacingRatioHelp =
    "the luminaires' spacing as a ratio of the mounting height H, 1 / n (0.25 as DIALux and Relux "
    "print it, 1 for CIE 190's 1:1; default 0.25)";

int cmdGlareTable(const Args& args) {
    std::string path, csvPath, spacingText;
    UgrTableOptions options;
    CommandLine cli("glare");
    cli.group("the table form (candela glare --table FILE)");
    cli.option("--table", "FILE",
               "the standard UGR table of this photometry file (.ldt, .ies, .xml or .gldf)",
               [&path](const std::string& v) {
                   if (v.empty())
                       throw InputError("--table: expected a photometry file, got an empty name");
                   path = v;
               });
    cli.option("--spacing-ratio", "R", kSpacingRatioHelp, [&](const std::string& v) {
        spacingText = v;
        options.spacing = parseDouble("--spacing-ratio", v, 0.05, 1.0);
    });
    cli.output("--out", csvPath, "F.csv",
               "also write every cell with its intermediate values as CSV");
    cli.renamed("--csv", "--out");
    cli.renamed("--spacing", "--spacing-ratio");
    if (!cli.parse(args)) return 0;
    if (path.empty())
        throw CommandUsageError("missing --table FILE (the photometry file)", cli.shortHelp());
    double perH = 1.0 / options.spacing;
    if (std::abs(perH - std::round(perH)) > 1e-6)
        throw InputError(
            "--spacing-ratio: expected 1 / n of H (1, 0.5, 0.25, .., 0.05) so that each "
            "standard room holds whole rows of luminaires, got " +
            spacingText);
    std::shared_ptr<const PhotometricData> data;
    std::string name;
    if (lowerExtension(path) == ".gldf") {
        // A GLDF container: its first variant's photometry file (the catalogue table is the
        // photometry file's, not the L3D geometry's).
        PhotometricLuminaire luminaire;
        luminaire.loadGldf(path, "");
        data = luminaire.data;
        name = "GLDF variant \"" + luminaire.gldfVariant + "\"";
    } else {
        data = std::make_shared<PhotometricData>(loadPhotometry(path));
    }
    if (!data->name.empty()) name += (name.empty() ? "\"" : ", \"") + data->name + "\"";
    ProtectedInputs inputs({path, data->path, data->tiltPath});
    checkNotAnInput(csvPath, "--out", "glare --table");
    UgrTable table = computeUgrTable(*data, options);
    table.path = path;
    // The CSV first, so that a file that cannot be written fails before the table is printed.
    if (!csvPath.empty())
        writeFileAtomically(csvPath, tableCsv(table), "cannot write the CSV file");
    printTable(table, name.empty() ? "" : " (" + name + ")");
    if (!csvPath.empty()) std::printf("wrote %s\n", csvPath.c_str());
    return 0;
}

}  // namespace candela
