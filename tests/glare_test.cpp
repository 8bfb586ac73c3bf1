// The Unified Glare Rating (calculation/Glare.h) against closed forms: Guth's position index from
// the published coefficients of Levin's fit, worked by hand; a uniform-luminance luminaire, whose
// L, omega and UGR follow from the geometry alone; two mirrored luminaires (+8 log10 2); the
// maintenance factor (L^2 scales, a given Lb does not); CIE 147's small-source form; what is left
// out; the background from the interreflected light; the scene file's observers.

#include "calculation/Glare.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "TestUtil.h"
#include "calculation/CalculationGrid.h"
#include "scene/Scene.h"
#include "scene/SceneIo.h"
#include "tests/TempDir.h"
#include "util/Error.h"

using namespace candela;
using candela::test::TempDir;

namespace {

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;

/// A scene with lambert.ies (I = 1000 cd cos gamma on a 0.6 x 0.3 m opening: a uniform luminance
/// of 1000 / 0.18 cd/m2 in every direction) at each of `positions`, aimed down, and `extra` JSON
/// fields.
Scene lambertScene(TempDir& tmp, const std::vector<std::string>& positions,
                   const std::string& extra = "", const std::string& luminaireExtra = "") {
    std::string lum;
    for (const std::string& p : positions)
        lum += std::string(lum.empty() ? "" : ",") + R"({"type": "photometric", "file": ")" +
               test::dataDir() + R"(/photometric/lambert.ies", "position": )" + p +
               R"(, "aim": [0, -1, 0], "c0": [1, 0, 0])" + luminaireExtra + "}";
    std::ofstream(tmp.file("scene.json")) << R"({"luminaires": [)" + lum + "]" + extra + "}";
    return loadScene(tmp.file("scene.json"));
}

GlareObserver observer(glm::dvec3 eye, glm::dvec3 view, double background) {
    GlareObserver o;
    o.position = eye;
    o.view = view;
    o.background = background;
    return o;
}

/// p = exp(sigma (35.2 - 0.31889 tau - 1.22 e^(-2 tau / 9)) 1e-3 + sigma^2 (21 + 0.26667 tau -
/// 0.002963 tau^2) 1e-5), sigma and tau in degrees, written out again here.
double levin(double sigma, double tau) {
    return std::exp(sigma * (35.2 - 0.31889 * tau - 1.22 * std::exp(-2.0 * tau / 9.0)) * 1e-3 +
                    sigma * sigma * (21.0 + 0.26667 * tau - 0.002963 * tau * tau) * 1e-5);
}

}  // namespace

// Values worked by hand from the coefficients: sigma 45, tau 0: ln p = 45 x 0.03398 + 2025 x
// 0.00021 = 1.95435, p = 7.0598; sigma 45, tau 90: ln p = 45 x 0.0064999 + 2025 x 0.00021 =
// 0.71775, p = 2.0498 (to the 5 digits worked).
TEST(Glare, PositionIndexIsLevinsFitOfGuthsTable) {
    const glm::dvec3 up(0, 1, 0), view(0, 0, -1);
    EXPECT_DOUBLE_EQ(guthPositionIndex(view, view, up), 1.0);  // straight ahead
    double s = std::sqrt(0.5);
    EXPECT_NEAR(guthPositionIndex({0, s, -s}, view, up), 7.0598, 5e-4);   // 45 degrees above
    EXPECT_NEAR(guthPositionIndex({s, 0, -s}, view, up), 2.0498, 5e-4);   // 45 degrees aside
    EXPECT_NEAR(guthPositionIndex({0, -s, -s}, view, up), 7.0598, 5e-4);  // below: mirrored
    EXPECT_EQ(guthPositionIndex({0, 1, 0}, view, up), 0.0);               // in the frontal plane
    EXPECT_EQ(guthPositionIndex({0, 0.3, 0.95}, view, up), 0.0);          // behind
    // Off-axis in both: sigma and tau from the direction.
    glm::dvec3 d = glm::normalize(glm::dvec3(0.4, 0.7, -1.0));
    double sigma = std::acos(-d.z) / kDegToRad;
    double tau = std::acos(std::abs(d.y) / std::sqrt(1.0 - d.z * d.z)) / kDegToRad;
    EXPECT_NEAR(guthPositionIndex(d, view, up), levin(sigma, tau), 1e-12);
    // Guth's observation: a source above the line of sight glares less (a larger p) than one
    // the same angle aside.
    EXPECT_GT(guthPositionIndex({0, s, -s}, view, up), guthPositionIndex({s, 0, -s}, view, up));
}

// A uniform-luminance luminaire: L = I / Ap = 1000 cos g / (0.18 cos g) = 5555.6 cd/m2 whatever
// the direction, omega = 0.18 cos g / r^2. Eye at (0, 1.2, 3) looking -z, luminaire at
// (0, 2.8, 0): r = 3.4 m (1.6, 3, 3.4), cos g = 1.6 / 3.4, sigma = acos(3 / 3.4), tau = 0.
// The table holds 1000 cos g at 0.5 degree steps: its interpolation error (1e-5 relative) moves
// UGR by 1e-4, hence 1e-3.
TEST(Glare, UniformLuminanceLuminaireMatchesTheClosedForm) {
    TempDir tmp;
    Scene scene = lambertScene(tmp, {"[0, 2.8, 0]"});
    const double lb = 20.0;
    GlareReport r = computeGlare(scene, GridSpec{}, {observer({0, 1.2, 3}, {0, 0, -1}, lb)});
    ASSERT_EQ(r.observers.size(), 1u);
    const GlareResult& g = r.observers[0];
    ASSERT_EQ(g.sources.size(), 1u);
    const GlareSource& s = g.sources[0];
    EXPECT_EQ(s.excluded, "");
    const double cosG = 1.6 / 3.4, L = 1000.0 / 0.18, omega = 0.18 * cosG / (3.4 * 3.4);
    const double p = levin(std::acos(3.0 / 3.4) / kDegToRad, 0.0);
    EXPECT_NEAR(s.distance, 3.4, 1e-12);
    EXPECT_NEAR(s.intensity, 1000.0 * cosG, 1e-2);
    EXPECT_NEAR(s.luminance, L, 1e-4 * L);
    EXPECT_NEAR(s.solidAngle, omega, 1e-12);
    // acos and exp of a direction normalised in another order: 1e-9 relative.
    EXPECT_NEAR(s.positionIndex, p, 1e-8 * p);
    EXPECT_FALSE(s.small);
    EXPECT_FALSE(g.backgroundFromIndirect);
    EXPECT_NEAR(g.ugr, 8.0 * std::log10(0.25 / lb * L * L * omega / (p * p)), 1e-3);
    EXPECT_GT(g.ugr, 10.0);  // a bright source 28 degrees above the line of sight
}

// Two identical luminaires mirrored about the line of sight give twice the sum: + 8 log10 2.
TEST(Glare, TwoMirroredLuminairesAddEightLogTwo) {
    TempDir tmp;
    GlareObserver o = observer({0, 1.2, 3}, {0, 0, -1}, 15.0);
    double one = computeGlare(lambertScene(tmp, {"[1, 2.8, 0]"}), {}, {o}).observers[0].ugr;
    double two =
        computeGlare(lambertScene(tmp, {"[1, 2.8, 0]", "[-1, 2.8, 0]"}), {}, {o}).observers[0].ugr;
    EXPECT_NEAR(two - one, 8.0 * std::log10(2.0), 1e-9);
}

// The maintenance factor scales every intensity, so L^2 omega by its square; with Lb given, UGR
// moves by 16 log10 MF. A limit below the value fails.
TEST(Glare, MaintenanceFactorScalesTheLuminanceSquared) {
    TempDir tmp;
    GlareObserver o = observer({0, 1.2, 3}, {0, 0, -1}, 15.0);
    o.limit = 19.0;
    GlareResult initial = computeGlare(lambertScene(tmp, {"[0, 2.8, 0]"}), {}, {o}).observers[0];
    GlareReport maintained =
        computeGlare(lambertScene(tmp, {"[0, 2.8, 0]"}, R"(, "maintenance_factor": 0.8)"), {}, {o});
    EXPECT_NEAR(maintained.observers[0].ugr - initial.ugr, 16.0 * std::log10(0.8), 1e-9);
    EXPECT_NE(maintained.maintenance.find("0.8"), std::string::npos) << maintained.maintenance;
    EXPECT_EQ(initial.passes, initial.ugr <= 19.0);
    o.limit = initial.ugr - 0.5;
    EXPECT_FALSE(computeGlare(lambertScene(tmp, {"[0, 2.8, 0]"}), {}, {o}).observers[0].passes);
}

// CIE 147: below 0.005 m2 of projected area the term is 200 I^2 / (r^2 p^2), which is L^2 omega
// of the same intensity on 0.005 m2: continuous where the two forms meet, bounded as Ap shrinks.
TEST(Glare, SmallSourcesTakeCie147sForm) {
    TempDir tmp;
    GlareObserver o = observer({0, 1.2, 3}, {0, 0, -1}, 15.0);
    Scene small = lambertScene(tmp, {"[0, 2.8, 0]"}, "", R"(, "opening": [0.05, 0.05])");
    const GlareSource s = computeGlare(small, {}, {o}).observers[0].sources[0];
    EXPECT_TRUE(s.small);
    EXPECT_NEAR(s.projectedArea, 0.0025 * 1.6 / 3.4, 1e-12);
    double p = levin(std::acos(3.0 / 3.4) / kDegToRad, 0.0);
    EXPECT_NEAR(s.term, 200.0 * s.intensity * s.intensity / (3.4 * 3.4 * p * p), 1e-8 * s.term);
    // An opening whose projection is just above 0.005 m2 gives nearly the same term.
    Scene edge = lambertScene(tmp, {"[0, 2.8, 0]"}, "", R"(, "opening": [0.1031, 0.1031])");
    const GlareSource e = computeGlare(edge, {}, {o}).observers[0].sources[0];
    EXPECT_FALSE(e.small);
    EXPECT_NEAR(e.term, s.term, 0.01 * s.term);  // the intensities differ by the table's rounding
}

TEST(Glare, LuminairesOutsideTheIndexAreLeftOut) {
    TempDir tmp;
    GlareObserver o = observer({0, 1.2, 3}, {0, 0, -1}, 15.0);
    Scene scene = lambertScene(tmp, {"[0, 2.8, 5]", "[0, 1.0, 0]", "[0, 2.8, 0]"});
    GlareResult g = computeGlare(scene, {}, {o}).observers[0];
    ASSERT_EQ(g.sources.size(), 3u);
    EXPECT_EQ(g.sources[0].excluded, "behind the eye's frontal plane");
    EXPECT_EQ(g.sources[1].excluded, "not above eye height (outside Guth's position index)");
    EXPECT_EQ(g.sources[2].excluded, "");
    // Only the third counts: the same UGR as with it alone.
    EXPECT_DOUBLE_EQ(g.ugr,
                     computeGlare(lambertScene(tmp, {"[0, 2.8, 0]"}), {}, {o}).observers[0].ugr);
}

// Without a given Lb, the background is the interreflected light at the eye (on the plane facing
// the line of sight) over pi: what computeReceivers' indirect part gives at the eye. A scene with
// no surfaces to reflect light is refused, naming the observer.
TEST(Glare, BackgroundIsTheInterreflectedLightAtTheEyeOverPi) {
    Scene office = loadScene(test::sourceDir() + "/resources/scenes/office.json");
    GlareObserver o = observer({0, 1.2, 1.5}, {0, 0, -1}, 0.0);
    GridSpec how;
    how.spp = 256;
    GlareResult g = computeGlare(office, how, {o}).observers[0];
    EXPECT_TRUE(g.backgroundFromIndirect);
    GridSpec indirect = how;
    indirect.indirect = true;
    ReceiverResult at = computeReceivers(office, indirect, {{o.position, o.view}});
    EXPECT_NEAR(g.background, at.indirect[0] / 3.14159265358979323846, 1e-9 * g.background);
    EXPECT_GT(g.background, 1.0);  // cd/m2: a lit office's walls
    EXPECT_GT(g.ugr, 10.0);
    EXPECT_LT(g.ugr, 35.0);

    TempDir tmp;
    Scene bare = lambertScene(tmp, {"[0, 2.8, 0]"});
    try {
        computeGlare(bare, how, {o});
        ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("observer \"observer\" needs the background "
                                             "luminance"),
                  std::string::npos)
            << e.what();
    }
}

TEST(Glare, ObserversLoadAndSaveWithTheScene) {
    TempDir tmp;
    Scene scene = lambertScene(
        tmp, {"[0, 2.8, 0]"},
        R"(, "glare_observers": [{"name": "desk", "position": [0, 1.2, 3], "view": [0, -0.2, -2],
              "limit": 19, "background_cd_m2": 12}])");
    ASSERT_EQ(scene.glareObservers.size(), 1u);
    const GlareObserver& o = scene.glareObservers[0];
    EXPECT_EQ(o.name, "desk");
    EXPECT_EQ(o.view, glm::dvec3(0, 0, -1));  // made horizontal and unit
    EXPECT_EQ(o.limit, 19.0);
    EXPECT_EQ(o.background, 12.0);
    saveScene(scene, tmp.file("saved.json"));
    EXPECT_EQ(loadScene(tmp.file("saved.json")).glareObservers, scene.glareObservers);
    EXPECT_EQ(computeGlare(scene, {}).observers.size(), 1u);  // the scene's own

    for (auto [bad, expect] : std::vector<std::pair<std::string, std::string>>{
             {R"({"position": [0, 1.2, 0], "view": [0, 1, 0]})", "a horizontal part"},
             {R"({"position": [0, 1.2, 0]})", "view"},
             {R"({"view": [1, 0, 0]})", "position"},
             {R"({"position": [0, 1.2, 0], "view": [1, 0, 0], "limit": -3})", "limit"},
             {R"({"position": [0, 1.2, 0], "view": [1, 0, 0], "eye": 1})", "eye"}}) {
        std::ofstream(tmp.file("bad.json")) << R"({"glare_observers": [)" + bad + "]}";
        try {
            loadScene(tmp.file("bad.json"));
            ADD_FAILURE() << bad;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(expect), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("glare_observers[0]"), std::string::npos)
                << e.what();
        }
    }
}
