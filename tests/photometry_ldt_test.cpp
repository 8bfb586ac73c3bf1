// EULUMDAT parsing: every Isym unfolded and scaled, the shared files' symmetry, lamp flux times
// LOR against the table, and defects reported with their line (split from photometry_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "PhotometryTestUtil.h"
#include "TestUtil.h"
#include "formats/Photometry.h"

namespace candela {
namespace {

using namespace phototest;
constexpr double kDeg = std::numbers::pi / 180.0;

// ---------------------------------------------------------------------------------------------
// EULUMDAT

/// A hand-made EULUMDAT file for symmetry `isym` with Mc = 24 planes (15 degrees), Ng gamma
/// angles from `gammas` (Dg = 0), intensities f(C, gamma) in cd/klm for the planes Isym needs.
std::string makeLdt(int isym, const std::vector<double>& gammas,
                    const std::function<double(double, double)>& f,
                    const std::string& lampCount = "1", bool decimalComma = false) {
    const int mc = 24;
    std::ostringstream s;
    s.precision(17);
    auto num = [&](double v) {
        std::ostringstream t;
        t.precision(17);
        t << v;
        std::string out = t.str();
        if (decimalComma) std::replace(out.begin(), out.end(), '.', ',');
        return out;
    };
    s << "Test company\n1\n"
      << isym << "\n"
      << mc << "\n15\n"
      << gammas.size() << "\n0\nREPORT\nTest luminaire\n"
      << "NUM\nfile.ldt\ndate\n600\n0\n50\n500\n0\n0\n0\n0\n0\n100\n"
      << num(80.5) << "\n1\n0\n1\n"
      << lampCount << "\nLED\n"
      << num(2000) << "\n3000K\n80\n20\n";
    for (int k = 0; k < 10; ++k) s << "0.5\n";
    for (int k = 0; k < mc; ++k) s << k * 15 << "\n";
    for (double g : gammas) s << num(g) << "\n";
    int first = 0, planes = mc;
    if (isym == 1) planes = 1;
    if (isym == 2) planes = mc / 2 + 1;
    if (isym == 3) first = mc / 4, planes = mc / 2 + 1;
    if (isym == 4) planes = mc / 4 + 1;
    for (int p = first; p < first + planes; ++p)
        for (double g : gammas) s << num(f(p * 15.0, g)) << "\n";
    return s.str();
}

TEST(PhotometryLdt, EachIsymUnfoldsAndScales) {
    std::vector<double> gammas = {0, 5, 20, 45, 60, 90, 120, 180};  // non-equidistant (Dg = 0)
    // f is built to have the symmetry of each Isym, so the unfolded table equals f everywhere on
    // the nodes (exact to 1e-9 cd).
    std::map<int, std::function<double(double, double)>> funcs = {
        {0, [](double c, double g) { return 100.0 + g + 0.5 * c; }},
        {1, [](double, double g) { return 100.0 + g; }},
        {2, [](double c, double g) { return 100.0 + g + std::abs(c <= 180 ? c : 360 - c); }},
        {3,
         [](double c, double g) {
             return 100.0 + g + std::abs(std::sin(c * kDeg) * 30.0) + (c > 90 && c < 270 ? c : 0);
         }},
        {4, [](double c, double g) { return 100.0 + g + 20.0 * std::abs(std::sin(c * kDeg)); }}};
    const PhotometricSymmetry expected[] = {
        PhotometricSymmetry::None, PhotometricSymmetry::Axial, PhotometricSymmetry::PlaneC0C180,
        PhotometricSymmetry::PlaneC90C270, PhotometricSymmetry::Quadrant};
    for (int isym = 0; isym <= 4; ++isym) {
        auto f = funcs[isym];
        // Isym 3: the function must itself be mirror-symmetric about C90-C270 (C -> 180 - C).
        std::function<double(double, double)> sym = f;
        if (isym == 3)
            sym = [f](double c, double g) {
                return (c >= 90 && c <= 270) ? f(c, g) : f(c < 90 ? 180 - c : 540 - c, g);
            };
        PhotometricData d = parseEulumdat(makeLdt(isym, gammas, sym), "t.ldt");
        EXPECT_EQ(d.symmetry, expected[isym]);
        EXPECT_EQ(d.vertical, gammas);
        EXPECT_NEAR(d.lightOutputRatio, 0.805, 1e-12);
        EXPECT_EQ(d.lampFlux, 2000.0);
        // cd = cd/klm x 2000 lm / 1000.
        for (int c = 0; c < 360; c += 15)
            for (double g : gammas)
                if (g > 0.0 && g < 180.0) {  // at the poles every C plane is the same direction
                    EXPECT_NEAR(d.intensity(dirC(g, c)), 2.0 * sym(isym == 1 ? 0.0 : c, g), 1e-9)
                        << "Isym " << isym << " C" << c << " gamma " << g;
                }
        expectValidTable(d, "Isym " + std::to_string(isym));
        // Round luminous area (width 0), 500 mm diameter.
        EXPECT_EQ(d.opening.shape, LuminousOpening::Shape::Ellipse);
        EXPECT_DOUBLE_EQ(d.opening.length, 0.5);
        EXPECT_DOUBLE_EQ(d.opening.width, 0.5);
    }
    // Decimal commas and a negative lamp count (absolute photometry marker) read the same.
    auto f0 = funcs[0];
    PhotometricData plain = parseEulumdat(makeLdt(0, gammas, f0), "t.ldt");
    PhotometricData comma = parseEulumdat(makeLdt(0, gammas, f0, "-1", true), "t.ldt");
    EXPECT_EQ(plain.candela, comma.candela);
    EXPECT_NEAR(comma.lightOutputRatio, 0.805, 1e-12);
    bool absolute = false;
    for (const auto& [k, v] : comma.keywords) absolute = absolute || k == "absolute photometry";
    EXPECT_TRUE(absolute);
}

TEST(PhotometryLdt, SharedSymmetryFilesMirror) {
    std::string dir = photometryDir() + "/ldt/photometric-viewer/";
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> gamma(0.0, 180.0), azim(0.0, 360.0);
    struct Case {
        const char* file;
        std::function<double(double)> mirror;
    };
    std::vector<Case> cases = {
        {"symmetry_to_c0c180.ldt", [](double c) { return 360.0 - c; }},
        {"symmetry_to_c90c270.ldt", [](double c) { return std::fmod(540.0 - c, 360.0); }},
        {"symmetry_to_c0c90c180c270.ldt", [](double c) { return std::fmod(180.0 + c, 360.0); }},
        {"symmetry_to_c0c90c180c270.ldt", [](double c) { return 360.0 - c; }},
        {"symmetry_about_vertical_axis.ldt", [](double c) { return std::fmod(c + 77.0, 360.0); }}};
    for (const Case& k : cases) {
        PhotometricData d = loadPhotometry(dir + k.file);
        for (int n = 0; n < 200; ++n) {
            double g = gamma(rng), c = azim(rng);
            EXPECT_NEAR(d.intensity(dirC(g, c)), d.intensity(dirC(g, k.mirror(c))), 1e-9) << k.file;
        }
    }
}

// The luminous area's length runs along C90-C270, the luminaire's long axis (EN 13032-1's C
// planes: C0-C180 crosswise, C90-C270 lengthwise), its width along C0-C180. lidrs/example.ldt is
// a linear luminaire (Ityp 2) with a 1195 x 210 mm luminous area: its emitting polygon spans
// 0.21 m along local x (C0) and 1.195 m along local y (C90).
TEST(PhotometryLdt, LuminousAreaLengthRunsAlongC90) {
    PhotometricData d = loadPhotometry(photometryDir() + "/ldt/lidrs/example.ldt");
    EXPECT_EQ(d.opening.shape, LuminousOpening::Shape::Rectangle);
    EXPECT_DOUBLE_EQ(d.opening.length, 0.210);  // along C0-C180: the file's width
    EXPECT_DOUBLE_EQ(d.opening.width, 1.195);   // along C90-C270: the file's length
    glm::dvec2 lo(1e9), hi(-1e9);
    for (const glm::dvec2& v : d.opening.polygon()) lo = glm::min(lo, v), hi = glm::max(hi, v);
    EXPECT_NEAR(hi.x - lo.x, 0.210, 1e-12);
    EXPECT_NEAR(hi.y - lo.y, 1.195, 1e-12);
    // A round area (width 0) is a circle of the length's diameter, whichever axis.
    PhotometricData round =
        loadPhotometry(photometryDir() +
                       "/ldt/photometric-viewer/rectangular_luminaire_round_luminous_opening.ldt");
    EXPECT_EQ(round.opening.length, round.opening.width);
    EXPECT_DOUBLE_EQ(round.opening.length, 0.050);
}

TEST(PhotometryLdt, LampFluxTimesLorAgainstTable) {
    // For a consistent file, flux from the table = lamp flux x LOR. Files found inconsistent
    // are reported (printed) and not forced: the photometric-viewer dummies reuse one made-up
    // curve with LORL 100 %.
    const std::map<std::string, bool> consistent = {{"lidrs/example.ldt", true}};
    for (const fs::path& p : sharedFiles(false)) {
        if (p.extension() != ".ldt") continue;
        PhotometricData d = loadPhotometry(p.string());
        double expected = d.declaredFlux();
        if (expected == 0.0) continue;  // lenient/lorl_zero.ldt declares no luminaire flux
        double ratio = d.fluxFromTable() / expected;
        std::string rel = fs::relative(p, photometryDir() + "/ldt").string();
        std::printf("%-70s table %10.2f lm, lamp x LOR %10.2f lm, ratio %.4f%s\n", rel.c_str(),
                    d.fluxFromTable(), expected, ratio,
                    consistent.count(rel) ? "" : "  (inconsistent file)");
        if (consistent.count(rel)) {
            EXPECT_NEAR(ratio, 1.0, 0.01) << rel;  // 1 %: rounding of the published cd/klm values
        }
    }
}

TEST(PhotometryLdt, DefectsAreReportedWithLine) {
    std::vector<double> gammas = {0, 45, 90};
    auto f = [](double, double) { return 10.0; };
    std::string good = makeLdt(0, gammas, f);
    ASSERT_NO_THROW(parseEulumdat(good, "t.ldt"));
    auto expectError = [](const std::string& text, const std::string& needle) {
        try {
            parseEulumdat(text, "t.ldt");
            ADD_FAILURE() << "no exception for " << needle;
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
        }
    };
    std::string bad = good;
    bad.replace(bad.find("\n1\n0\n"), 5, "\n1\n7\n");  // Isym 7
    expectError(bad, "t.ldt:3: expected symmetry indicator Isym (an integer from 0 to 4), found 7");
    expectError(good.substr(0, good.find("Test luminaire")),
                "t.ldt:8: expected luminaire name on line 9, found the end");
    // 24 planes x 3 values = 72 intensities; drop the last line.
    std::string cut = good.substr(0, good.rfind('\n', good.size() - 2) + 1);
    expectError(cut,
                "expected 72 intensities (cd/klm, 24 C planes x 3 gamma angles), found only 71");
    std::string neg = good.substr(0, good.rfind('\n', good.size() - 2) + 1) + "-3\n";
    expectError(neg, "expected non-negative intensities (C345, gamma 90), found -3");
}

}  // namespace
}  // namespace candela
