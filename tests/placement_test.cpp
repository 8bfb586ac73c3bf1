// Luminaire models apart from their placements: a model is shared by the placements of it and
// evaluated at each one's pose; kinds are an enum whose scene-file names round-trip; every kind's
// adapter writes an entry that reads back as the same luminaire; the interreflection sees a move
// or a new model from the placement, and a copy of the scene as no change.
#include <gtest/gtest.h>

#include <cmath>

#include "TestUtil.h"
#include "calculation/Interreflection.h"
#include "luminaires/Registry.h"
#include "luminaires/lambertian/LambertianRect.h"
#include "luminaires/photometric/PhotometricLuminaire.h"
#include "scene/SceneIo.h"

namespace candela {
namespace {

/// The pose `pose` moved by the rigid motion x -> R x + t (R a rotation by `angle` about `axis`).
struct Motion {
    glm::dvec3 axis{0.3, 1.0, -0.4};
    double angle = 0.7;
    glm::dvec3 t{1.5, -0.25, 2.0};
    glm::dvec3 rotate(const glm::dvec3& v) const {
        // Rodrigues' formula, written out (not the code under test's frame).
        glm::dvec3 k = glm::normalize(axis);
        return v * std::cos(angle) + glm::cross(k, v) * std::sin(angle) +
               k * glm::dot(k, v) * (1.0 - std::cos(angle));
    }
    glm::dvec3 point(const glm::dvec3& p) const { return rotate(p) + t; }
    Pose pose(const Pose& p) const { return {point(p.position), rotate(p.aim), rotate(p.c0)}; }
};

TEST(Placement, CopiesShareTheModelAndMoveAlone) {
    std::unique_ptr<Luminaire> first = adapterOf(LuminaireKind::Photometric).create();
    ASSERT_TRUE(first);
    first->pose = {{0.5, 2.8, -1.0}, {0.0, -1.0, 0.0}, {1.0, 0.0, 0.0}};
    std::unique_ptr<Luminaire> second = first->clone();
    EXPECT_EQ(&first->model(), &second->model());  // shared, not copied
    std::vector<glm::dvec3> before = first->outline();
    glm::dvec3 shift(2.0, -0.5, 3.25);
    second->pose.position += shift;
    // The first is where it was; the second's outline is the first's moved by the shift (metres;
    // 1e-12: the rounding of coordinates of a few metres).
    std::vector<glm::dvec3> still = first->outline(), moved = second->outline();
    ASSERT_EQ(still.size(), before.size());
    ASSERT_EQ(moved.size(), before.size());
    for (size_t i = 0; i < before.size(); ++i) {
        EXPECT_EQ(still[i], before[i]);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(moved[i][c], before[i][c] + shift[c], 1e-12);
    }
    EXPECT_EQ(second->power(), first->power());
}

TEST(Placement, OneModelLightsTheSameWhereverItIsPlaced) {
    // The irradiance is invariant under a rigid motion of the luminaire and the receiver together:
    // the model at pose A seen from p equals the same model at M(A) seen from M(p). Both are
    // closed forms (the rectangle's polygon formula), so they agree to rounding (1e-9 relative).
    auto model = std::make_shared<LambertianRect>();
    model->size = {1.2, 0.5};
    model->emitted = glm::dvec3(40.0, 20.0, 10.0);
    Luminaire a(model), b(model);
    a.pose = {{0.2, 3.0, -0.4}, {0.1, -1.0, 0.2}, {1.0, 0.0, 0.3}};
    Motion m;
    b.pose = m.pose(a.pose);
    const TechniqueInfo* analytic = findTechnique(LuminaireKind::LambertianRect, "analytic");
    ASSERT_TRUE(analytic);
    EstimateOptions o;
    for (glm::dvec3 p : {glm::dvec3(0, 0, 0), glm::dvec3(1.5, 0.8, -2.0), glm::dvec3(-3, 1, 4)}) {
        glm::dvec3 n = glm::normalize(glm::dvec3(0.2, 1.0, -0.1));
        Estimate ea = analytic->irradiance(a, p, n, o);
        Estimate eb = analytic->irradiance(b, m.point(p), m.rotate(n), o);
        ASSERT_GT(ea.irradiance.x, 0.0);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(eb.irradiance[c], ea.irradiance[c], 1e-9 * ea.irradiance[c]);
        // A sample's direction moves with the luminaire; its pdf (per solid angle) does not.
        LightSample sa = a.sample(p, {0.3, 0.6}), sb = b.sample(m.point(p), {0.3, 0.6});
        ASSERT_GT(sa.pdf, 0.0);
        EXPECT_NEAR(sb.pdf, sa.pdf, 1e-9 * sa.pdf);
        glm::dvec3 turned = m.rotate(sa.wi);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(sb.wi[c], turned[c], 1e-9);
    }
}

TEST(Placement, KindsAreAnEnumWhoseNamesRoundTrip) {
    ASSERT_EQ(sourceKinds().size(), 4u);
    for (const LuminaireKindInfo& k : sourceKinds()) {
        EXPECT_EQ(kindName(k.kind), k.name);
        LuminaireKind back = LuminaireKind::Environment;
        ASSERT_TRUE(kindNamed(k.name, back)) << k.name;
        EXPECT_EQ(back, k.kind);
        ASSERT_NE(findKind(k.name), nullptr);
        EXPECT_EQ(findKind(k.name)->kind, k.kind);
        EXPECT_EQ(&findKind(k.kind), &k);
        // Placed kinds read and make luminaires; the environment is made by the scene itself.
        EXPECT_EQ(k.placed(), k.kind != LuminaireKind::Environment) << k.name;
        EXPECT_EQ(k.adapter().create != nullptr, k.placed()) << k.name;
    }
    LuminaireKind unused = LuminaireKind::Photometric;
    EXPECT_FALSE(kindNamed("Photometric", unused));  // names are exact
    // Every technique renders a kind of the table (findKind falls back to the first line).
    for (const TechniqueInfo& t : techniques()) EXPECT_EQ(findKind(t.kind).kind, t.kind) << t.name;
}

TEST(Placement, EveryKindWritesAnEntryThatReadsBackAsTheSameLuminaire) {
    // The adapter's writeJson and parse are each other's inverse: the entry of a default luminaire
    // of every placed kind, read back, describes itself alike and packs the same GPU record.
    for (const LuminaireKindInfo& k : luminaireKinds()) {
        std::unique_ptr<Luminaire> made = k.adapter().create();
        ASSERT_TRUE(made) << k.name;
        made->name = "Made";
        made->technique = std::string(k.defaultTechnique);
        made->pose = {{0.25, 2.5, -0.75}, {0.0, -1.0, 0.1}, {0.0, 0.0, 1.0}};
        made->maintenanceFactor = 0.8;
        nlohmann::json entry = luminaireToJson(*made);
        EXPECT_EQ(entry["type"], std::string(k.name));
        std::unique_ptr<Luminaire> read = parseLuminaire(entry, json::Where{"(test)", "entry"}, 0);
        ASSERT_TRUE(read);
        EXPECT_EQ(read->kind(), made->kind());
        EXPECT_EQ(read->name, made->name);
        EXPECT_EQ(read->technique, made->technique);
        EXPECT_EQ(read->pose, made->pose);
        EXPECT_EQ(read->maintenanceFactor, made->maintenanceFactor);
        EXPECT_EQ(describe(*read), describe(*made));
        EXPECT_EQ(gpuData(*read), gpuData(*made));
        EXPECT_EQ(luminaireToJson(*read), entry);
    }
}

std::string lampAt(double x, double y, double z) {
    return R"({"type": "photometric", "name": "Lamp", "file": ")" + test::dataDir() +
           R"(/photometric/lambert.ies", "position": [)" + std::to_string(x) + "," +
           std::to_string(y) + "," + std::to_string(z) + R"(], "technique": "scattered"})";
}

TEST(Placement, TheInterreflectionSeesANewModelAndNotACopy) {
    Scene s = parseScene(
        nlohmann::json::parse(
            R"({"geometry": [{"box": {"center": [0, 1.4, 0], "size": [4, 2.8, 3], "inside": true},
                "albedo": [0.6, 0.5, 0.4]}], "luminaires": [)" +
            lampAt(-1, 2.7, 0) + "," + lampAt(1, 2.7, 0.5) + "]}"),
        test::dataDir() + "/scene.json");
    InterreflectionOptions o;
    o.mesh.targetPatches = 400;
    Interreflection live(s, o);
    ASSERT_TRUE(live.compute());
    std::vector<glm::dvec3> before = live.indirect();

    // A copy of the scene (what undo and the editor's worker hold) shares the models: nothing is
    // computed again, and nothing changes.
    int computed = 0;
    Progress counting;
    counting.report = [&](double) { ++computed; };
    Scene copy = s.clone();
    ASSERT_TRUE(live.sync(copy, o.directSpp, counting));
    EXPECT_EQ(computed, 0);
    EXPECT_EQ(live.indirect(), before);

    // A new model for the second lamp (twice its output): its share is computed again and the
    // solution equals a fresh computation (the solver's tolerance, as for a move: 1e-5 of the
    // largest patch's light).
    auto brighter = std::make_shared<PhotometricLuminaire>(*photometricModel(*copy.luminaires[1]));
    brighter->scale = 2.0;
    copy.luminaires[1]->setModel(brighter);
    ASSERT_TRUE(live.sync(copy, o.directSpp, counting));
    EXPECT_GT(computed, 0);
    Interreflection fresh(copy, o);
    ASSERT_TRUE(fresh.compute());
    double largest = 0.0, changed = 0.0;
    for (size_t i = 0; i < fresh.indirect().size(); ++i) {
        largest = std::max(largest, fresh.indirect()[i].y);
        changed = std::max(changed, std::abs(fresh.indirect()[i].y - before[i].y));
    }
    ASSERT_GT(changed, 0.05 * largest);  // doubling one of two lamps matters
    for (size_t i = 0; i < fresh.indirect().size(); ++i)
        ASSERT_NEAR(live.indirect()[i].y, fresh.indirect()[i].y, 1e-5 * largest) << "patch " << i;
}

}  // namespace
}  // namespace candela
