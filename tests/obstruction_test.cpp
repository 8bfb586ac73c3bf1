// Shadows in every CPU estimator (issue 17, part 1): an opaque table between a luminaire and the
// floor. For every luminaire kind and every technique the registry lists (a technique added later
// is covered without editing this file), the points under the table's umbra read exactly 0, the
// points outside its shadow read exactly what they read without visibility, and the points in the
// penumbra match the closed form of the part of the emitter they see.
//
// Every kind is set up as the same Lambertian square emitter of luminance L (0.2 x 0.2 m, 2 m
// above the floor, facing down): a Lambertian rectangle, a photometric light from a cosine table
// (lambert.ies) on a 0.2 x 0.2 m opening, and a light field whose images are all L over that
// square (with B-splines that sum to one wherever its rays start). The table is a two-sided
// 0.8 x 0.6 m plane at 0.75 m, centred under the luminaire. From a floor point (x, 0, 0), the ray
// to emitter point (qx, 2, qz) crosses the table's plane at x + t (qx - x), t = 0.75 / 2, so the
// point sees exactly the strip qx >= x + (0.4 - x) / t of the emitter: a rectangle, whose
// irradiance is L pi F with F the closed-form form factor (test::rectangleFormFactor).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>

#include "TestUtil.h"
#include "luminaires/Registry.h"
#include "luminaires/environment/EnvironmentSampling.h"
#include "luminaires/lightfield/LightField.h"
#include "scene/EmbreeVisibility.h"
#include "scene/SceneIo.h"
#include "shaders/shared/Constants.h"

namespace candela {
namespace {

namespace fs = std::filesystem;
using gpu::kPi;

constexpr double kL =
    25000.0;  ///< Luminance of every emitter, cd/m2 (lambert.ies: 1000 cd / 0.04 m2).
constexpr double kHalf = 0.1;        ///< Half-size of the emitter, m.
constexpr double kHeight = 2.0;      ///< Emitter above the floor, m.
constexpr double kTable = 0.75;      ///< Table plane above the floor, m.
constexpr double kTableHalfX = 0.4;  ///< Half its extent along x, m.

/// Closed form: irradiance (lux) at floor point (x, 0, 0) from the part of the emitter the table
/// leaves visible (all of it when `shadowed` is false).
double closedForm(double x, bool shadowed) {
    double lo = -kHalf;
    if (shadowed) lo = std::max(lo, x + (kTableHalfX - x) / (kTable / kHeight));
    if (lo >= kHalf) return 0.0;
    return kL * kPi * test::rectangleFormFactor(lo - x, kHalf - x, -kHalf, kHalf, kHeight);
}

/// How a technique's shadow is defined, when it is not the visible part of the whole emitter.
enum class ShadowModel {
    Area,    ///< The visible part of the emitter (every technique by default).
    Centre,  ///< A point light at the centre: all or nothing (photometric `point`).
    Nodes,   ///< One spot light per basis function at its node (`granier2003`): the visible
             ///< fraction moves in steps of one node's share of the emitter.
};

ShadowModel modelOf(LuminaireKind kind, std::string_view name) {
    if (kind == LuminaireKind::Photometric && name == "point") return ShadowModel::Centre;
    if (kind == LuminaireKind::LightField && name == "granier2003") return ShadowModel::Nodes;
    return ShadowModel::Area;
}

/// A light field of constant images kL on S = [-0.1, 0.1]^2 (delta 0.05 m): its nodes span
/// [-0.2, 0.2] at 0.05 m, so the B-splines sum to one on [-0.175, 0.175], wider than where any
/// ray from the test points through S starts on U (within 0.045 m of S's edge).
fs::path writeConstantField(const fs::path& dir) {
    LightFieldData lf;
    lf.count = {9, 9};
    lf.spacing = {0.05, 0.05};
    lf.origin = {-0.2, -0.2};
    lf.delta = 0.05;
    lf.imageMin = {-kHalf, -kHalf};
    lf.imageMax = {kHalf, kHalf};
    lf.width = lf.height = 4;
    lf.unit = "cd/m2";
    lf.images.resize(81);
    for (auto& image : lf.images) image.luminance.assign(16, float(kL));
    fs::path file = dir / "square.lf.json";
    lf.save(file);
    return file;
}

class Obstruction : public testing::Test {
  protected:
    static void SetUpTestSuite() {
        dir = fs::temp_directory_path() / ("candela-obstruction-" + std::to_string(::getpid()));
        fs::create_directories(dir);
        writeConstantField(dir);
    }
    static void TearDownTestSuite() { fs::remove_all(dir); }

    /// The scene with the luminaire of `kind` and the table.
    static Scene scene(LuminaireKind kind) {
        std::string luminaire;
        if (kind == LuminaireKind::LambertianRect)
            luminaire = R"({"type": "lambertian-rect", "name": "L", "size": [0.2, 0.2],
                            "radiance": [25000, 25000, 25000], "position": [0, 2, 0]})";
        else if (kind == LuminaireKind::Photometric)
            luminaire =
                R"({"type": "photometric", "name": "L", "file": ")" + test::dataDir() +
                R"(/photometric/lambert.ies", "opening": [0.2, 0.2], "position": [0, 2, 0]})";
        else if (kind == LuminaireKind::LightField)  // U 0.05 m above S, so S is at 2 m
            luminaire = R"({"type": "lightfield", "name": "L", "file": ")" +
                        (dir / "square.lf.json").string() + R"(", "position": [0, 2.05, 0]})";
        std::string text = R"({"geometry": [{"plane": {"center": [0, 0.75, 0], "normal": [0, 1, 0],
                                "size": [0.8, 0.6]}}], "luminaires": [)" +
                           luminaire + "]}";
        return parseScene(nlohmann::json::parse(text), (dir / "scene.json").string());
    }

    static fs::path dir;
};
fs::path Obstruction::dir;

// Umbra: every ray to the emitter (and to the light field's outermost nodes, 0.2 m out) is
// blocked for x < 0.52. Lit: none is for x > 0.76. The penumbra of the emitter is 0.58 < x < 0.7.
const double kUmbra[] = {0.0, 0.3};
const double kPenumbra[] = {0.6, 0.62, 0.64, 0.66, 0.68};
const double kLit[] = {0.9, 1.2, 1.6};

TEST_F(Obstruction, EveryTechniqueOfEveryKindShadowsTheTableClosedForm) {
    int checked = 0;
    for (const LuminaireKindInfo& info : luminaireKinds()) {
        const LuminaireKind kind = info.kind;
        Scene s = scene(kind);
        ASSERT_EQ(s.luminaires.size(), 1u);
        const Luminaire& light = *s.luminaires[0];
        EmbreeVisibility visibility(s);
        for (const TechniqueInfo& t : techniques()) {
            if (t.kind != kind || !t.irradiance) continue;
            SCOPED_TRACE(std::string(kindName(kind)) + " " + std::string(t.name));
            ++checked;
            EstimateOptions open, shadowed;
            open.spp = shadowed.spp = 8192;
            shadowed.visibility = &visibility;
            auto estimate = [&](double x, const EstimateOptions& o) {
                return t.irradiance(light, {x, 0.0, 0.0}, {0.0, 1.0, 0.0}, o);
            };
            for (double x : kUmbra) {
                Estimate free = estimate(x, open);
                ASSERT_GT(free.irradiance.y, 0.0)
                    << "x = " << x << ": the table must hide some light";
                EXPECT_EQ(estimate(x, shadowed).irradiance.y, 0.0)
                    << "x = " << x << " is in the umbra";
            }
            for (double x : kLit) {
                // Every ray is free, so the shadowed estimate is the unshadowed one to rounding
                // (the same samples; the visible fractions are exactly 1).
                double free = estimate(x, open).irradiance.y;
                EXPECT_NEAR(estimate(x, shadowed).irradiance.y, free, 1e-12 * free) << "x = " << x;
            }
            ShadowModel model = modelOf(t.kind, t.name);
            for (double x : kPenumbra) {
                Estimate free = estimate(x, open), shade = estimate(x, shadowed);
                double cfFree = closedForm(x, false), cfShadow = closedForm(x, true);
                double fraction = cfShadow / cfFree;  // the exact irradiance-weighted visible part
                ASSERT_GT(fraction, 0.02);
                ASSERT_LT(fraction, 0.98);
                double got = shade.irradiance.y;
                if (model == ShadowModel::Centre) {
                    // A point light at the centre: lit exactly when the centre is visible, which
                    // for x > 0.4 / (1 - t) = 0.64 it is.
                    bool centreVisible = x * (1.0 - kTable / kHeight) > kTableHalfX;
                    EXPECT_EQ(got, centreVisible ? free.irradiance.y : 0.0) << "x = " << x;
                    continue;
                }
                double sigma = shade.stdError.y;
                if (model == ShadowModel::Nodes) {
                    // Five nodes span the emitter's width: each spot light carries about a fifth.
                    EXPECT_NEAR(got / free.irradiance.y, fraction, 0.25) << "x = " << x;
                    EXPECT_LT(got, free.irradiance.y) << "x = " << x;
                    continue;
                }
                // Techniques accurate without shadows (within four standard errors and 0.5 %,
                // the cosine table's interpolation and the light field's pixel grid) must give
                // the closed form; approximate ones (mrp, a fixed point set, ...) must scale their
                // own value by the visible fraction, within four of its standard errors.
                bool accurate =
                    std::abs(free.irradiance.y - cfFree) <= 4.0 * free.stdError.y + 0.005 * cfFree;
                if (accurate)
                    EXPECT_NEAR(got, cfShadow, 4.0 * sigma + 0.005 * cfFree)
                        << "x = " << x << ", unshadowed " << free.irradiance.y << " (closed form "
                        << cfFree << ")";
                else
                    EXPECT_NEAR(got / free.irradiance.y, fraction,
                                4.0 * sigma / free.irradiance.y + 1e-3)
                        << "x = " << x << ", unshadowed " << free.irradiance.y << " (closed form "
                        << cfFree << ")";
            }
        }
    }
    EXPECT_GE(checked, 15);  // 2 + 5 + 8 techniques today
}

TEST_F(Obstruction, GridShowsTheTablesShadowWithVisibilityOnly) {
    // The shipped photometric room (two real luminaires over a table): with --visibility the
    // points under the table lose the pendant's direct light, without it they keep it.
    Scene room = loadScene(test::sourceDir() + "/resources/scenes/photometric.json");
    EmbreeVisibility visibility(room);
    EstimateOptions open, shadowed;
    shadowed.visibility = &visibility;
    const Luminaire& pendant = *room.luminaires[0];
    const TechniqueInfo* t = findTechnique(LuminaireKind::Photometric, pendant.technique);
    ASSERT_NE(t, nullptr);
    // Under the middle of the table top (0.7 m up, 1.6 x 0.9 m centred on (0, -0.5)), straight
    // below the pendant: the table blocks every ray from the pendant's opening.
    glm::dvec3 under(0.0, 0.0, -0.5), beside(0.0, 0.0, 1.2), up(0.0, 1.0, 0.0);
    EXPECT_GT(t->irradiance(pendant, under, up, open).irradiance.y, 50.0);
    EXPECT_EQ(t->irradiance(pendant, under, up, shadowed).irradiance.y, 0.0);
    double free = t->irradiance(pendant, beside, up, open).irradiance.y;
    EXPECT_NEAR(t->irradiance(pendant, beside, up, shadowed).irradiance.y, free, 1e-12 * free);
}

TEST_F(Obstruction, EveryEnvironmentTechniqueShadowsTheTableClosedForm) {
    // A constant environment of radiance 2 W/(m2 sr) over the same table (no floor: the
    // receivers are free points facing up): a point sees the sky but for the table, so it
    // receives 2 pi (1 - F) with F the closed-form form factor from the point to the table.
    std::string text = R"({"geometry": [{"plane": {"center": [0, 0.75, 0], "normal": [0, 1, 0],
                          "size": [0.8, 0.6]}}], "environment": {"file": ")" +
                       test::dataDir() + R"(/environment/constant_2.exr"}})";
    Scene s = parseScene(nlohmann::json::parse(text), (dir / "scene.json").string());
    EnvironmentLighting lighting(s.environmentMap);
    EmbreeVisibility visibility(s);
    int checked = 0;
    for (const TechniqueInfo& t : techniquesOf(LuminaireKind::Environment)) {
        SCOPED_TRACE(std::string(t.name));
        ++checked;
        for (double x : {0.0, 0.3, 0.5, 1.0, 2.5}) {
            double F =
                test::rectangleFormFactor(-kTableHalfX - x, kTableHalfX - x, -0.3, 0.3, kTable);
            double want = 2.0 * kPi * (1.0 - F);
            EstimateOptions o;
            o.spp = 8192;
            o.visibility = &visibility;
            Estimate e = t.irradiance(test::lightOf(lighting), {x, 0.0, 0.0}, {0.0, 1.0, 0.0}, o);
            // Stochastic techniques: four standard errors. The exact reference: 0.5 %, the error
            // of its visibility at 6 x 6 rays per texel along the table's outline. havran2005's
            // 256 lights (one direction each) see the table's solid angle in steps of one
            // light's: 3 % of the sky.
            double tolerance =
                4.0 * e.stdError.y + (t.name.starts_with("havran") ? 0.03 : 0.005) * 2.0 * kPi;
            EXPECT_NEAR(e.irradiance.y, want, tolerance) << "x = " << x << ", F = " << F;
        }
    }
    EXPECT_GE(checked, 7);
}

}  // namespace
}  // namespace candela
