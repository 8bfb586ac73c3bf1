// The standard UGR table (calculation/UgrTable.h) against a closed form and a published table: a
// flat Lambertian panel, whose luminance is the same in every direction and whose distribution
// fractions are sin^2 of the zone limits; its invariances (crosswise = endwise for a square or a
// circle, + 8 log10 2 for twice the flux or half the area, nothing for another H); Guth's table
// as CIE 117 prints it; the luminous area as DIALux and Relux project it; the first lamp set's
// flux; refusals; and the 190 cells that eulumdat-ugr computed for a real EULUMDAT file.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "TestUtil.h"
#include "calculation/UgrTable.h"
#include "formats/Photometry.h"
#include "shaders/shared/Constants.h"
#include "util/Error.h"

using namespace candela;

namespace {

using gpu::kPi;
constexpr double kRad = kPi / 180.0;

/// An EULUMDAT file of a flat downward Lambertian panel, I = (1000 / pi) cos gamma cd/klm
/// (1000 lm per 1000 lm of lamp flux: LORL 100 %), rotationally symmetric (Isym 1), gamma every
/// degree so that linear interpolation follows cos gamma within 4e-5 of itself ((1 deg)^2 / 8 in
/// radians). Luminous area `length` x `width` mm (width 0: round), side heights `heights` mm
/// (C0, C90, C180, C270), one lamp set per entry of `sets` (lm).
std::string panelLdt(double length, double width, const std::vector<double>& sets,
                     const std::vector<double>& heights = {0, 0, 0, 0}) {
    std::ostringstream o;
    o.precision(12);
    o << "Candela test\n1\n1\n24\n15\n181\n1\npanel\npanel\npanel\npanel.ldt\ntest\n"
      << length << "\n"
      << (width > 0 ? width : 0) << "\n10\n"
      << length << "\n"
      << width << "\n";
    for (double h : heights) o << h << "\n";
    o << "100\n100\n1\n0\n" << sets.size() << "\n";
    for (double flux : sets) o << "1\nLED\n" << flux << "\n4000\n80\n10\n";
    for (int k = 0; k < 10; ++k) o << "0.5\n";
    for (int c = 0; c < 24; ++c) o << 15 * c << "\n";
    for (int g = 0; g <= 180; ++g) o << g << "\n";
    for (int g = 0; g <= 180; ++g) o << (g < 90 ? 1000.0 / kPi * std::cos(g * kRad) : 0.0) << "\n";
    return o.str();
}

UgrTable panelTable(double length, double width, const std::vector<double>& sets,
                    UgrTableOptions options = {}) {
    return computeUgrTable(parseEulumdat(panelLdt(length, width, sets), "panel.ldt"), options);
}

/// sin^2 g: for I proportional to cos gamma (downward), the fraction of the flux within g of
/// the nadir (the integral of cos g sin g from 0 to g, over its value at 90 degrees).
double fluxWithin(double gDeg) {
    return std::pow(std::sin(gDeg * kRad), 2);
}

double cell(const UgrRoomResult& r, bool crosswise, int set) {
    return crosswise ? r.crosswise[set] : r.endwise[set];
}

}  // namespace

// CIE 117 Table 4.1 at its entries, between them (bilinear) and where it has none.
TEST(UgrTable, GuthTableIsCie117Table41) {
    EXPECT_DOUBLE_EQ(guthTablePositionIndex(0.0, 0.0), 1.0);    // straight ahead
    EXPECT_DOUBLE_EQ(guthTablePositionIndex(1.0, 1.0), 7.00);   // row T/R 1.0, column H/R 1.0
    EXPECT_DOUBLE_EQ(guthTablePositionIndex(2.7, 0.6), 7.50);   // the published oddity, kept
    EXPECT_DOUBLE_EQ(guthTablePositionIndex(0.2, 1.7), 15.70);  // last entry of its row
    // Midway between rows 1.0, 1.1 and columns 1.0, 1.1: the mean of 7.00, 7.90, 7.20, 8.15
    // (rounding of 1.05 x 10 in binary: 1e-12).
    EXPECT_NEAR(guthTablePositionIndex(1.05, 1.05), (7.00 + 7.90 + 7.20 + 8.15) / 4.0, 1e-12);
    EXPECT_EQ(guthTablePositionIndex(0.2, 1.75), 0.0);  // next to a missing entry
    EXPECT_EQ(guthTablePositionIndex(3.1, 0.5), 0.0);   // T/R beyond 3
    EXPECT_EQ(guthTablePositionIndex(1.0, 1.95), 0.0);  // H/R beyond 1.9
}

// A flat Lambertian panel: L = I0 cos g / (A cos g) = Phi / (pi A) towards every luminaire, so
// each cell is 8 log10(0.25 / Lb x L^2 x sum of A cos g_i / (r_i^2 p_i^2)), the sum worked here
// over the grid, and Lb from the distribution fractions in closed form: downward only, F_DF =
// sum of sin^2(g_i) F_GLi at g = 41.4, 60, 75.5, 90 degrees, F_DW = 1 - F_DF, F_DC = 0.
//
// How the code's zonal sums approximate those fractions: at the zone midpoints gamma_m the
// midpoint rule gives each 10-degree zone cos(g_m) sin(g_m) Delta = sin(2 g_m) Delta / 2, the
// exact zone is (sin^2 b - sin^2 a) / 2 = sin(Delta) sin(2 g_m) / 2: the same factor
// sin(Delta) / Delta in every zone, which the scaling to the light output ratio removes. So the
// full zones (60 and 90 degrees) come out exact, checked below. The standard's parts of the
// zones 40-50 and 70-80 degrees, 0.130 and 0.547, are not this distribution's (0.139 and 0.625),
// so the code's fractions below 41.4 and 75.5 degrees fall short of sin^2 by d1 = 0.00158 and
// d3 = 0.00679 (computed below). F_DF is short by d1 F_GL1 + d3 F_GL3, which moves F_UWID by that
// times (F_T,WW-1 - F_T,FW) and UGR by 8 log10 of the ratio: each cell's tolerance is that bound
// (under 0.015 UGR over the table; the largest difference found is 0.015) plus 1e-3 for the
// interpolated cos gamma (4e-5 in I, 3e-4 in UGR).
TEST(UgrTable, LambertianPanelMatchesTheClosedForm) {
    const double length = 0.6, width = 0.3, flux = 3000.0;  // m, m, lm
    UgrTableOptions options;
    UgrTable t = panelTable(length * 1e3, width * 1e3, {flux}, options);
    const double area = length * width, luminance = flux / (kPi * area);
    const double h = options.height, s = options.spacing * h;

    const double g[4] = {41.4, 60.0, 75.5, 90.0};
    const double d1 =
        fluxWithin(41.4) - (fluxWithin(40) + 0.130 * (fluxWithin(50) - fluxWithin(40)));
    const double d3 =
        fluxWithin(75.5) - (fluxWithin(70) + 0.547 * (fluxWithin(80) - fluxWithin(70)));
    EXPECT_NEAR(d1, 0.00158, 1e-5);
    EXPECT_NEAR(d3, 0.00679, 1e-5);
    // The code's fractions: exact at the zone limits 60 and 90 degrees, the standard's parts of a
    // zone at 41.4 and 75.5 (1e-9: the file's 12 digits).
    EXPECT_NEAR(t.rDLO, 1.0, 1e-9);
    EXPECT_NEAR(t.rULO, 0.0, 1e-9);
    EXPECT_NEAR(t.cumulative[0], fluxWithin(41.4) - d1, 1e-9);
    EXPECT_NEAR(t.cumulative[1], fluxWithin(60.0), 1e-9);
    EXPECT_NEAR(t.cumulative[2], fluxWithin(75.5) - d3, 1e-9);
    EXPECT_NEAR(t.cumulative[3], 1.0, 1e-9);
    EXPECT_DOUBLE_EQ(t.flux, flux);

    double largest = 0.0;
    ASSERT_EQ(t.rooms.size(), size_t(kUgrRoomCount));
    for (const UgrRoomResult& r : t.rooms) {
        const double x = r.size.x * h, y = r.size.y * h;
        // The grid: x / s columns symmetric about the line of sight, y / s rows ahead.
        int n = 0;
        double geometric = 0.0;  // sum of A cos g / (r^2 p^2), sr
        for (double tt = s / 2; tt < x / 2; tt += s)
            for (double rr = s / 2; rr < y; rr += s) {
                double gamma = std::atan(std::hypot(tt, rr) / h);
                double p = guthTablePositionIndex(tt / rr, h / rr);
                if (tt / rr > 3.0 || gamma > 85.0 * kRad || !(p > 0.0)) continue;
                double r2 = tt * tt + rr * rr + h * h;
                geometric += 2.0 * area * std::cos(gamma) / (r2 * p * p);  // both sides
                n += 2;
            }
        const int all = int(std::lround(x / s)) * int(std::lround(y / s));
        EXPECT_EQ(r.luminaires, all);
        EXPECT_EQ(r.counted[0], n);
        const double sum = luminance * luminance * geometric;
        // The interpolated cos gamma: 4e-5 in I, 8e-5 in I^2.
        EXPECT_NEAR(r.sum[0], sum, 2e-4 * sum) << r.size.x << "H x " << r.size.y << "H";
        EXPECT_NEAR(r.sum[1], sum, 2e-4 * sum) << r.size.x << "H x " << r.size.y << "H";

        double fDF = 0.0;
        for (int k = 0; k < 4; ++k) fDF += fluxWithin(g[k]) * r.fGL[k];
        const double shortfall = std::abs(d1 * r.fGL[0]) + std::abs(d3 * r.fGL[2]);
        const double wall = flux * all / (2.0 * h * (x + y));  // B, lm/m2
        for (int set = 0; set < kUgrReflectanceCount; ++set) {
            const auto& f = r.fT[set];
            const double fUWID = fDF * f[0] + (1.0 - fDF) * f[1];
            const double lb = wall * fUWID / kPi;
            const double tolerance =
                8.0 * std::log10(1.0 + shortfall * std::abs(f[1] - f[0]) / fUWID) + 1e-3;
            EXPECT_LT(tolerance, 0.016 + 1e-3);
            const double want = 8.0 * std::log10(0.25 / lb * sum);
            for (bool crosswise : {true, false}) {
                double got = cell(r, crosswise, set);
                EXPECT_NEAR(got, want, tolerance)
                    << r.size.x << "H x " << r.size.y << "H, set " << set;
                largest = std::max(largest, std::abs(got - want));
            }
        }
    }
    std::printf("Lambertian panel: largest difference from the closed form %.4f UGR\n", largest);
}

// A square or round panel of a rotationally symmetric distribution looks the same from every
// side: crosswise and endwise agree.
TEST(UgrTable, SymmetricPanelIsTheSameCrosswiseAndEndwise) {
    for (double width : {600.0, 0.0}) {  // square 0.6 x 0.6 m, then a circle 0.6 m across
        UgrTable t = panelTable(600.0, width, {4000.0});
        EXPECT_EQ(t.area.shape,
                  width > 0 ? UgrLuminousArea::Shape::Box : UgrLuminousArea::Shape::Round);
        for (const UgrRoomResult& r : t.rooms)
            for (int set = 0; set < kUgrReflectanceCount; ++set)
                EXPECT_NEAR(r.crosswise[set], r.endwise[set], 1e-9);  // rounding only
    }
    // The circle's area is pi d^2 / 4.
    EXPECT_NEAR(panelTable(600.0, 0.0, {4000.0}).area.bottom(), kPi * 0.09, 1e-12);
}

// L^2 scales as the flux squared, Lb as the flux: UGR(2 Phi) = UGR(Phi) + 8 log10 2 (CIE 190
// eq. 2). At the same flux, half the area doubles L^2 omega = I^2 / (A cos g r^2) and leaves Lb:
// + 8 log10 2 again. H scales the sum and Lb alike (1 / H^2): no change. Exact but for rounding.
TEST(UgrTable, ScalesWithFluxAndAreaAndNotWithHeight) {
    const double step = 8.0 * std::log10(2.0);
    UgrTable base = panelTable(600.0, 300.0, {2000.0});
    UgrTable doubled = panelTable(600.0, 300.0, {4000.0});
    UgrTable half = panelTable(300.0, 300.0, {2000.0});
    UgrTableOptions higher;
    higher.height = 3.7;
    UgrTable tall = panelTable(600.0, 300.0, {2000.0}, higher);
    for (int room = 0; room < kUgrRoomCount; ++room)
        for (int set = 0; set < kUgrReflectanceCount; ++set)
            for (bool crosswise : {true, false}) {
                double u = cell(base.rooms[room], crosswise, set);
                EXPECT_NEAR(cell(doubled.rooms[room], crosswise, set) - u, step, 1e-9);
                EXPECT_NEAR(cell(half.rooms[room], crosswise, set) - u, step, 1e-9);
                EXPECT_NEAR(cell(tall.rooms[room], crosswise, set), u, 1e-9);
            }
}

// The intermediate values hang together: F_DF + F_DW = R_DLO, Lb = B F_UWID / pi, N = XY / S^2
// (4H x 8H: 512 luminaires at 0.25 H, CIE 190's 32 at 1 H).
TEST(UgrTable, IntermediateValuesAreConsistent) {
    for (double spacing : {0.25, 1.0}) {
        UgrTableOptions options;
        options.spacing = spacing;
        UgrTable t = panelTable(600.0, 600.0, {3000.0}, options);
        for (const UgrRoomResult& r : t.rooms) {
            EXPECT_NEAR(r.fDF + r.fDW, t.rDLO, 1e-12);
            EXPECT_EQ(r.luminaires, int(std::lround(r.size.x * r.size.y / (spacing * spacing))));
            if (r.size.x == 4 && r.size.y == 8) {
                EXPECT_EQ(r.luminaires, spacing == 1.0 ? 32 : 512);
            }
            for (int set = 0; set < kUgrReflectanceCount; ++set)
                EXPECT_NEAR(r.background[set], r.wallFlux * r.fUWID[set] / kPi,
                            1e-12 * r.background[set]);
        }
    }
    UgrTableOptions odd;
    odd.spacing = 0.3;  // 2H / 0.3H is not a whole number of columns
    EXPECT_THROW(panelTable(600.0, 600.0, {3000.0}, odd), InputError);
}

// DIALux and Relux take the first lamp set's flux (the intensities are cd/klm of it): a file
// with sets of 1000 and 3000 lm gives the table of a 1000 lm file.
TEST(UgrTable, FirstLampSetGivesTheFlux) {
    UgrTable two = panelTable(600.0, 300.0, {1000.0, 3000.0});
    UgrTable one = panelTable(600.0, 300.0, {1000.0});
    EXPECT_DOUBLE_EQ(two.flux, 1000.0);
    EXPECT_NE(two.fluxNote.find("lamp set 1 of 2"), std::string::npos) << two.fluxNote;
    for (int room = 0; room < kUgrRoomCount; ++room)
        for (int set = 0; set < kUgrReflectanceCount; ++set)
            EXPECT_NEAR(two.rooms[room].crosswise[set], one.rooms[room].crosswise[set], 1e-9);
}

// The EULUMDAT luminous area as Relux projects it: the length runs along C90-C270, so seen from
// C0 the side is length x h_C0. Relux prints 1677 cd/m2 at C0, gamma 65 for a 1208 x 105 mm
// area with h_C0 = h_C180 = 51 mm and I = 92.55 cd/klm x 1983 lm (eulumdat-luminance's
// relux_reference.json, sample_06): 183.5 cd / (l b cos 65 + l h sin 65). The other reading
// (b x h_C0) would give 3139 cd/m2. Within 1 cd/m2: Relux prints whole cd/m2.
TEST(UgrTable, LuminousAreaProjectsAsReluxDoes) {
    PhotometricData d =
        parseEulumdat(panelLdt(1208.0, 105.0, {1983.0}, {51.0, 0.0, 51.0, 0.0}), "side.ldt");
    UgrLuminousArea a = ugrLuminousArea(d);
    EXPECT_EQ(a.shape, UgrLuminousArea::Shape::Box);
    EXPECT_DOUBLE_EQ(a.alongC90, 1.208);
    const double l = 1.208, b = 0.105, hc0 = 0.051, g = 65.0 * kRad;
    EXPECT_NEAR(a.projected(0.0, 65.0), l * b * std::cos(g) + l * hc0 * std::sin(g), 1e-12);
    EXPECT_NEAR(a.projected(180.0, 65.0), a.projected(0.0, 65.0), 1e-12);
    EXPECT_NEAR(a.projected(90.0, 65.0), l * b * std::cos(g), 1e-12);  // h_C90 = 0
    EXPECT_NEAR(92.55 * 1.983 / a.projected(0.0, 65.0), 1677.0, 1.0);
    EXPECT_NEAR(a.bottom(), l * b, 1e-12);
}

// The renderer's opening reads the EULUMDAT length along the same axis as the UGR table (until
// 2026-11-26 it put it along C0, turning linear luminaires' rectangles by 90 degrees).
TEST(UgrTable, RendererOpeningAgreesWithTheLuminousArea) {
    PhotometricData d =
        parseEulumdat(panelLdt(1208.0, 105.0, {1983.0}, {51.0, 0.0, 51.0, 0.0}), "side.ldt");
    UgrLuminousArea a = ugrLuminousArea(d);
    EXPECT_DOUBLE_EQ(d.opening.length, a.alongC0);
    EXPECT_DOUBLE_EQ(d.opening.width, a.alongC90);
}

TEST(UgrTable, FilesWithoutALuminousAreaAreRefused) {
    PhotometricData ldt = parseEulumdat(panelLdt(0.0, 0.0, {1000.0}), "dot.ldt");
    PhotometricData ies = parseIes(
        "IESNA:LM-63-2002\n[TEST] point\nTILT=NONE\n1 -1 1 3 1 1 2 0 0 0\n1 1 10\n0 45 90\n0\n"
        "100 70 0\n",
        "dot.ies");
    for (const PhotometricData* d : {&ldt, &ies}) {
        try {
            computeUgrTable(*d);
            ADD_FAILURE() << d->path << ": no InputError";
        } catch (const InputError& e) {
            std::string m = e.what();
            EXPECT_EQ(m.rfind(d->path + ": no luminous area", 0), 0u) << m;
            EXPECT_NE(m.find("luminance"), std::string::npos) << m;
            EXPECT_EQ(m.find('\n'), std::string::npos) << m;
        }
    }
}

// An IES file's opening: the same panel written as an absolute IES file (0.6 x 0.3 m, I0 =
// 3000 / pi cd) gives the EULUMDAT panel's table (the flux from the table's integral, within
// 1e-4 of 3000 lm: 8 log10(1 + 1e-4) = 3e-4 UGR; 1e-3).
TEST(UgrTable, IesPanelMatchesTheEulumdatPanel) {
    std::ostringstream o;
    o.precision(12);
    o << "IESNA:LM-63-2002\n[TEST] panel\nTILT=NONE\n1 -1 1 181 1 1 2 0.3 0.6 0\n1 1 10\n";
    for (int g = 0; g <= 180; ++g) o << g << " ";
    o << "\n0\n";
    for (int g = 0; g <= 180; ++g) o << (g < 90 ? 3000.0 / kPi * std::cos(g * kRad) : 0.0) << " ";
    UgrTable ies = computeUgrTable(parseIes(o.str() + "\n", "panel.ies"));
    UgrTable ldt = panelTable(600.0, 300.0, {3000.0});
    EXPECT_NEAR(ies.flux, 3000.0, 0.3);
    for (int room = 0; room < kUgrRoomCount; ++room)
        for (int set = 0; set < kUgrReflectanceCount; ++set)
            for (bool crosswise : {true, false})
                EXPECT_NEAR(cell(ies.rooms[room], crosswise, set),
                            cell(ldt.rooms[room], crosswise, set), 1e-3);
}

// The published table: eulumdat-ugr v1.0.x's 19 x 10 table for sample_02_isym4.ldt (tests/data/
// ugr/LICENSE.md; eulumdat-ugr's README reports agreement with Relux within 0.43 and DIALux within
// 1.01). Tolerance 0.2 UGR: the published values are rounded to 0.1 (0.05), and independent
// reproductions of the method (this one and a separate Python one) both sit 0.0-0.12 above them
// (mean +0.05), from details of eulumdat-ugr's interpolation not published; 0.2 still catches
// the conventions that matter (crosswise and endwise swapped: 2-3 UGR; spacing 1 H: 2-9 UGR).
TEST(UgrTable, MatchesThePublishedTableOfARealLuminaire) {
    const double published[kUgrRoomCount][10] = {
        {17.1, 18.2, 17.5, 18.5, 18.8, 19.9, 21.0, 20.3, 21.3, 21.6},
        {17.5, 18.4, 17.8, 18.7, 19.1, 19.9, 20.9, 20.3, 21.2, 21.6},
        {17.6, 18.5, 18.0, 18.8, 19.2, 19.9, 20.8, 20.3, 21.2, 21.5},
        {17.7, 18.5, 18.1, 18.9, 19.3, 19.9, 20.7, 20.4, 21.1, 21.5},
        {17.7, 18.5, 18.2, 18.9, 19.3, 19.9, 20.7, 20.4, 21.1, 21.5},
        {17.7, 18.4, 18.1, 18.8, 19.2, 19.9, 20.6, 20.4, 21.0, 21.4},
        {17.1, 17.9, 17.5, 18.3, 18.7, 19.7, 20.6, 20.1, 21.0, 21.3},
        {17.5, 18.2, 17.9, 18.6, 19.0, 19.8, 20.5, 20.2, 20.9, 21.3},
        {17.7, 18.4, 18.2, 18.8, 19.2, 19.9, 20.5, 20.3, 20.9, 21.4},
        {17.9, 18.5, 18.4, 18.9, 19.4, 19.9, 20.5, 20.4, 20.9, 21.4},
        {17.9, 18.4, 18.4, 18.9, 19.3, 19.9, 20.4, 20.4, 20.9, 21.4},
        {17.9, 18.3, 18.4, 18.8, 19.3, 19.9, 20.4, 20.4, 20.9, 21.3},
        {17.7, 18.2, 18.2, 18.7, 19.1, 19.8, 20.3, 20.3, 20.7, 21.2},
        {17.9, 18.3, 18.4, 18.8, 19.3, 19.9, 20.3, 20.4, 20.8, 21.3},
        {17.9, 18.3, 18.5, 18.8, 19.3, 19.9, 20.3, 20.5, 20.8, 21.3},
        {17.9, 18.2, 18.4, 18.7, 19.3, 20.0, 20.3, 20.5, 20.8, 21.3},
        {17.7, 18.1, 18.2, 18.6, 19.1, 19.7, 20.2, 20.2, 20.6, 21.1},
        {17.9, 18.3, 18.4, 18.7, 19.3, 19.8, 20.2, 20.4, 20.7, 21.2},
        {17.9, 18.2, 18.4, 18.7, 19.3, 19.9, 20.2, 20.4, 20.7, 21.3},
    };
    UgrTable t = computeUgrTable(loadPhotometry(test::dataDir() + "/ugr/sample_02_isym4.ldt"));
    EXPECT_DOUBLE_EQ(t.flux, 12334.0);
    // LORL 100 %, all but the file's few hundredths of a cd/klm above 90 degrees downward.
    EXPECT_NEAR(t.rDLO + t.rULO, 1.0, 1e-12);
    EXPECT_LT(t.rULO, 1e-4);
    double largest = 0.0, mean = 0.0;
    for (int room = 0; room < kUgrRoomCount; ++room)
        for (int col = 0; col < 10; ++col) {
            double got = col < 5 ? t.rooms[room].crosswise[col] : t.rooms[room].endwise[col - 5];
            double diff = got - published[room][col];
            EXPECT_NEAR(got, published[room][col], 0.2)
                << kUgrRoomSizes[room].x << "H x " << kUgrRoomSizes[room].y << "H, column " << col;
            largest = std::max(largest, std::abs(diff));
            mean += diff / (kUgrRoomCount * 10);
        }
    std::printf(
        "sample_02_isym4.ldt: largest difference from the published table %.3f UGR, "
        "mean %+.3f\n",
        largest, mean);
}
