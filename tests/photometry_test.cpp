// Far-field photometry: IES LM-63 and EULUMDAT parsers, symmetry unfolding, bilinear evaluation
// and the exact flux of the table (formats/Photometry.h).

#include "formats/Photometry.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <numbers>
#include <random>
#include <sstream>
#include <stdexcept>

#include "PhotometryTestUtil.h"
#include "TestUtil.h"

namespace candela {
namespace {

namespace fs = std::filesystem;
using namespace phototest;
constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

std::string readFile(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

glm::dvec3 dirB(double hDeg, double vDeg) {
    double h = hDeg * kDeg, v = vDeg * kDeg;
    return {std::cos(v) * std::sin(h), std::sin(v), std::cos(v) * std::cos(h)};
}

std::vector<double> range(double a, double b, double step) {
    std::vector<double> r;
    int n = int(std::lround((b - a) / step));
    for (int k = 0; k <= n; ++k) r.push_back(a + step * k);
    return r;
}

/// A hand-made IES file.
struct Ies {
    std::string header = "IESNA:LM-63-2002";
    std::string keywords = "[TEST] hand-made\n[LUMINAIRE] test luminaire\n";
    std::string tilt = "TILT=NONE\n";
    int lamps = 1;
    double lumens = 1000.0, multiplier = 1.0;
    int type = 1, units = 2;
    double width = 0.0, length = 0.0, height = 0.0;
    double ballast = 1.0, blp = 1.0, watts = 10.0;
    std::vector<double> v, h;
    std::function<double(double v, double h)> f;

    std::string text() const {
        std::ostringstream s;
        s.precision(17);
        if (!header.empty()) s << header << "\n";
        s << keywords << tilt;
        s << lamps << " " << lumens << " " << multiplier << " " << v.size() << " " << h.size()
          << " " << type << " " << units << " " << width << " " << length << " " << height << "\n";
        s << ballast << " " << blp << " " << watts << "\n";
        for (double a : v) s << a << " ";
        s << "\n";
        for (double a : h) s << a << " ";
        s << "\n";
        for (double hh : h) {
            for (double vv : v) s << f(vv, hh) << " ";
            s << "\n";
        }
        return s.str();
    }
    PhotometricData parse(const std::string& path = "test.ies") const {
        return parseIes(text(), path);
    }
};

/// Independent check of fluxFromTable(): midpoint rule over a (gamma, azimuth) grid of
/// directions with the sin(gamma) solid-angle weight, evaluating intensity() only. gamma = 90 is
/// a cell boundary, so the jump at the horizon of a hemisphere-only table costs nothing.
double bruteForceFlux(const PhotometricData& d, int ngamma = 2048, int nphi = 1024) {
    double sum = 0.0;
    for (int i = 0; i < ngamma; ++i) {
        double g = (i + 0.5) * kPi / ngamma;
        double row = 0.0;
        for (int j = 0; j < nphi; ++j) {
            double phi = (j + 0.5) * 2.0 * kPi / nphi;
            row += d.intensity(
                {std::sin(g) * std::cos(phi), std::sin(g) * std::sin(phi), std::cos(g)});
        }
        sum += row * std::sin(g);
    }
    return sum * (kPi / ngamma) * (2.0 * kPi / nphi);
}

const char* symmetryName(PhotometricSymmetry s) {
    switch (s) {
        case PhotometricSymmetry::None:
            return "none";
        case PhotometricSymmetry::Axial:
            return "axial";
        case PhotometricSymmetry::Quadrant:
            return "quadrant";
        case PhotometricSymmetry::PlaneC0C180:
            return "C0-C180";
        case PhotometricSymmetry::PlaneC90C270:
            return "C90-C270";
    }
    return "?";
}

// ---------------------------------------------------------------------------------------------
// Shared files

TEST(PhotometryFiles, EveryWellFormedFileLoadsAndPrintsSummary) {
    std::vector<fs::path> files = sharedFiles(false);
    // 37 well-formed .ies + 17 .ldt copied from the shared test data, 5 synthetic lenient files
    // (lenient/, loaded with warnings: tests/photometry_leniency_test.cpp).
    ASSERT_EQ(files.size(), 59u);
    std::printf("%-72s %-15s %-4s %-9s %-9s %12s %10s %8s\n", "file", "format", "type", "symmetry",
                "v x h", "flux(lm)", "lamp(lm)", "ratio");
    for (const fs::path& p : files) {
        PhotometricData d;
        ASSERT_NO_THROW(d = loadPhotometry(p.string())) << p;
        expectValidTable(d, p.string());
        double flux = d.fluxFromTable();
        std::string rel = fs::relative(p, photometryDir()).string();
        std::string counts =
            std::to_string(d.vertical.size()) + "x" + std::to_string(d.horizontal.size());
        std::printf("%-72s %-15s %-4s %-9s %-9s %12.2f %10.1f %8.4f\n", rel.c_str(),
                    d.format.c_str(), d.goniometer == Goniometer::C ? "C" : "B",
                    symmetryName(d.symmetry), counts.c_str(), flux, d.lampFlux,
                    d.lampFlux > 0.0 ? flux / d.lampFlux : 0.0);
    }
}

TEST(PhotometryFiles, BrokenFilesThrowWithFileAndLine) {
    std::string invalid = photometryDir() + "/ies/ies_rescale/Invalid Profile - 01.ies";
    try {
        loadPhotometry(invalid);
        FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
        std::string m = e.what();
        EXPECT_NE(m.find(invalid + ":1: expected a TILT= line"), std::string::npos) << m;
    }
    // Truncated after the fourth of the ten numbers on line 24.
    std::string truncated = photometryDir() + "/ies/ies_rescale/Truncated Profile - 01.IES";
    try {
        loadPhotometry(truncated);
        FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
        std::string m = e.what();
        EXPECT_NE(m.find(truncated + ":24: expected 10 values on the lamp line"), std::string::npos)
            << m;
        EXPECT_NE(m.find("found only 4 before the data ended at line 24"), std::string::npos) << m;
    }
}

TEST(PhotometryFiles, OddFilesLoadCorrectly) {
    std::string dir = photometryDir() + "/ies/";
    // Annotated LM-63-1995 example: [BLOCK], [MORE], TILT=INCLUDE, "//" comments on data lines.
    PhotometricData a = loadPhotometry(dir + "ies_rescale/Type C - Annotated.ies");
    EXPECT_EQ(a.format, "IES LM-63-1995");
    EXPECT_EQ(a.name, "Wide beam flood to be used without tilt");
    EXPECT_EQ(a.tiltGeometry, 1);
    ASSERT_EQ(a.tiltAngles.size(), 13u);
    EXPECT_EQ(a.tiltFactors[6], 0.98);
    EXPECT_EQ(a.symmetry, PhotometricSymmetry::Quadrant);
    EXPECT_EQ(a.vertical, (std::vector<double>{0, 22.5, 45, 67.5, 90}));
    EXPECT_EQ(a.lampFlux, 50000.0);
    // Tilt factor at 0 is 1.0: candela as in the file. C = 45, gamma = 22.5 -> 35000.
    EXPECT_NEAR(a.intensity(dirC(22.5, 45.0)), 35000.0, 1e-6);
    EXPECT_NEAR(a.intensity(dirC(22.5, 135.0)), 35000.0, 1e-6);  // quadrant mirror
    bool more = false;
    for (const auto& [k, v] : a.keywords)
        if (k == "OTHER" && v.find("\nand to reduce light pollution") != std::string::npos)
            more = true;
    EXPECT_TRUE(more) << "[MORE] should continue [OTHER]";
    // 1 ft = 0.3048 m: width .5 ft (local y), length .6 ft (local x).
    EXPECT_NEAR(a.opening.width, 0.5 * 0.3048, 1e-12);
    EXPECT_NEAR(a.opening.length, 0.6 * 0.3048, 1e-12);

    // IESNA91, header numbers one per line, comma-separated angles, [MORE].
    PhotometricData s = loadPhotometry(dir + "RenderPipeline/star_focused.ies");
    EXPECT_EQ(s.format, "IES LM-63-1991");
    EXPECT_EQ(s.vertical.size(), 37u);
    EXPECT_EQ(s.lampFlux, 68.0);
    EXPECT_NEAR(s.intensity({0, 0, 1}), 166.0, 1e-9);
    EXPECT_NEAR(s.intensity(dirC(2.5, 22.5)), 158.0, 1e-9);
    EXPECT_NEAR(s.intensity(dirC(2.5, 360.0 - 22.5)), 158.0, 1e-9);

    // LM-63-1986 without header, extra tokens ("END") after the candela block, multiplier 2.2.
    PhotometricData o = loadPhotometry(dir + "RenderPipeline/defined_diffuse.ies");
    EXPECT_EQ(o.format, "IES LM-63-1986");
    EXPECT_EQ(o.symmetry, PhotometricSymmetry::Axial);
    EXPECT_NEAR(o.intensity({0, 0, 1}), 681.879276637 * 2.2, 1e-9);
    EXPECT_NEAR(o.intensity(dirC(5.0, 123.0)), 557.110079287 * 2.2, 1e-9);
    EXPECT_EQ(o.name, "");

    // LM-63-2002 Annex example: "IESNA: LM-63-2002 " header, user keywords, TILT=INCLUDE.
    PhotometricData l = loadPhotometry(dir + "lidrs/iesna2002_example_typec.ies");
    EXPECT_EQ(l.format, "IES LM-63-2002");
    EXPECT_EQ(l.tiltAngles.size(), 13u);
    bool user = false;
    for (const auto& [k, v] : l.keywords) user = user || k == "_NEMATYPE";
    EXPECT_TRUE(user);
}

TEST(PhotometryFiles, OpeningShapesFromFiles) {
    std::string dir = photometryDir() + "/ies/photometric-viewer/ies95/";
    using S = LuminousOpening::Shape;
    EXPECT_EQ(loadPhotometry(dir + "point_opening.ies").opening.shape, S::Point);
    LuminousOpening sphere = loadPhotometry(dir + "sphere_opening.ies").opening;
    EXPECT_EQ(sphere.shape, S::Sphere);
    EXPECT_DOUBLE_EQ(sphere.length, 0.12);
    EXPECT_DOUBLE_EQ(sphere.width, 0.12);
    EXPECT_DOUBLE_EQ(sphere.height, 0.12);
    LuminousOpening round = loadPhotometry(dir + "round_opening_with_height.ies").opening;
    EXPECT_EQ(round.shape, S::Cylinder);
    EXPECT_EQ(round.axis, LuminousOpening::Axis::Z);
    EXPECT_DOUBLE_EQ(round.length, 0.12);
    EXPECT_DOUBLE_EQ(round.height, 0.34);
    LuminousOpening hl =
        loadPhotometry(dir + "horizontal_cylinder_opening_along_length.ies").opening;
    EXPECT_EQ(hl.shape, S::Cylinder);
    EXPECT_EQ(hl.axis, LuminousOpening::Axis::X);
    EXPECT_DOUBLE_EQ(hl.length, 0.12);
    EXPECT_DOUBLE_EQ(hl.width, 0.34);
    LuminousOpening hw =
        loadPhotometry(dir + "horizontal_cylinder_opening_along_width.ies").opening;
    EXPECT_EQ(hw.axis, LuminousOpening::Axis::Y);
    EXPECT_DOUBLE_EQ(hw.width, 0.12);
    EXPECT_DOUBLE_EQ(hw.length, 0.34);
    LuminousOpening rect = loadPhotometry(dir + "rectangular_opening_with_height.ies").opening;
    EXPECT_EQ(rect.shape, S::Rectangle);
    EXPECT_DOUBLE_EQ(rect.width, 0.12);
    EXPECT_DOUBLE_EQ(rect.length, 0.34);
    EXPECT_DOUBLE_EQ(rect.height, 0.56);
    // The same numbers in feet.
    LuminousOpening feet = loadPhotometry(dir + "imperial_units.ies").opening;
    EXPECT_DOUBLE_EQ(feet.width, 0.12 * 0.3048);
    EXPECT_DOUBLE_EQ(feet.length, 0.34 * 0.3048);
    EXPECT_DOUBLE_EQ(feet.height, 0.56 * 0.3048);
}

// ---------------------------------------------------------------------------------------------
// Hand-made IES files: closed-form flux, symmetries, units, multipliers

/// Horizontal angle sets for each IES type C symmetry.
std::vector<std::pair<PhotometricSymmetry, std::vector<double>>> typeCSymmetries() {
    return {{PhotometricSymmetry::Axial, {0.0}},
            {PhotometricSymmetry::Quadrant, range(0, 90, 15)},
            {PhotometricSymmetry::PlaneC0C180, range(0, 180, 22.5)},
            {PhotometricSymmetry::PlaneC90C270, range(90, 270, 30)},
            {PhotometricSymmetry::None, range(0, 360, 10)},
            {PhotometricSymmetry::None, range(0, 350, 10)}};  // full turn without the 360 row
}

TEST(PhotometryIes, ClosedFormFluxForEverySymmetry) {
    for (const auto& [sym, h] : typeCSymmetries()) {
        // Constant 100 cd over the lower hemisphere: the interpolant is exactly constant, so the
        // flux is 2 pi 100 lm to rounding (1e-12 relative).
        Ies flat;
        flat.v = range(0, 90, 5);
        flat.h = h;
        flat.f = [](double, double) { return 100.0; };
        PhotometricData d = flat.parse();
        EXPECT_EQ(d.symmetry, sym);
        EXPECT_NEAR(d.fluxFromTable(), 2.0 * kPi * 100.0, 2.0 * kPi * 100.0 * 1e-12);

        // I0 cos(gamma), lower hemisphere: pi I0. The bilinear interpolant of cos at 1 degree
        // steps is below cos by at most h^2/8 = 3.8e-5 (relative to I0), so 1e-4 relative.
        Ies lam = flat;
        lam.v = range(0, 90, 1);
        lam.f = [](double v, double) { return 1000.0 * std::cos(v * kDeg); };
        PhotometricData l = lam.parse();
        EXPECT_NEAR(l.fluxFromTable(), kPi * 1000.0, kPi * 1000.0 * 1e-4);

        // Full sphere, 0..180: constant 50 cd gives 4 pi 50 lm exactly.
        Ies sphere = flat;
        sphere.v = range(0, 180, 10);
        sphere.f = [](double, double) { return 50.0; };
        EXPECT_NEAR(sphere.parse().fluxFromTable(), 4.0 * kPi * 50.0, 4.0 * kPi * 50.0 * 1e-12);

        // Upper hemisphere only (90..180).
        Ies up = flat;
        up.v = range(90, 180, 10);
        EXPECT_NEAR(up.parse().fluxFromTable(), 2.0 * kPi * 100.0, 2.0 * kPi * 100.0 * 1e-12);
    }
}

TEST(PhotometryIes, ExactQuadratureMatchesBruteForce) {
    // A distribution that depends on C (compatible with each symmetry) and on gamma, plus every
    // shared file. The brute-force midpoint rule (2048 x 1024 cells) converges as h^2 away from
    // the table's kinks; on the shared files it is within 1e-5 of the exact value (measured at
    // 512, 1024, 2048 cells: 1.4e-4, 3.6e-5, 9e-6 for the worst, display.ies), so 1e-4 leaves a
    // margin of 10 while still catching a wrong weight or a misplaced cell.
    for (const auto& [sym, h] : typeCSymmetries()) {
        Ies ies;
        ies.v = range(0, 180, 7.5);
        ies.h = h;
        ies.f = [](double v, double c) {
            return 200.0 + 150.0 * std::cos(v * kDeg) +
                   40.0 * std::cos(2.0 * c * kDeg) * std::sin(v * kDeg);
        };
        PhotometricData d = ies.parse();
        double exact = d.fluxFromTable(), brute = bruteForceFlux(d);
        EXPECT_NEAR(exact, brute, 1e-4 * brute) << symmetryName(sym);
    }
    // Shared files with the same table (the photometric-viewer dummies share one curve) are
    // checked once; axial tables are constant in azimuth, so 16 azimuths integrate them exactly.
    std::vector<double> seen;
    for (const fs::path& p : sharedFiles(false)) {
        PhotometricData d = loadPhotometry(p.string());
        double exact = d.fluxFromTable();
        if (std::any_of(seen.begin(), seen.end(),
                        [&](double f) { return std::abs(f - exact) < 1e-9 * exact; }))
            continue;
        seen.push_back(exact);
        double brute =
            bruteForceFlux(d, 2048, d.symmetry == PhotometricSymmetry::Axial ? 16 : 1024);
        EXPECT_NEAR(exact, brute, 1e-4 * brute) << p;
    }
}

TEST(PhotometryIes, SymmetryUnfoldingMirrorsDirections) {
    // An asymmetric function over the given range; the unfolded table must repeat it at the
    // mirrored azimuths. Exact to rounding (1e-9 cd) because the mirrored points evaluate the same
    // table rows.
    auto f = [](double v, double c) { return 10.0 + v + 0.37 * c + 0.001 * v * c; };
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> gamma(0.0, 180.0), azim(0.0, 90.0);
    for (const auto& [sym, h] : typeCSymmetries()) {
        if (sym == PhotometricSymmetry::None) continue;
        Ies ies;
        ies.v = range(0, 180, 10);
        ies.h = h;
        ies.f = f;
        PhotometricData d = ies.parse();
        for (int k = 0; k < 200; ++k) {
            double g = gamma(rng), c = azim(rng);
            double ref = d.intensity(dirC(g, c));
            switch (sym) {
                case PhotometricSymmetry::Axial:
                    EXPECT_NEAR(d.intensity(dirC(g, c * 4.0 - 17.0)), ref, 1e-9);
                    break;
                case PhotometricSymmetry::Quadrant:
                    EXPECT_NEAR(d.intensity(dirC(g, 180.0 - c)), ref, 1e-9);
                    EXPECT_NEAR(d.intensity(dirC(g, 180.0 + c)), ref, 1e-9);
                    EXPECT_NEAR(d.intensity(dirC(g, 360.0 - c)), ref, 1e-9);
                    break;
                case PhotometricSymmetry::PlaneC0C180:  // y -> -y
                    EXPECT_NEAR(d.intensity(dirC(g, 360.0 - 2.0 * c)),
                                d.intensity(dirC(g, 2.0 * c)), 1e-9);
                    break;
                case PhotometricSymmetry::PlaneC90C270:  // x -> -x
                    EXPECT_NEAR(d.intensity(dirC(g, 180.0 - (90.0 + 2.0 * c))),
                                d.intensity(dirC(g, 90.0 + 2.0 * c)), 1e-9);
                    break;
                default:
                    break;
            }
        }
        // At the file's own nodes the table holds the file's values (1e-9: printed with 17 digits).
        for (double c : h)
            for (double v : {10.0, 50.0, 120.0})
                EXPECT_NEAR(d.intensity(dirC(v, c)), f(v, c), 1e-9)
                    << symmetryName(sym) << " C" << c;
    }
}

TEST(PhotometryIes, UnitsMultipliersAndAbsolutePhotometry) {
    Ies ies;
    ies.v = range(0, 90, 45);
    ies.h = {0};
    ies.f = [](double, double) { return 100.0; };
    ies.width = -0.5;
    ies.length = -0.5;
    ies.units = 1;  // feet
    PhotometricData feet = ies.parse();
    EXPECT_DOUBLE_EQ(feet.opening.length, 0.5 * 0.3048);
    EXPECT_EQ(feet.opening.shape, LuminousOpening::Shape::Ellipse);
    ies.units = 2;
    PhotometricData metres = ies.parse();
    EXPECT_DOUBLE_EQ(metres.opening.length, 0.5);
    // 16-gon inscribed in the circle of diameter 0.5: area 8 sin(pi/8)... = (16/2) r^2 sin(2
    // pi/16).
    EXPECT_NEAR(metres.opening.area(), 8.0 * 0.25 * 0.25 * std::sin(2.0 * kPi / 16.0), 1e-12);

    // Multiplier x ballast factor x ballast-lamp factor scale the candela; lamp flux does not.
    ies.lamps = 2;
    ies.lumens = 1500.0;
    ies.multiplier = 2.0;
    ies.ballast = 0.9;
    ies.blp = 0.8;
    PhotometricData scaled = ies.parse();
    EXPECT_NEAR(scaled.maxIntensity(), 100.0 * 2.0 * 0.9 * 0.8, 1e-9);
    EXPECT_EQ(scaled.lampFlux, 3000.0);
    // LM-63-2019: the second field is the file generation type, not a factor.
    ies.header = "IES:LM-63-2019";
    ies.blp = 1.10001;
    PhotometricData y2019 = ies.parse();
    EXPECT_EQ(y2019.format, "IES LM-63-2019");
    EXPECT_NEAR(y2019.maxIntensity(), 100.0 * 2.0 * 0.9, 1e-9);
    // Absolute photometry.
    ies.lumens = -1.0;
    EXPECT_EQ(ies.parse().lampFlux, -1.0);
    // Versions from the header line.
    ies.header = "IESNA91";
    EXPECT_EQ(ies.parse().format, "IES LM-63-1991");
    ies.header = "";
    ies.keywords = "some free text\n";
    EXPECT_EQ(ies.parse().format, "IES LM-63-1986");
}

TEST(PhotometryIes, TypeBMatchesTypeC) {
    // A Lambertian emitter I = 1000 max(z, 0) written as type C (cos gamma, 0..90, axial) and as
    // type B (cos V cos H over H -90..90, or 0..90 mirrored). Both are pi 1000 lm; the bilinear
    // tables at 2.5 degree steps differ from cos by at most h^2/8 ~ 1e-3 relative in either angle,
    // so intensities agree to 2e-3 x 1000 cd and fluxes to 1e-3.
    Ies c;
    c.v = range(0, 90, 2.5);
    c.h = {0};
    c.f = [](double v, double) { return 1000.0 * std::cos(v * kDeg); };
    PhotometricData tc = c.parse();
    for (auto h : {range(-90, 90, 2.5), range(0, 90, 2.5)}) {
        Ies b;
        b.type = 2;
        b.v = range(-90, 90, 2.5);
        b.h = h;
        b.f = [](double v, double hh) { return 1000.0 * std::cos(v * kDeg) * std::cos(hh * kDeg); };
        PhotometricData tb = b.parse();
        EXPECT_EQ(tb.goniometer, Goniometer::B);
        EXPECT_EQ(tb.horizontal.front(), -90.0);
        EXPECT_EQ(tb.horizontal.back(), 90.0);
        EXPECT_NEAR(tb.fluxFromTable(), kPi * 1000.0, kPi * 1000.0 * 1e-3);
        EXPECT_NEAR(tc.fluxFromTable(), kPi * 1000.0, kPi * 1000.0 * 1e-3);
        std::mt19937 rng(3);
        std::normal_distribution<double> n01;
        for (int k = 0; k < 500; ++k) {
            glm::dvec3 d = glm::normalize(glm::dvec3(n01(rng), n01(rng), n01(rng)));
            EXPECT_NEAR(tb.intensity(d), tc.intensity(d), 2.0) << d.x << " " << d.y << " " << d.z;
            EXPECT_NEAR(tb.intensity(d), 1000.0 * std::max(d.z, 0.0), 2.0);
        }
        // The aim of type B is +z, V lifts towards +y, H turns towards +x.
        EXPECT_NEAR(tb.intensity(dirB(30.0, 0.0)), 1000.0 * std::cos(30.0 * kDeg), 1.0);
        EXPECT_NEAR(tb.intensity(dirB(0.0, -45.0)), 1000.0 * std::cos(45.0 * kDeg), 1.0);
    }
}

TEST(PhotometryIes, TiltIncludeIsApplied) {
    Ies ies;
    ies.v = range(0, 90, 30);
    ies.h = {0, 90};
    ies.f = [](double, double) { return 400.0; };
    ies.tilt = "TILT=INCLUDE\n2\n3\n-10 10 90\n0.3 0.5 1.0\n";
    PhotometricData d = ies.parse();
    EXPECT_EQ(d.tiltGeometry, 2);
    EXPECT_EQ(d.tiltAngles, (std::vector<double>{-10, 10, 90}));
    // Factor at 0: halfway between 0.3 and 0.5.
    EXPECT_NEAR(d.maxIntensity(), 400.0 * 0.4, 1e-9);

    // TILT=<file> next to the .ies.
    fs::path dir =
        fs::temp_directory_path() / ("candela_photometry_tilt_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    {
        std::ofstream(dir / "lamp.tlt") << "1\n2\n0 90\n0.25 1\n";
        ies.tilt = "TILT=lamp.tlt\n";
        std::ofstream(dir / "a.ies") << ies.text();
    }
    PhotometricData t = loadPhotometry((dir / "a.ies").string());
    EXPECT_NEAR(t.maxIntensity(), 400.0 * 0.25, 1e-9);
    EXPECT_EQ(t.tiltFactors, (std::vector<double>{0.25, 1.0}));
    ies.tilt = "TILT=missing.tlt\n";
    try {
        parseIes(ies.text(), (dir / "b.ies").string());
        FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
        std::string m = e.what();
        EXPECT_NE(m.find("b.ies:4: expected the TILT file 'missing.tlt'"), std::string::npos) << m;
    }
    fs::remove_all(dir);
}

TEST(PhotometryIes, DefectsAreReportedWithLine) {
    Ies good;
    good.v = range(0, 90, 45);
    good.h = {0, 90};
    good.f = [](double v, double) { return 100.0 - v; };
    ASSERT_NO_THROW(good.parse());
    auto expectError = [](const std::string& text, const std::string& needle) {
        try {
            parseIes(text, "x.ies");
            ADD_FAILURE() << "no exception for " << needle;
        } catch (const std::runtime_error& e) {
            std::string m = e.what();
            EXPECT_NE(m.find(needle), std::string::npos) << m;
        }
    };
    // Lines: 1 header, 2-3 keywords, 4 TILT, 5 lamp line, 6 ballast, 7 vertical, 8 horizontal, 9+
    // candela.
    Ies b = good;
    b.type = 3;
    expectError(b.text(),
                "x.ies:5: expected photometric type 1 (C) or 2 (B), found 3: type A (automotive) "
                "photometry is not supported");
    b = good;
    b.f = [](double v, double h) { return h == 90 && v == 45 ? -1.0 : 1.0; };
    expectError(
        b.text(),
        "x.ies:10: expected non-negative candela values (horizontal angle 90, vertical angle 45)");
    std::string nan = good.text();
    nan.replace(nan.rfind("55"), 2, "nan");
    expectError(nan, "x.ies:10: expected a finite number (candela values");
    b = good;
    b.v = {0, 60, 45};
    expectError(b.text(),
                "x.ies:7: expected vertical angles in strictly ascending order, found 45 after 60");
    b = good;
    b.h = {0, 45};
    expectError(b.text(), "x.ies:8: expected type C horizontal angles 0 (axial)");
    b = good;
    b.units = 3;
    expectError(b.text(), "x.ies:5: expected units type 1 (feet) or 2 (metres)");
    std::string text = good.text();
    std::string counts = text;
    counts.replace(counts.find(" 3 2 1 2 "), 9, " 0 2 1 2 ");
    expectError(
        counts,
        "x.ies:5: expected number of vertical angles (an integer from 1 to 100000), found 0");
    counts = text;
    counts.replace(counts.find(" 3 2 1 2 "), 9, " 3 200000 1 2 ");
    expectError(counts,
                "expected number of horizontal angles (an integer from 1 to 100000), found 200000");
    // Truncated in the candela block: 6 values expected, the last line dropped.
    std::string cut = text.substr(0, text.rfind('\n', text.size() - 2) + 1);
    expectError(cut,
                "x.ies:9: expected 6 candela values (2 horizontal x 3 vertical angles), found only "
                "3 before "
                "the data ended at line 9");
    expectError("IESNA:LM-63-2002\n[TEST] x\n", "x.ies:2: expected a TILT= line");
    expectError("", "x.ies:1: expected a TILT= line");
    // CRLF line ends and comma separators are fine.
    std::string crlf;
    for (char c : text) {
        if (c == '\n')
            crlf += "\r\n";
        else
            crlf += c;
    }
    EXPECT_NO_THROW(parseIes(crlf, "x.ies"));
    EXPECT_THROW(loadPhotometry(photometryDir() + "/LICENSE.md"), std::runtime_error);
    EXPECT_THROW(loadPhotometry(photometryDir() + "/nonexistent.ies"), std::runtime_error);
}

TEST(PhotometryOpening, PolygonsAndAreas) {
    LuminousOpening o;
    EXPECT_TRUE(o.polygon().empty());
    EXPECT_EQ(o.area(), 0.0);
    o.shape = LuminousOpening::Shape::Rectangle;
    o.length = 0.4;
    o.width = 0.2;
    std::vector<glm::dvec2> p = o.polygon();
    ASSERT_EQ(p.size(), 4u);
    double signedArea = 0.0;
    for (size_t k = 0; k < p.size(); ++k)
        signedArea += 0.5 * (p[k].x * p[(k + 1) % 4].y - p[(k + 1) % 4].x * p[k].y);
    EXPECT_NEAR(signedArea, 0.08, 1e-15);  // counter-clockwise seen from +z: positive
    EXPECT_NEAR(o.area(), 0.08, 1e-15);
    o.shape = LuminousOpening::Shape::Ellipse;
    EXPECT_EQ(o.polygon().size(), 16u);
    // Inscribed 16-gon of the 0.2 x 0.1 (semi-axes) ellipse: 8 a b sin(pi/8)... = 8 a b sin(2
    // pi/16).
    EXPECT_NEAR(o.area(), 8.0 * 0.2 * 0.1 * std::sin(2.0 * kPi / 16.0), 1e-15);
    o.shape = LuminousOpening::Shape::Cylinder;
    o.axis = LuminousOpening::Axis::X;
    EXPECT_NEAR(o.area(), 0.08, 1e-15);
}

// ---------------------------------------------------------------------------------------------
// Robustness

TEST(PhotometryFuzz, TruncatedAndFlippedFilesLoadOrThrow) {
    // Every shared file (the broken ones too), truncated at 64 positions and with one byte
    // replaced at 64 positions, plus random garbage: each either parses into a valid table or
    // throws std::runtime_error; anything else (a crash, another exception) fails the test.
    std::mt19937 rng(1234);
    int loaded = 0, thrown = 0;
    auto attempt = [&](const std::string& text, bool ldt, const std::string& path) {
        try {
            PhotometricData d = ldt ? parseEulumdat(text, path) : parseIes(text, path);
            expectValidTable(d, path);
            (void)d.intensity({0.3, -0.2, 0.9});
            ++loaded;
        } catch (const std::runtime_error&) {
            ++thrown;
        }
    };
    for (const fs::path& p : sharedFiles(true)) {
        std::string text = readFile(p);
        bool ldt = p.extension() == ".ldt";
        std::string path = p.string();
        std::uniform_int_distribution<size_t> pos(0, text.empty() ? 0 : text.size() - 1);
        std::uniform_int_distribution<int> byte(0, 255);
        const char specials[] = {'\n', '\r', ' ', ',', '-', '9', '0', '.', 'e', '\0', '[', '/'};
        for (int k = 0; k < 64; ++k)
            attempt(text.substr(0, text.size() * size_t(k) / 64), ldt, path);
        for (int k = 0; k < 64; ++k) {
            std::string t = text;
            if (t.empty()) break;
            t[pos(rng)] = k % 2 ? char(byte(rng)) : specials[size_t(byte(rng)) % sizeof specials];
            attempt(t, ldt, path);
        }
    }
    for (int k = 0; k < 200; ++k) {
        std::string junk(size_t(k * 3), ' ');
        for (char& c : junk) c = "0123456789 .,-\n[]TILT=NONEe"[rng() % 27];
        attempt(junk, k % 2 == 0, "junk");
        attempt("TILT=NONE\n" + junk, false, "junk.ies");
    }
    std::printf("fuzz: %d loaded, %d rejected\n", loaded, thrown);
    EXPECT_GT(loaded, 0);
    EXPECT_GT(thrown, 0);
}

}  // namespace
}  // namespace candela
