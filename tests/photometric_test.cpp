// Photometric area lights (Prost 2019): the spherical-polygon geometry behind scattered sampling,
// the luminaire model and every technique, against closed forms and independent quadrature.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <memory>

#include "TestUtil.h"
#include "luminaires/Random.h"
#include "luminaires/Registry.h"
#include "luminaires/SphericalPolygon.h"
#include "luminaires/photometric/PhotometricLuminaire.h"
#include "shaders/shared/Constants.h"

namespace candela {
namespace {

using gpu::kPi;
const std::string kData = CANDELA_TEST_DATA "/photometric/";

spherical::Polygon rectangle(double x0, double y0, double x1, double y1, double z) {
    spherical::Polygon p;
    p.count = 4;
    p.v[0] = {x0, y0, z};
    p.v[1] = {x1, y0, z};
    p.v[2] = {x1, y1, z};
    p.v[3] = {x0, y1, z};
    return p;
}

/// Form factor from a point under one corner of an a x b rectangle at height h, normal facing
/// it (the classic closed form, e.g. Howell's catalogue, configuration B-2).
double cornerFormFactor(double a, double b, double h) {
    double A = a / h, B = b / h;
    return (A / std::sqrt(1 + A * A) * std::atan(B / std::sqrt(1 + A * A)) +
            B / std::sqrt(1 + B * B) * std::atan(A / std::sqrt(1 + B * B))) /
           (2 * kPi);
}

TEST(SphericalPolygon, SolidAnglesMatchClosedForms) {
    // One face of a cube seen from its centre: 4 pi / 6.
    EXPECT_NEAR(spherical::solidAngle(rectangle(-1, -1, 1, 1, -1)), 4 * kPi / 6, 1e-12);
    // The octant triangle: pi / 2.
    EXPECT_NEAR(spherical::triangleSolidAngle({1, 0, 0}, {0, 1, 0}, {0, 0, 1}), kPi / 2, 1e-12);
    // Projected solid angle = pi F for a rectangle above a corner; tiny one far away ~ A cos / d^2.
    for (double h : {0.01, 0.5, 3.0, 100.0}) {
        double exact = kPi * cornerFormFactor(0.6, 0.3, h);
        double got = spherical::projectedSolidAngle(rectangle(0, 0, 0.6, 0.3, h), {0, 0, 1});
        EXPECT_NEAR(got, exact, 1e-10 * exact + 1e-15) << h;
    }
}

TEST(SphericalPolygon, ClipKeepsTheUpperPartExactly) {
    // Half the square below the horizon z >= 0 of a tilted receiver normal: what is kept is
    // the polygon with x >= 0 for normal +x.
    spherical::Polygon q = spherical::clip(rectangle(-1, -1, 1, 1, 2), {1, 0, 0});
    ASSERT_EQ(q.count, 4);
    double omega = spherical::solidAngle(q);
    EXPECT_NEAR(omega, spherical::solidAngle(rectangle(0, -1, 1, 1, 2)), 1e-12);
    EXPECT_EQ(spherical::clip(rectangle(-1, -1, 1, 1, 2), {0, 0, -1}).count, 0);
}

TEST(SphericalPolygon, ClosestPointPlaces) {
    auto rect = rectangle(-1, -1, 1, 1, 2);
    auto at = [&](glm::dvec3 shift) {
        spherical::Polygon q = rect;
        for (int i = 0; i < 4; ++i) q.v[size_t(i)] += shift;
        return spherical::closestPoint(q, 1e-9);
    };
    spherical::ClosestPoint inside = at({0.2, 0.3, 0});
    EXPECT_EQ(inside.place, spherical::Place::Inside);
    EXPECT_NEAR(glm::length(inside.point - glm::dvec3(0, 0, 2)), 0.0, 1e-12);
    spherical::ClosestPoint edge = at({-1.5, 0.2, 0});  // x spans [-2.5, -0.5]: beyond its edge
    EXPECT_EQ(edge.place, spherical::Place::Edge);
    EXPECT_NEAR(edge.point.x, -0.5, 1e-12);
    EXPECT_NEAR(edge.point.y, 0.0, 1e-12);
    spherical::ClosestPoint corner = at({-3, -3, 0});
    EXPECT_EQ(corner.place, spherical::Place::Corner);
    EXPECT_NEAR(glm::length(corner.point - glm::dvec3(-2, -2, 2)), 0.0, 1e-12);
    // Exactly on an edge and exactly on a corner (coincident samples) snap, never near-miss.
    EXPECT_EQ(at({-1, 0, 0}).place, spherical::Place::Edge);
    EXPECT_EQ(at({-1, -1, 0}).place, spherical::Place::Corner);
}

TEST(SphericalPolygon, FlipsGiveADelaunayTriangulationCoveringThePolygon) {
    // Random convex polygons (points of a circle) with a random interior point, triangulated as
    // a fan and flipped: afterwards no vertex lies inside any triangle's circumcircle and the
    // triangles' solid angles sum to the polygon's.
    Random rng(7);
    int totalFlips = 0;
    for (int trial = 0; trial < 200; ++trial) {
        int n = 3 + int(rng.uniform() * 8);
        spherical::Polygon q;
        double start = rng.uniform() * 2 * kPi;
        std::vector<double> angles;
        for (int i = 0; i < n; ++i)
            angles.push_back(start + 2 * kPi * (i + 0.8 * rng.uniform()) / n);
        double z = 0.05 + 2 * rng.uniform();
        glm::dvec3 centre(rng.uniform() - 0.5, rng.uniform() - 0.5, 0);
        for (int i = 0; i < n; ++i)
            q.v[size_t(q.count++)] =
                centre + glm::dvec3(std::cos(angles[size_t(i)]), std::sin(angles[size_t(i)]), z);
        spherical::ClosestPoint cp;
        cp.point = q.v[0] * 0.3 + q.v[1] * 0.3 + q.v[2] * 0.4;  // inside (a convex combination)
        spherical::Triangulation t = spherical::initialTriangulation(n, cp);
        glm::dvec3 dirs[spherical::kMaxPolygon + 1];
        dirs[0] = glm::normalize(cp.point);
        for (int i = 0; i < n; ++i) dirs[i + 1] = glm::normalize(q.v[size_t(i)]);
        spherical::makeDelaunay(t, dirs);
        totalFlips += t.flips;
        ASSERT_EQ(t.count, n);
        double sum = 0.0;
        for (int i = 0; i < t.count; ++i) {
            const auto& tr = t.tri[size_t(i)];
            sum += spherical::triangleSolidAngle(dirs[tr[0]], dirs[tr[1]], dirs[tr[2]]);
            for (int v = 0; v <= n; ++v) {
                if (v == tr[0] || v == tr[1] || v == tr[2]) continue;
                EXPECT_FALSE(
                    spherical::inCircumcircle(dirs[tr[0]], dirs[tr[1]], dirs[tr[2]], dirs[v]))
                    << "trial " << trial << " triangle " << i << " vertex " << v;
            }
        }
        EXPECT_NEAR(sum, spherical::solidAngle(q), 1e-9);
    }
    EXPECT_GT(totalFlips, 0);  // the test did exercise flipping
}

std::unique_ptr<Luminaire> place(const std::string& file, glm::dvec3 position = {0, 2, 0},
                                 glm::dvec3 aim = {0, -1, 0}, glm::dvec3 c0 = {1, 0, 0}) {
    auto model = std::make_shared<PhotometricLuminaire>();
    model->file = kData + file;
    model->data = PhotometricLuminaire::load(model->file);
    model->updateOpening();
    std::unique_ptr<Luminaire> light = placed(model);
    light->pose.position = position;
    light->pose.aim = aim;
    light->pose.c0 = c0;
    return light;
}

/// The photometric model of a luminaire placed by place().
const PhotometricLuminaire& model(const Luminaire& l) {
    return *photometricModel(l);
}

/// Candela towards world direction w from the luminaire where it is placed.
double intensity(const Luminaire& l, const glm::dvec3& w) {
    return model(l).intensity(l.pose, w);
}

Estimate run(const char* technique, const Luminaire& l, glm::dvec3 p, glm::dvec3 n,
             int spp = 4096) {
    const TechniqueInfo* t = findTechnique(LuminaireKind::Photometric, technique);
    EXPECT_NE(t, nullptr) << technique;
    EstimateOptions o;
    o.spp = spp;
    return t->irradiance(l, p, glm::normalize(n), o);
}

/// The Lambertian rectangle's exact irradiance: L times the projected solid angle of the part
/// above the receiver's horizon (independent of the luminaire code: its own corner math here).
double lambertExact(const Luminaire& l, double radianceL, glm::dvec3 p, glm::dvec3 n) {
    glm::dvec3 x, y, z;
    l.pose.frame(x, y, z);
    spherical::Polygon q;
    for (glm::dvec2 c : {glm::dvec2(-0.3, -0.15), glm::dvec2(0.3, -0.15), glm::dvec2(0.3, 0.15),
                         glm::dvec2(-0.3, 0.15)})
        q.v[size_t(q.count++)] = l.pose.position + c.x * x + c.y * y - p;
    if (glm::dot(p - l.pose.position, z) <= 0.0) return 0.0;
    return radianceL * spherical::projectedSolidAngle(spherical::clip(q, n), glm::normalize(n));
}

TEST(PhotometricLuminaire, LambertianFileIsALambertianRectangle) {
    // I = 1000 cos(gamma) cd from a 0.6 x 0.3 m opening is a Lambertian emitter of radiance
    // 1000 / 0.18 cd/m2. The table is bilinear in 0.5 degree steps: cos is then exact to
    // (0.5 deg)^2 / 8 ~ 1e-5 relative.
    auto l = place("lambert.ies");
    EXPECT_NEAR(model(*l).area(), 0.18, 1e-12);
    EXPECT_NEAR(l->power().y, kPi * 1000.0, 1e-4 * kPi * 1000.0);
    const double L = 1000.0 / 0.18;
    struct Case {
        glm::dvec3 p, n;
    };
    std::vector<Case> cases = {
        {{0, 0, 0}, {0, 1, 0}},          // under the centre, 2 m
        {{0.1, 1.95, 0.05}, {0, 1, 0}},  // 5 cm below the opening, under it
        {{0.5, 1.9, 0.3}, {0, 1, 0}},    // near, beside the opening
        {{0.2, 1.9, 0}, {1, 0.2, 0}},    // tilted: the opening is half below its horizon
        {{1.0, 1.5, -0.5}, {-1, 0.1, 0.3}},
        {{3, 0, 2}, {0, 1, 0}},  // far and oblique
    };
    for (size_t i = 0; i < cases.size(); ++i) {
        double exact = lambertExact(*l, L, cases[i].p, cases[i].n);
        ASSERT_GT(exact, 0.0) << i;
        // Scattered sampling is exact for a Lambertian emitter (the cubature's mean of a constant
        // is that constant, times the closed-form projected solid angle): 1e-4 covers the table.
        EXPECT_NEAR(run("scattered", *l, cases[i].p, cases[i].n).irradiance.y, exact, 1e-4 * exact)
            << i;
        EXPECT_NEAR(run("hybrid", *l, cases[i].p, cases[i].n).irradiance.y, exact, 0.05 * exact)
            << i;
        // So is the adaptive refinement of it, whatever it splits.
        EXPECT_NEAR(run("adaptive", *l, cases[i].p, cases[i].n).irradiance.y, exact, 1e-4 * exact)
            << i;
        // The reference is unbiased: within 4 standard errors (+ the table's 1e-4).
        Estimate ref = run("reference", *l, cases[i].p, cases[i].n, 200000);
        EXPECT_NEAR(ref.irradiance.y, exact, 4 * ref.stdError.y + 1e-4 * exact) << i;
    }
}

/// Independent area-form quadrature: 64 x 64 Gauss-Legendre-free midpoint cells, each split
/// 4 x 4, of (1/A) I(w) cos / r^2 over the opening — its own loop, not the estimators'.
double areaQuadrature(const Luminaire& l, glm::dvec3 p, glm::dvec3 n, int cells = 256) {
    glm::dvec3 x, y, z;
    l.pose.frame(x, y, z);
    glm::dvec2 lo(1e9), hi(-1e9);
    for (auto c : model(l).polygon()) lo = glm::min(lo, c), hi = glm::max(hi, c);
    double sum = 0.0;
    n = glm::normalize(n);
    for (int j = 0; j < cells; ++j)
        for (int i = 0; i < cells; ++i) {
            glm::dvec2 q = lo + (glm::dvec2(i, j) + 0.5) / double(cells) * (hi - lo);
            glm::dvec3 s = l.pose.position + q.x * x + q.y * y;
            glm::dvec3 v = s - p;
            double r2 = glm::dot(v, v);
            double c = glm::dot(n, v) / std::sqrt(r2);
            if (c <= 0.0) continue;
            sum += intensity(l, -v) * c / r2;
        }
    return sum / double(cells * cells);
}

TEST(PhotometricLuminaire, CGrowsCounterClockwiseSeenFromAboveADownlight) {
    // The frame: gamma = 0 along aim, C = 0 along c0, C = 90 along c0 x aim. A downlight
    // (aim -Y, c0 +X) seen from above (from +Y, X to the right, Z towards the viewer's bottom):
    // counter-clockwise from +X is -Z. cplanes.ies has 100, 200, 300, 400 cd at C 0, 90, 180, 270.
    auto l = place("cplanes.ies", {0, 2, 0}, {0, -1, 0}, {1, 0, 0});
    const double s = std::sqrt(0.5);
    struct Case {
        glm::dvec3 dir;
        double cd;
    };
    for (Case c : {Case{{s, -s, 0}, 100.0}, Case{{0, -s, -s}, 200.0}, Case{{-s, -s, 0}, 300.0},
                   Case{{0, -s, s}, 400.0}}) {
        EXPECT_NEAR(intensity(*l, c.dir), c.cd, 1e-9) << c.dir.x << " " << c.dir.z;
        // And through a technique: the point law at a receiver 1 m along that direction.
        glm::dvec3 p = l->pose.position + c.dir;
        EXPECT_NEAR(run("point", *l, p, -c.dir).irradiance.y, c.cd, 1e-9);
    }
}

TEST(PhotometricLuminaire, ReferenceMatchesQuadratureNearAndPointLawFar) {
    for (const char* file : {"spot.ies", "side.ies", "lambert.ies"}) {
        auto l = place(file, {0, 2, 0}, glm::normalize(glm::dvec3(0.3, -1, 0.1)), {1, 0, 0});
        // Near: 2 cm to 30 cm from the opening, including a receiver 1e-6 m from its plane.
        glm::dvec3 z = glm::normalize(l->pose.aim);
        std::vector<std::pair<glm::dvec3, glm::dvec3>> near = {
            {l->pose.position + 0.02 * z + glm::dvec3(0.05, 0, 0), -z},
            {l->pose.position + 0.3 * z + glm::dvec3(0.1, 0.0, 0.3), glm::dvec3(0, 1, 0)},
            {l->pose.position + 1e-6 * z + glm::dvec3(0, 0, 0.6), glm::dvec3(0, 0, -1)},
        };
        for (auto [p, n] : near) {
            double quad = areaQuadrature(*l, p, n, 512);
            Estimate ref = run("reference", *l, p, n, 400000);
            // The midpoint rule with 512^2 cells is accurate to ~1e-3 here (the 2 cm receiver's
            // peak is 40 cells wide); plus four standard errors of the reference.
            EXPECT_NEAR(ref.irradiance.y, quad, 4 * ref.stdError.y + 2e-3 * quad) << file;
            EXPECT_TRUE(std::isfinite(ref.irradiance.y));
        }
        // Far: beyond ten opening sizes, within 1 % of I(w) cos / d^2.
        for (glm::dvec3 p : {glm::dvec3(0, -8, 0), glm::dvec3(5, -5, 2), glm::dvec3(-3, -7, 3)}) {
            glm::dvec3 v = l->pose.position - p;
            double d = glm::length(v);
            ASSERT_GT(d, 10 * model(*l).size());
            glm::dvec3 n(0, 1, 0);
            double law = intensity(*l, -v) * glm::dot(n, v / d) / (d * d);
            Estimate ref = run("reference", *l, p, n, 20000);
            EXPECT_NEAR(ref.irradiance.y, law, 0.01 * law + 4 * ref.stdError.y) << file;
            EXPECT_NEAR(run("point", *l, p, n).irradiance.y, law, 1e-9 * law) << file;
        }
    }
}

TEST(PhotometricLuminaire, HardCasesStayFinite) {
    auto side = place("side.ies");
    auto lambert = place("lambert.ies");
    glm::dvec3 origin = side->pose.position;
    struct Case {
        const char* what;
        const Luminaire* l;
        glm::dvec3 p, n;
    };
    std::vector<Case> cases = {
        {"in the light's plane", side.get(), origin + glm::dvec3(1, 0, 0), {-1, 0, 0}},
        {"1e-6 m from the plane", side.get(), origin + glm::dvec3(1, -1e-6, 0), {-1, 0, 0}},
        {"on the opening itself", lambert.get(), origin, {0, -1, 0}},
        {"light below the horizon", lambert.get(), origin + glm::dvec3(0, -1, 0), {0, -1, 0}},
        {"light half below the horizon", lambert.get(), origin + glm::dvec3(0, -0.5, 0), {1, 0, 0}},
        {"closest point on a corner",
         lambert.get(),
         origin + glm::dvec3(0.3, -0.4, 0.15),
         {0, 1, 0}},
        {"closest point on an edge", lambert.get(), origin + glm::dvec3(0.3, -0.4, 0.0), {0, 1, 0}},
        {"grazing receiver", lambert.get(), origin + glm::dvec3(2, -0.01, 0), {0, 1, 0}},
        {"behind the light", lambert.get(), origin + glm::dvec3(0, 1, 0), {0, -1, 0}},
    };
    for (const auto& c : cases)
        for (const auto& t : techniques()) {
            if (t.kind != LuminaireKind::Photometric) continue;
            Estimate e = run(std::string(t.name).c_str(), *c.l, c.p, c.n, 1000);
            EXPECT_TRUE(std::isfinite(e.irradiance.y) && e.irradiance.y >= 0.0)
                << c.what << " " << t.name;
        }
    // The side emitter lights receivers in its own plane; the reference sees it (finite, > 0),
    // and 1e-6 m off the plane agrees with the in-plane value within 1 %.
    Estimate inPlane = run("reference", *side, origin + glm::dvec3(1, 0, 0), {-1, 0, 0}, 100000);
    Estimate offPlane =
        run("reference", *side, origin + glm::dvec3(1, -1e-6, 0), {-1, 0, 0}, 100000);
    EXPECT_GT(inPlane.irradiance.y, 0.0);
    EXPECT_NEAR(offPlane.irradiance.y, inPlane.irradiance.y,
                0.01 * inPlane.irradiance.y + 4 * inPlane.stdError.y);
    // Below the horizon: exactly 0 for every technique; behind a downlight: exactly 0.
    for (const auto& t : techniques())
        if (t.kind == LuminaireKind::Photometric) {
            EXPECT_EQ(run(std::string(t.name).c_str(), *lambert, origin + glm::dvec3(0, -1, 0),
                          {0, -1, 0})
                          .irradiance.y,
                      0.0)
                << t.name;
            EXPECT_EQ(
                run(std::string(t.name).c_str(), *lambert, origin + glm::dvec3(0, 1, 0), {0, -1, 0})
                    .irradiance.y,
                0.0)
                << t.name;
        }
    // Coincident scattered samples (closest point on a corner or an edge) still give the exact
    // Lambertian answer.
    const double L = 1000.0 / 0.18;
    for (glm::dvec3 p : {origin + glm::dvec3(0.3, -0.4, 0.15), origin + glm::dvec3(0.3, -0.4, 0.0),
                         origin + glm::dvec3(0.7, -0.4, 0.5)}) {
        double exact = lambertExact(*lambert, L, p, {0, 1, 0});
        EXPECT_NEAR(run("scattered", *lambert, p, {0, 1, 0}).irradiance.y, exact, 1e-4 * exact);
    }
}

TEST(PhotometricLuminaire, DegenerateOpeningIsASegment) {
    // Zero width: the opening is a 0.6 m segment along x; every technique gives the line
    // average of point sources, which for a receiver on the axis below its middle is checked
    // against a 10000-point midpoint sum written here.
    auto l = place("lambert.ies");
    auto segment = std::make_shared<PhotometricLuminaire>(model(*l));
    segment->openingOverride = {0.6, 0.0};
    segment->updateOpening();
    l->setModel(segment);
    ASSERT_EQ(model(*l).polygon().size(), 2u);
    glm::dvec3 p(0.0, 1.0, 0.0), n(0, 1, 0);
    double sum = 0.0;
    for (int i = 0; i < 10000; ++i) {
        double x = -0.3 + 0.6 * (i + 0.5) / 10000.0;
        glm::dvec3 v = glm::dvec3(x, 2, 0) - p;
        double r = glm::length(v);
        sum += intensity(*l, -v) * (v.y / r) / (r * r);
    }
    double expected = sum / 10000.0;
    for (const auto& t : techniques())
        if (t.kind == LuminaireKind::Photometric) {
            // The point law ignores the extent: the segment's ends are 0.3 m off-axis at 1 m,
            // which costs it ~6 % here; the others are the 16-point Gauss-Legendre rule on a
            // smooth integrand (1e-6).
            double tol = t.name == "point" ? 0.1 : 1e-6;
            EXPECT_NEAR(run(std::string(t.name).c_str(), *l, p, n).irradiance.y, expected,
                        tol * expected)
                << t.name;
        }
}

TEST(PhotometricLuminaire, AreaSamplerDrawsItsPdf) {
    // sample() is uniform in area; chi-square of where its points land on a 6 x 3 grid of the
    // opening, and pdf() agrees with the returned sample's pdf.
    auto l = place("lambert.ies");
    Random rng(11);
    const int N = 60000;
    std::vector<double> observed(18, 0.0), expected(18, N / 18.0);
    glm::dvec3 p(0.4, 0.5, 0.2);
    for (int k = 0; k < N; ++k) {
        LightSample s = l->sample(p, {rng.uniform(), rng.uniform()});
        ASSERT_GT(s.pdf, 0.0);
        EXPECT_NEAR(l->pdf(p, s.wi), s.pdf, 1e-9 * s.pdf);
        double x = s.position.x + 0.3,
               z = s.position.z + 0.15;  // local x = world x, local y = world z
        int i = std::clamp(int(x / 0.1), 0, 5), j = std::clamp(int(z / 0.1), 0, 2);
        observed[size_t(j * 6 + i)] += 1.0;
    }
    test::ChiSquareResult r = test::chiSquare(observed, expected);
    EXPECT_GT(r.pValue, 1e-3) << r.statistic;  // a correct sampler fails 0.1 % of seeds
}

TEST(PhotometricLuminaire, FluxFromASphereOfProbesMatchesTheTable) {
    // Irradiance integrated over a sphere of receivers (facing the centre) equals the flux, for
    // every well-formed file in the shared test data and the synthetic ones: a midpoint rule in
    // (theta, phi) of the `reference` technique (what `candela probe` runs) at 4 spp, radius 20
    // opening sizes (at least 1 m). The sphere's poles are on the aim so type C gamma steps fall
    // on rows; 1 % is the bound (the rule itself is good to ~1e-3 here, the Monte Carlo
    // noise summed over 26k receivers to ~1e-4).
    namespace fs = std::filesystem;
    std::vector<std::string> files;
    for (const char* f : {"lambert.ies", "side.ies", "spot.ies", "cplanes.ies"})
        files.push_back(kData + f);
    for (const auto& e : fs::recursive_directory_iterator(CANDELA_TEST_DATA "/photometry")) {
        std::string ext = e.path().extension().string();
        for (char& c : ext) c = char(std::tolower((unsigned char)c));
        if (e.is_regular_file() && (ext == ".ies" || ext == ".ldt"))
            files.push_back(e.path().string());
    }
    std::sort(files.begin(), files.end());
    int loaded = 0;
    for (const std::string& file : files) {
        std::unique_ptr<Luminaire> l;
        try {
            auto m = std::make_shared<PhotometricLuminaire>();
            m->file = file;
            m->data = PhotometricLuminaire::load(file);
            m->updateOpening();
            l = placed(m);
        } catch (const std::exception& e) {
            // Only the two deliberately broken files may fail.
            EXPECT_TRUE(file.find("Invalid Profile") != std::string::npos ||
                        file.find("Truncated Profile") != std::string::npos)
                << e.what();
            continue;
        }
        ++loaded;
        l->pose.position = {0, 0, 0};
        l->pose.aim = {0, -1, 0};
        l->pose.c0 = {1, 0, 0};
        double flux = l->power().y;
        double R = 20.0 * std::max(model(*l).size(), 0.05);
        glm::dvec3 x, y, z;
        l->pose.frame(x, y, z);
        const int nt = 720, np = 36;
        double sum = 0.0;
        EstimateOptions o;
        o.spp = 4;
        const TechniqueInfo* ref = findTechnique(LuminaireKind::Photometric, "reference");
        for (int i = 0; i < nt; ++i) {
            double th = kPi * (i + 0.5) / nt;
            for (int j = 0; j < np; ++j) {
                double ph = 2 * kPi * (j + 0.5) / np;
                glm::dvec3 d = std::sin(th) * std::cos(ph) * x + std::sin(th) * std::sin(ph) * y +
                               std::cos(th) * z;
                o.seed = uint64_t(i * np + j + 1);
                sum += ref->irradiance(*l, R * d, -d, o).irradiance.y * std::sin(th);
            }
        }
        double integrated = sum * R * R * (kPi / nt) * (2 * kPi / np);
        EXPECT_NEAR(integrated, flux, 0.01 * flux) << file;
    }
    EXPECT_GE(loaded, 58);  // 54 shared files and 4 synthetic ones
}

}  // namespace
}  // namespace candela
