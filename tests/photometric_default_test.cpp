// The default photometric technique on real files, point by point: the files that are hardest
// for a few-sample technique (narrow beams, light out of the sides, long linear openings, large
// up-and-down boxes, round openings), receivers 0.1 and 0.3 m from the opening (above, below,
// beside) and 1, 2, 5 and 28 opening diagonals away, each against the `reference` technique (an
// unbiased Monte Carlo estimator with three strategies, which shares no code with the default's
// cubature). The default must be within its stated limit: 3 % nearer than 2 opening diagonals,
// 1 % from there on, of the point's value or, where the point gets less, of 1 % of the brightest
// point at that distance (a peak narrower than its first triangles may be missed there). Points
// equal by the file's symmetry must agree within the same limit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "luminaires/Registry.h"
#include "luminaires/photometric/PhotometricLuminaire.h"
#include "scene/SceneIo.h"

namespace candela {
namespace {

/// Relative limits of the default technique (its registry statement).
constexpr double kNearLimit = 3e-2;
constexpr double kFarLimit = 1e-2;
/// From this many opening diagonals on, kFarLimit.
constexpr double kFarFromDiagonals = 2.0;
/// Points that get less than this fraction of the brightest at their distance are judged
/// against it instead of their own value.
constexpr double kDimFraction = 1e-2;
/// The reference's samples per point: its standard error is some 0.3 % near the opening; the
/// comparison allows four of them.
constexpr int kReferenceSpp = 40000;

const char* const kFiles[] = {
    "photometric/up-down-box.ies",
    "photometric/spot.ies",
    "photometric/side.ies",
    "photometric/cplanes.ies",
    "photometry/ies/RenderPipeline/vee.ies",
    "photometry/ies/RenderPipeline/display.ies",
    "photometry/ies/RenderPipeline/star_focused.ies",
    "photometry/ies/ies_rescale/Type C - 02.ies",
    "photometry/ies/ies_rescale/Type C - 03.ies",
    "photometry/ldt/photometric-viewer/round_luminaire_round_luminous_opening.ldt",
    "ugr/sample_02_isym4.ldt",
    "../../resources/luminaires/photometric/linear-pendant.ies",
    "../../resources/luminaires/photometric/prolicht-e30.ldt",
    "../../resources/luminaires/photometric/halo-recessed-downlight.ies",
    "../../resources/luminaires/photometric/floor-washlight.ies",
};

struct Receiver {
    std::string group;     ///< Points of one distance (for the brightest there).
    std::string mirrorOf;  ///< Non-empty: equal by symmetry to that receiver.
    glm::dvec3 p, n;
    double diagonals = 0.0;  ///< Distance from the opening's centre, in opening diagonals.
};

/// The luminaire at the origin aiming down (local x = world x, local y = world z).
std::unique_ptr<Luminaire> load(const std::string& file) {
    nlohmann::json entry = {{"type", "photometric"},
                            {"file", std::string(CANDELA_TEST_DATA) + "/" + file},
                            {"position", {0, 0, 0}},
                            {"aim", {0, -1, 0}},
                            {"c0", {1, 0, 0}}};
    return parseLuminaire(entry, json::Where{file, "luminaire"});
}

std::map<std::string, Receiver> receivers(const PhotometricLuminaire& light) {
    glm::dvec2 hi(0.0);
    for (const glm::dvec2& c : light.polygon()) hi = glm::max(hi, c);
    double size = light.size();
    std::map<std::string, Receiver> out;
    auto add = [&](const std::string& name, const std::string& group, glm::dvec3 p, glm::dvec3 n,
                   const std::string& mirrorOf = {}) {
        out[name] = {group, mirrorOf, p, glm::normalize(n), glm::length(p) / size};
    };
    for (double d : {0.1, 0.3}) {
        std::string g = d < 0.2 ? "0.1 m" : "0.3 m";
        add(g + " above the centre", g, {0, d, 0}, {0, -1, 0});
        add(g + " above a corner", g, {hi.x, d, hi.y}, {0, -1, 0});
        add(g + " below the centre", g, {0, -d, 0}, {0, 1, 0});
        add(g + " below an edge", g, {hi.x, -d, 0.2 * hi.y}, {0, 1, 0});
        add(g + " below the opposite edge", g, {-hi.x, -d, -0.2 * hi.y}, {0, 1, 0},
            g + " below an edge");
        add(g + " beside, at its height", g, {hi.x + d, 0.01, 0.1 * hi.y}, {-1, 0, 0});
        add(g + " beside, below", g, {hi.x + d, -d, 0.1 * hi.y}, {-1, 0, 0});
        add(g + " beside the other side, below", g, {-hi.x - d, -d, -0.1 * hi.y}, {1, 0, 0},
            g + " beside, below");
    }
    for (double k : {1.0, 2.0, 5.0, 28.0}) {
        std::string g = std::to_string(int(k)) + " diagonals";
        double r = k * size;
        add(g + " +x", g, {0.6 * r, -0.8 * r, 0.0}, {0, 1, 0});
        add(g + " -x", g, {-0.6 * r, -0.8 * r, 0.0}, {0, 1, 0}, g + " +x");
        add(g + " +z", g, {0.0, -0.8 * r, 0.6 * r}, {0, 1, 0});
        add(g + " -z", g, {0.0, -0.8 * r, -0.6 * r}, {0, 1, 0}, g + " +z");
        add(g + " diagonal", g, {0.42 * r, -0.8 * r, 0.42 * r}, {0, 1, 0});
    }
    return out;
}

/// Whether the file's symmetry makes the pairs above equal: their points are images under a half
/// turn about the aim (x -> -x and z -> -z), the product of the two mirrors, which a table
/// symmetric about both C planes (quadrants) or about its axis keeps, with its rectangle or round
/// opening.
bool halfTurnSymmetric(const PhotometricData& data) {
    return data.symmetry == PhotometricSymmetry::Axial ||
           data.symmetry == PhotometricSymmetry::Quadrant;
}

TEST(PhotometricDefault, HoldsItsStatedLimitOnRealFilesAtEveryDistance) {
    const LuminaireKindInfo* kind = findKind("photometric");
    ASSERT_NE(kind, nullptr);
    const TechniqueInfo* technique =
        findTechnique(LuminaireKind::Photometric, kind->defaultTechnique);
    const TechniqueInfo* reference = findTechnique(LuminaireKind::Photometric, "reference");
    ASSERT_NE(technique, nullptr);
    ASSERT_NE(reference, nullptr);
    for (const char* file : kFiles) {
        std::unique_ptr<Luminaire> light = load(file);
        ASSERT_NE(photometricModel(*light), nullptr) << file;
        const PhotometricLuminaire& photometric = *photometricModel(*light);
        std::map<std::string, Receiver> points = receivers(photometric);
        std::map<std::string, double> value, truth, error;
        std::map<std::string, double> brightest;
        for (const auto& [name, r] : points) {
            EstimateOptions options;
            options.spp = kReferenceSpp;
            options.seed = std::hash<std::string>{}(name);
            Estimate ref = reference->irradiance(*light, r.p, r.n, options);
            truth[name] = ref.irradiance.y;
            error[name] = ref.stdError.y;
            options.spp = 1;
            value[name] = technique->irradiance(*light, r.p, r.n, options).irradiance.y;
            brightest[r.group] = std::max(brightest[r.group], ref.irradiance.y);
        }
        for (const auto& [name, r] : points) {
            double limit = r.diagonals >= kFarFromDiagonals ? kFarLimit : kNearLimit;
            double scale = std::max(truth[name], kDimFraction * brightest[r.group]);
            EXPECT_NEAR(value[name], truth[name], limit * scale + 4.0 * error[name])
                << file << ", " << name << " (" << r.diagonals
                << " opening diagonals): " << technique->name << " " << value[name]
                << " lx, reference " << truth[name] << " +- " << error[name] << " lx";
            if (!r.mirrorOf.empty() && halfTurnSymmetric(*photometric.data)) {
                double other = value[r.mirrorOf];
                EXPECT_NEAR(value[name], other, limit * std::max(scale, 1e-300))
                    << file << ": " << name << " and " << r.mirrorOf
                    << " are equal by symmetry: " << value[name] << " and " << other << " lx";
            }
        }
    }
}

/// The case: a point 0.3 m above a 0.45 m up-and-down box luminaire reads, with the
/// default technique, what the reference reads within 3 %. (Prost's hybrid read 25 % more.)
TEST(PhotometricDefault, ThirtyCentimetresAboveALargeBoxLuminaire) {
    std::unique_ptr<Luminaire> light = load("photometric/up-down-box.ies");
    const TechniqueInfo* technique =
        findTechnique(LuminaireKind::Photometric, findKind("photometric")->defaultTechnique);
    const TechniqueInfo* reference = findTechnique(LuminaireKind::Photometric, "reference");
    glm::dvec3 p(0.0, 0.3, 0.0), n(0.0, -1.0, 0.0);
    EstimateOptions options;
    options.spp = 200000;
    Estimate truth = reference->irradiance(*light, p, n, options);
    double value = technique->irradiance(*light, p, n, options).irradiance.y;
    EXPECT_NEAR(value, truth.irradiance.y, 3e-2 * truth.irradiance.y + 4.0 * truth.stdError.y);
    double hybrid = findTechnique(LuminaireKind::Photometric, "hybrid")
                        ->irradiance(*light, p, n, options)
                        .irradiance.y;
    EXPECT_GT(hybrid, 1.2 * truth.irradiance.y) << "the case the default fixes";
}

}  // namespace
}  // namespace candela
