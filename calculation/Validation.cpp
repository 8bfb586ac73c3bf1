#include "calculation/Validation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>

#include "calculation/CalculationGrid.h"
#include "calculation/Interreflection.h"
#include "luminaires/Registry.h"
#include "luminaires/lambertian/LambertianRect.h"
#include "luminaires/lightfield/LightField.h"
#include "luminaires/photometric/PhotometricLuminaire.h"
#include "scene/EmbreeVisibility.h"
#include "scene/SceneIo.h"
#include "shaders/shared/Constants.h"
#include "util/Error.h"

namespace candela {

namespace {

using gpu::kPi;

std::string resource(const std::string& relative) {
    return std::string(CANDELA_SOURCE_DIR) + "/resources/" + relative;
}

double luminance(const glm::dvec3& c) {
    return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
}

std::string number(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", x);
    return text;
}

Scene sceneOf(const std::string& geometry, const std::string& luminaire) {
    std::string text = R"({"geometry": [)" + geometry + R"(], "luminaires": [)" + luminaire + "]}";
    return parseScene(nlohmann::json::parse(text), resource("validation/case.json"));
}

/// A closed cube room of edge 2 m, its six faces looking in, of uniform reflectance rho.
std::string cubeRoom(double rho) {
    std::string a = number(rho);
    return R"({"box": {"center": [0, 1, 0], "size": [2, 2, 2], "inside": true}, "albedo": [)" + a +
           "," + a + "," + a + "]}";
}

/// The luminaires of the validation cases: an isotropic point source (1000 cd, synthetic), a
/// Lambertian table on a 0.6 x 0.3 m opening (synthetic), the measured OSRAM LED light field.
std::string isotropicAt(const glm::dvec3& p) {
    return R"({"type": "photometric", "name": "Isotropic", "file": ")" +
           resource("validation/isotropic.ies") + R"(", "position": [)" + number(p.x) + "," +
           number(p.y) + "," + number(p.z) + R"(], "technique": "point"})";
}
const char* kAreaSource = "Lambertian table on a 0.6 x 0.3 m opening (scattered)";

ValidationResult finish(ValidationResult r, double expected, double measured, double tolerance) {
    r.expected = expected;
    r.measured = measured;
    r.deviation = expected != 0.0 ? (measured - expected) / expected : measured;
    r.tolerance = tolerance;
    r.pass = std::isfinite(r.deviation) && std::abs(r.deviation) <= tolerance;
    return r;
}

/// The integrating cube: mean illuminance over every inner surface, from the radiosity solution.
ValidationResult cube(const std::string& source, double rho) {
    ValidationResult r;
    r.unit = "lx";
    std::string luminaire;
    if (source == "point") {
        luminaire = isotropicAt({0.13, 1.21, -0.17});
        r.description = "integrating cube, isotropic point source, rho " + number(rho) +
                        ": mean E = Phi / (S (1 - rho))";
    } else if (source == "area") {
        // The standard's sources are ideal: no housing absorbs the light going round the cube.
        luminaire = R"({"type": "photometric", "name": "Area", "file": ")" +
                    resource("validation/lambert.ies") +
                    R"(", "position": [0.1, 1.7, 0], "technique": "scattered", "body": false})";
        r.description = "integrating cube, " + std::string(kAreaSource) + ", rho " + number(rho) +
                        ": mean E = Phi / (S (1 - rho))";
    } else {
        luminaire = R"({"type": "lightfield", "name": "LED", "file": ")" +
                    resource("luminaires/osram-lertduw.lf.json") +
                    R"(", "position": [0, 1.5, 0], "technique": "restricted-cdf"})";
        r.description = "integrating cube, OSRAM LED light field (restricted-cdf), rho " +
                        number(rho) + ": mean E = Phi / (S (1 - rho))";
    }
    Scene scene = sceneOf(cubeRoom(rho), luminaire);
    InterreflectionOptions o;
    o.mesh.targetPatches = 1500;
    // The light field's estimates are Monte Carlo: enough samples that the direct flux's noise,
    // summed over 4500 patch points, stays near 0.1 %.
    o.directSpp = source == "lightfield" ? 64 : 16;
    Interreflection ir(scene, o);
    ir.compute();
    double area = 0.0, flux = 0.0, direct = 0.0;
    const RadiosityMesh& mesh = ir.mesh();
    for (size_t i = 0; i < mesh.patches.size(); ++i) {
        area += mesh.patches[i].area;
        flux += mesh.patches[i].area * luminance(ir.direct()[i] + ir.indirect()[i]);
        direct += mesh.patches[i].area * luminance(ir.direct()[i]);
    }
    double phi = luminance(scene.luminaires[0]->power());
    r.detail = std::to_string(mesh.patches.size()) + " patches, " +
               std::to_string(ir.lastIterations()) + " iterations; direct flux on the walls " +
               number(direct) + " of " + number(phi) + " lm";
    return finish(r, phi / (area * (1.0 - rho)), flux / area, 0.01);
}

/// The sphere: the interreflected part on every patch (and gathered at a few points) against
/// rho Phi / (A (1 - rho)); the one that deviates most is reported.
ValidationResult sphere(double rho) {
    ValidationResult r;
    r.unit = "lx";
    r.description =
        "closed geodesic sphere (r 1 m, 5120 facets), isotropic source 0.3 m off centre, rho " +
        number(rho) + ": interreflected E = rho Phi / (A (1 - rho)) everywhere";
    std::string a = number(rho);
    std::string geometry =
        R"({"sphere": {"center": [0, 0, 0], "radius": 1, "subdivisions": 4, "inside": true},
                             "albedo": [)" +
        a + "," + a + "," + a + "]}";
    // The direct light on the wall varies 3.4-fold from the nearest point to the farthest.
    Scene scene = sceneOf(geometry, isotropicAt({0.25, 0.15, -0.1}));
    InterreflectionOptions o;
    o.mesh.targetPatches = 5120;
    Interreflection ir(scene, o);
    ir.compute();
    const RadiosityMesh& mesh = ir.mesh();
    double phi = luminance(scene.luminaires[0]->power());
    double expected = rho * phi / (mesh.totalArea() * (1.0 - rho));
    double worst = expected;
    for (const glm::dvec3& e : ir.indirect())
        if (std::abs(luminance(e) - expected) > std::abs(worst - expected)) worst = luminance(e);
    // The final gather at points of the wall, facing in: within 2 % plus three standard errors.
    double gatherWorst = 0.0;
    for (glm::dvec3 d :
         {glm::dvec3(0, -1, 0), glm::dvec3(-0.6, 0.0, 0.8), glm::dvec3(0.0, 0.9, -0.43)}) {
        d = glm::normalize(d);
        EstimateOptions g;
        g.spp = 4096;
        g.seed = 11;
        Estimate e = ir.gather(0.995 * d, -d, g);
        double dev =
            (std::abs(luminance(e.irradiance) - expected) - 3.0 * luminance(e.stdError)) / expected;
        gatherWorst = std::max(gatherWorst, dev);
        if (dev > std::abs(worst - expected) / expected) worst = luminance(e.irradiance);
    }
    r.detail = std::to_string(mesh.patches.size()) + " patches, " +
               std::to_string(ir.lastIterations()) +
               " iterations; gather at 3 wall points within " + number(100.0 * gatherWorst) +
               " % (beyond 3 sigma)";
    return finish(r, expected, worst, 0.02);
}

/// Evaluates every listed technique at every point and keeps the one that deviates most from
/// the closed form (beyond three of its standard errors for stochastic ones).
struct Worst {
    double expected = 0.0, measured = 0.0, deviation = -1.0;
    std::string where;
    void add(double want, const Estimate& e, const std::string& label) {
        double got = luminance(e.irradiance), sigma = luminance(e.stdError);
        double dev = (std::abs(got - want) - 3.0 * sigma) / want;
        if (dev > deviation) {
            deviation = dev;
            expected = want;
            measured = got;
            where = label;
        }
    }
};

ValidationResult fromWorst(ValidationResult r, const Worst& w, double tolerance) {
    r.detail = "largest deviation: " + w.where;
    // Stochastic estimates are held to the tolerance beyond three standard errors.
    double shown =
        w.expected * (1.0 + (w.measured >= w.expected ? 1.0 : -1.0) * std::max(0.0, w.deviation));
    return finish(r, w.expected, shown, tolerance);
}

/// A light field that is a Lambertian rectangle of luminance L on S = [-a, a] x [-b, b] (delta
/// 0.05 m), made in memory. Its B-splines (0.05 m apart) sum to one over S widened by 0.3 m on
/// U, where every ray through S to the cases' points starts (at most 0.05 x 4 m / 1 m = 0.2 m
/// out: 4 m aside and 1 m below at worst).
std::unique_ptr<Luminaire> lambertianLightField(double L, double a, double b) {
    auto lf = std::make_shared<LightFieldData>();
    lf->delta = 0.05;
    lf->spacing = {0.05, 0.05};
    glm::ivec2 n(int(std::ceil((2.0 * a + 0.6) / 0.05)) + 2,
                 int(std::ceil((2.0 * b + 0.6) / 0.05)) + 2);
    lf->count = n;
    lf->origin = -0.5 * glm::dvec2(n - 1) * 0.05;
    lf->imageMin = {-a, -b};
    lf->imageMax = {a, b};
    lf->width = lf->height = 4;
    lf->unit = "cd/m2";
    lf->images.resize(size_t(n.x * n.y));
    for (auto& image : lf->images) image.luminance.assign(16, float(L));
    lf->validate("validation light field");
    lf->precompute();
    auto model = std::make_shared<LightFieldLuminaire>();
    model->data = lf;
    auto light = placed(std::move(model));
    light->technique = "reference";
    return light;
}

/// The same Lambertian emitter (luminance L, the rectangle [-a, a] x [-b, b] facing down at
/// height H over the origin) as each luminaire kind, with the techniques that are exact for it.
struct Emitter {
    std::unique_ptr<Luminaire> light;
    std::vector<const TechniqueInfo*> techniques;
};
std::vector<Emitter> lambertianEmitters(double a, double b, double H, double& L) {
    std::vector<Emitter> out;
    auto model = std::make_shared<LambertianRect>();
    model->size = {2 * a, 2 * b};
    L = 1000.0 / (4 * a * b);  // the photometric table's 1000 cd over the opening
    model->emitted = glm::dvec3(L);
    model->luminous = true;
    auto rect = placed(std::move(model));
    rect->pose.position = {0, H, 0};
    out.push_back({std::move(rect),
                   {findTechnique(LuminaireKind::LambertianRect, "analytic"),
                    findTechnique(LuminaireKind::LambertianRect, "reference")}});
    std::string lamp = R"({"type": "photometric", "name": "T", "file": ")" +
                       resource("validation/lambert.ies") + R"(", "opening": [)" + number(2 * a) +
                       "," + number(2 * b) + R"(], "position": [0, )" + number(H) + ", 0]}";
    Scene s = sceneOf("", lamp);
    out.push_back({std::move(s.luminaires[0]),
                   {findTechnique(LuminaireKind::Photometric, "scattered"),
                    findTechnique(LuminaireKind::Photometric, "reference")}});
    auto lf = lambertianLightField(L, a, b);
    lf->pose.position = {0, H + 0.05, 0};  // S at height H
    out.push_back({std::move(lf),
                   {findTechnique(LuminaireKind::LightField, "reference"),
                    findTechnique(LuminaireKind::LightField, "restricted-cdf")}});
    return out;
}

ValidationResult directPointPlane() {
    ValidationResult r;
    r.unit = "lx";
    r.description =
        "isotropic point source 2 m over a plane (every photometric technique): E = I cos^3 / h^2";
    Scene scene = sceneOf("", isotropicAt({0, 2, 0}));
    const Luminaire& lamp = *scene.luminaires[0];
    Worst w;
    for (const TechniqueInfo& t : techniques()) {
        if (t.kind != LuminaireKind::Photometric || !t.irradiance) continue;
        for (double d : {0.0, 0.7, 2.0, 4.5, 9.0}) {
            // The point d m from the foot of the source, along a direction off the axes.
            glm::dvec3 p(0.8 * d, 0.0, 0.6 * d);
            double c = 2.0 / std::sqrt(4.0 + d * d);
            EstimateOptions o;
            o.spp = 4096;
            w.add(1000.0 * c * c * c / 4.0, t.irradiance(lamp, p, {0, 1, 0}, o),
                  std::string(t.name) + " at " + number(d) + " m");
        }
    }
    return fromWorst(r, w, 0.005);
}

ValidationResult directRectangle(bool perpendicular) {
    ValidationResult r;
    r.unit = "lx";
    double a = perpendicular ? 0.3 : 0.25, b = perpendicular ? 0.15 : 0.25, H = 1.5, L = 0.0;
    r.description = std::string("Lambertian ") + (perpendicular ? "0.6 x 0.3 m" : "0.5 x 0.5 m") +
                    " rectangle over a " + (perpendicular ? "perpendicular" : "parallel") +
                    " plane (rectangle, photometric table, light field): E = L pi F (Howell)";
    Worst w;
    for (Emitter& e : lambertianEmitters(a, b, H, L))
        for (const TechniqueInfo* t : e.techniques) {
            std::vector<std::pair<glm::dvec3, glm::dvec3>> points;
            if (perpendicular)
                for (double y : {0.2, 0.8, 1.3}) points.push_back({{1.0, y, 0.1}, {-1, 0, 0}});
            else
                for (glm::dvec3 p : {glm::dvec3(0, 0, 0), glm::dvec3(0.4, 0, 0.2),
                                     glm::dvec3(1.5, 0, -1), glm::dvec3(3, 0.5, 2)})
                    points.push_back({p, {0, 1, 0}});
            for (const auto& [p, n] : points) {
                double F;
                if (perpendicular)  // element normal -x; the rectangle's plane y = H is c = H - p.y
                                    // away
                    F = perpendicularRectangleFactor(-b - p.z, b - p.z, p.x - a, p.x + a, H - p.y);
                else
                    F = parallelRectangleFactor(-a - p.x, a - p.x, -b - p.z, b - p.z, H - p.y);
                EstimateOptions o;
                o.spp = 65536;
                w.add(L * kPi * F, t->irradiance(*e.light, p, n, o),
                      std::string(kindName(t->kind)) + " " + std::string(t->name) + " at (" +
                          number(p.x) + ", " + number(p.y) + ", " + number(p.z) + ")");
            }
        }
    return fromWorst(r, w, 0.005);
}

ValidationResult obstruction() {
    ValidationResult r;
    r.unit = "lx";
    r.description =
        "a 0.8 x 0.6 m table 1.25 m under a 0.2 m Lambertian square: E = L pi F of the part seen";
    double L = 0.0, H = 2.0, table = 0.75, half = 0.4;
    Worst w;
    for (Emitter& e : lambertianEmitters(0.1, 0.1, H, L)) {
        Scene scene = sceneOf(
            R"({"plane": {"center": [0, 0.75, 0], "normal": [0, 1, 0], "size": [0.8, 0.6]}})", "");
        EmbreeVisibility visibility(scene);
        for (const TechniqueInfo* t : e.techniques)
            for (double x : {0.0, 0.6, 0.64, 0.68, 1.2}) {
                // The point sees the strip qx >= x + (half - x) H / table of the emitter.
                double lo = std::max(-0.1, x + (half - x) * H / table);
                double want =
                    lo >= 0.1 ? 0.0
                              : L * kPi * parallelRectangleFactor(lo - x, 0.1 - x, -0.1, 0.1, H);
                EstimateOptions o;
                o.spp = 65536;
                o.visibility = &visibility;
                Estimate got = t->irradiance(*e.light, {x, 0, 0}, {0, 1, 0}, o);
                std::string label = std::string(kindName(t->kind)) + " " + std::string(t->name) +
                                    " at x = " + number(x);
                if (want == 0.0) {
                    // The umbra: exactly dark (a relative deviation would divide by zero).
                    if (luminance(got.irradiance) != 0.0) w.add(1e-300, got, label + " (umbra)");
                    continue;
                }
                w.add(want, got, label);
            }
    }
    return fromWorst(r, w, 0.01);
}

// --- CIE 171:2006, Section 5: the standard's analytical cases ------------------------------------
//
// Each is computed the way a designer's calculation is (computeReceivers with applyLightChoice:
// the luminaires' own techniques, shadows and interreflected light wherever the scene calls for
// them, the design calculations' 1500 patches), in the standard's 4 m cube room (6 faces,
// S = 96 m2) with ideal sources (no housing). References are the closed forms the standard's
// tables come from, evaluated here in double precision.

const double kCieEdge = 4.0;     // the room's edge, m
const double kCieSource = 3.99;  // the sources' height: 1 cm under the ceiling, m

std::string cieRoom(double rho) {
    std::string a = number(rho);
    std::string e = number(kCieEdge);
    return R"({"box": {"center": [0, )" + number(0.5 * kCieEdge) + R"(, 0], "size": [)" + e + "," +
           e + "," + e + R"(], "inside": true}, "albedo": [)" + a + "," + a + "," + a + "]}";
}

/// A photometric luminaire without a body (the standard's sources are ideal).
std::string idealLuminaire(const std::string& file, const glm::dvec3& p,
                           const std::string& extra = "") {
    return R"({"type": "photometric", "name": "Source", "body": false, "file": ")" +
           resource(file) + R"(", "position": [)" + number(p.x) + "," + number(p.y) + "," +
           number(p.z) + "]" + extra + "}";
}

/// What a design calculation gives at the receivers: everything the scene calls for.
ReceiverResult designLight(const Scene& scene, const std::vector<Receiver>& receivers) {
    GridSpec how;
    applyLightChoice(scene, LightChoice{}, how);
    return computeReceivers(scene, how, receivers);
}

/// Floor points (facing up) and points of the wall x = 2 (facing into the room).
std::vector<Receiver> floorAndWallPoints() {
    std::vector<Receiver> out;
    for (glm::dvec3 p : {glm::dvec3(0, 0, 0), glm::dvec3(0.7, 0, 0.4), glm::dvec3(1.5, 0, -1.2),
                         glm::dvec3(1.9, 0, 1.9), glm::dvec3(-1.3, 0, 0.6)})
        out.push_back({p, {0, 1, 0}});
    for (glm::dvec3 p : {glm::dvec3(2, 0.5, 0), glm::dvec3(2, 2, 1), glm::dvec3(2, 3.5, -1.5),
                         glm::dvec3(2, 3.8, 0.2)})
        out.push_back({p, {-1, 0, 0}});
    return out;
}

std::string at(const glm::dvec3& p) {
    return "(" + number(p.x) + ", " + number(p.y) + ", " + number(p.z) + ")";
}

void addReceiver(Worst& w, double want, const ReceiverResult& got, size_t i,
                 const std::string& label) {
    Estimate e;
    e.irradiance = glm::dvec3(got.E[i]);
    e.stdError = glm::dvec3(got.stdError[i]);
    w.add(want, e, label);
}

/// A source alone in the black 4 m room, as a design calculation sees it at floorAndWallPoints,
/// against `want` at each point (1 %).
ValidationResult inBlackRoom(ValidationResult r, const std::string& luminaire,
                             const std::function<double(const Receiver&)>& want) {
    Scene scene = sceneOf(cieRoom(0), luminaire);
    std::vector<Receiver> points = floorAndWallPoints();
    ReceiverResult got = designLight(scene, points);
    Worst w;
    for (size_t i = 0; i < points.size(); ++i)
        addReceiver(w, want(points[i]), got, i, "at " + at(points[i].position));
    return fromWorst(r, w, 0.01);
}

/// 5.2: a point source with a non-uniform intensity distribution (1000 cos gamma cd, the
/// Lambertian table at 0.5 degree steps, whose linear interpolation is within 4e-5 of the cosine)
/// in a black room: E = I(gamma) cos(theta) / d^2 at floor and wall points.
ValidationResult ciePointSource() {
    ValidationResult r;
    r.unit = "lx";
    r.description =
        "CIE 171 5.2: a point source of 1000 cos(gamma) cd under the ceiling of a "
        "black 4 m room: E = I(gamma) cos(theta) / d^2 on the floor and a wall";
    glm::dvec3 s(0, kCieSource, 0);
    return inBlackRoom(r, idealLuminaire("validation/cosine-point.ies", s), [&](const Receiver& q) {
        glm::dvec3 d = s - q.position;
        double dist = glm::length(d);
        double cosGamma = d.y / dist, cosTheta = glm::dot(q.normal, d) / dist;
        return 1000.0 * std::max(0.0, cosGamma) * std::max(0.0, cosTheta) / (dist * dist);
    });
}

/// 5.3: a Lambertian area source (a 1 x 0.5 m opening of 1000 cd at nadir, L = 2000 cd/m2) in
/// a black room: E = L pi F with Howell's configuration factors, floor and wall points.
ValidationResult cieAreaSource() {
    ValidationResult r;
    r.unit = "lx";
    r.description =
        "CIE 171 5.3: a 1 x 0.5 m Lambertian source under the ceiling of a black 4 m "
        "room: E = L pi F (Howell) on the floor and a wall";
    const double a = 0.5, b = 0.25, L = 1000.0 / (4 * a * b);
    std::string lamp =
        idealLuminaire("validation/lambert.ies", {0, kCieSource, 0}, R"(, "opening": [1, 0.5])");
    return inBlackRoom(r, lamp, [&](const Receiver& q) {
        const glm::dvec3& p = q.position;
        double F = q.normal.y > 0.5 ? parallelRectangleFactor(-a - p.x, a - p.x, -b - p.z, b - p.z,
                                                              kCieSource - p.y)
                                    : perpendicularRectangleFactor(-b - p.z, b - p.z, p.x - a,
                                                                   p.x + a, kCieSource - p.y);
        return L * kPi * F;
    });
}

/// 5.4: luminous flux conservation: in a black room every lumen a luminaire emits lands on a
/// surface, so the direct flux over all six faces is the luminaires' flux. Two real files: a
/// direct-indirect linear luminaire and an asymmetric wall washer, each turned and off centre.
ValidationResult cieFlux() {
    ValidationResult r;
    r.unit = "lm";
    r.description =
        "CIE 171 5.4: a linear direct-indirect luminaire and an asymmetric wall "
        "washer in a black 4 m room: the flux on its faces = their flux";
    std::string lamps =
        idealLuminaire("luminaires/photometric/prolicht-e30.ldt", {0.4, 3.2, -0.3},
                       R"(, "c0": [0.866025, 0, 0.5])") +
        "," +
        idealLuminaire("luminaires/photometric/floor-washlight.ies", {-1.2, 2.5, 0.8},
                       R"(, "aim": [0.34, -0.94, 0], "c0": [0.94, 0.34, 0])");
    Scene scene = sceneOf(cieRoom(0), lamps);
    InterreflectionOptions o;
    o.mesh.targetPatches = GridSpec{}.patches;
    Interreflection ir(scene, o);
    ir.compute();
    double flux = 0.0, emitted = 0.0;
    for (size_t i = 0; i < ir.mesh().patches.size(); ++i)
        flux += ir.mesh().patches[i].area * luminance(ir.direct()[i]);
    UnitSystem units = scene.units();
    for (const auto& l : scene.luminaires)
        emitted += scene.lightScale(*l, units) * luminance(l->power());
    r.detail = std::to_string(ir.mesh().patches.size()) + " patches; " + number(emitted) +
               " lm emitted (the files' tables integrated)";
    return finish(r, emitted, flux, 0.01);
}

/// 5.6: light reflected by a diffuse surface: an 8 x 8 m floor of reflectance 0.6 alone (no
/// room), an isotropic 1000 cd source 2 m over it, points 1 m over it facing down (no direct
/// light reaches them). E = the integral of rho E_floor / pi cos cos / r^2 over the floor, by a
/// 1600 x 1600 midpoint quadrature (its error, for this smooth integrand, below 1e-6).
ValidationResult cieDiffuseReflection() {
    ValidationResult r;
    r.unit = "lx";
    r.description =
        "CIE 171 5.6: an 8 x 8 m floor of reflectance 0.6 under an isotropic source: "
        "the light it reflects onto points 1 m above, facing down";
    const double rho = 0.6, half = 4.0, hs = 2.0, hp = 1.0;
    Scene scene = sceneOf(
        R"({"plane": {"center": [0, 0, 0], "normal": [0, 1, 0], "size": [8, 8]}, "albedo": [0.6, 0.6, 0.6]})",
        isotropicAt({0, hs, 0}));
    std::vector<Receiver> points;
    for (glm::dvec3 p : {glm::dvec3(0, hp, 0.05), glm::dvec3(1.0, hp, 0.3), glm::dvec3(2.5, hp, -1),
                         glm::dvec3(3.6, hp, 3.6)})
        points.push_back({p, {0, -1, 0}});
    ReceiverResult got = designLight(scene, points);
    Worst w;
    const int n = 1600;
    const double cell = 2.0 * half / n;
    for (size_t i = 0; i < points.size(); ++i) {
        const glm::dvec3& p = points[i].position;
        double sum = 0.0;
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k) {
                double x = -half + (k + 0.5) * cell, z = -half + (j + 0.5) * cell;
                double rs2 = x * x + z * z + hs * hs;
                double floorE = 1000.0 * hs / (rs2 * std::sqrt(rs2));  // I cos / d^2
                double dx = x - p.x, dz = z - p.z, rp2 = dx * dx + dz * dz + hp * hp;
                sum += rho * floorE / kPi * hp * hp / (rp2 * rp2);  // cos cos / r^2 = h^2 / r^4
            }
        addReceiver(w, sum * cell * cell, got, i, "at " + at(p));
    }
    ValidationResult out = fromWorst(r, w, 0.01);
    out.detail = got.light + "; " + out.detail;
    return out;
}

/// 5.7: internal obstruction: a 1.2 x 1.2 m black panel 2 m over the floor, between a 0.6 m
/// square Lambertian source under the ceiling and the floor. A floor point sees the source less
/// the panel's shadow on it (the panel projected from the point onto the source's plane, a
/// rectangle): E = L pi (F(source) - F(source and shadow)).
ValidationResult cieObstruction() {
    ValidationResult r;
    r.unit = "lx";
    r.description =
        "CIE 171 5.7: a 1.2 m square panel 2 m up between a 0.6 m square Lambertian "
        "source and the floor of a black 4 m room: E = L pi F of the part seen";
    const double a = 0.3, L = 1000.0 / (4 * a * a);
    const double ox0 = 0.3, ox1 = 1.5, oz0 = -0.6, oz1 = 0.6, oh = 2.0;
    Scene scene = sceneOf(
        cieRoom(0) +
            R"(, {"plane": {"center": [0.9, 2, 0], "normal": [0, 1, 0], "size": [1.2, 1.2]}, "albedo": [0, 0, 0]})",
        idealLuminaire("validation/lambert.ies", {0, kCieSource, 0}, R"(, "opening": [0.6, 0.6])"));
    std::vector<Receiver> points;
    for (double x : {-1.2, 0.0, 0.3, 0.5, 0.9, 1.6, 1.9})
        points.push_back({{x, 0, 0.1}, {0, 1, 0}});
    ReceiverResult got = designLight(scene, points);
    Worst w;
    for (size_t i = 0; i < points.size(); ++i) {
        const glm::dvec3& p = points[i].position;
        double H = kCieSource - p.y, k = H / oh;
        auto F = [&](double x0, double x1, double z0, double z1) {
            if (x1 <= x0 || z1 <= z0) return 0.0;
            return parallelRectangleFactor(x0 - p.x, x1 - p.x, z0 - p.z, z1 - p.z, H);
        };
        double sx0 = p.x + (ox0 - p.x) * k, sx1 = p.x + (ox1 - p.x) * k;
        double sz0 = p.z + (oz0 - p.z) * k, sz1 = p.z + (oz1 - p.z) * k;
        double want = L * kPi *
                      (F(-a, a, -a, a) -
                       F(std::max(-a, sx0), std::min(a, sx1), std::max(-a, sz0), std::min(a, sz1)));
        std::string label = "at " + at(p);
        if (want < 1e-9) {
            // The umbra: exactly dark (a relative deviation would divide by zero).
            if (got.E[i] != 0.0) addReceiver(w, 1e-300, got, i, label + " (umbra)");
            continue;
        }
        addReceiver(w, want, got, i, label);
    }
    return fromWorst(r, w, 0.01);
}

/// 5.8: interreflection in the 4 m cube of uniform reflectance rho with an isotropic source at
/// its centre: the mean interreflected illuminance over the faces is rho Phi / (S (1 - rho))
/// (for rho = 0 the mean illuminance, Phi / S), from the design calculation's patches.
ValidationResult cieCube(double rho) {
    ValidationResult r;
    r.unit = "lx";
    r.description = "CIE 171 5.8: a 4 m cube of reflectance " + number(rho) +
                    ", isotropic source at its centre: mean " +
                    (rho > 0 ? "interreflected E = rho Phi / (S (1 - rho))" : "E = Phi / S");
    Scene scene = sceneOf(cieRoom(rho), isotropicAt({0, 2, 0}));
    InterreflectionOptions o;
    o.mesh.targetPatches = GridSpec{}.patches;
    Interreflection ir(scene, o);
    ir.compute();
    double area = 0.0, indirect = 0.0, total = 0.0;
    for (size_t i = 0; i < ir.mesh().patches.size(); ++i) {
        double A = ir.mesh().patches[i].area;
        area += A;
        indirect += A * luminance(ir.indirect()[i]);
        total += A * luminance(ir.direct()[i] + ir.indirect()[i]);
    }
    double phi = luminance(scene.luminaires[0]->power()), S = 6 * kCieEdge * kCieEdge;
    r.detail = std::to_string(ir.mesh().patches.size()) + " patches (" + number(area) + " m2), " +
               std::to_string(ir.lastIterations()) + " iterations; mean E " + number(total / area) +
               " lx against " + number(phi / (S * (1 - rho)));
    if (rho > 0) return finish(r, rho * phi / (S * (1 - rho)), indirect / area, 0.01);
    return finish(r, phi / S, total / area, 0.01);
}

const double kCieReflectances[] = {0, 0.2, 0.5, 0.8, 0.9, 0.95};

}  // namespace

ValidationResult validateClosedRoom(const Scene& scene, int patches) {
    auto start = std::chrono::steady_clock::now();
    const std::string file = scene.path.empty() ? "the scene" : scene.path;
    if (!scene.hasSurfaces())
        throw InputError(file + ": geometry: no surfaces (a closed room needs its walls)");
    if (scene.luminaires.empty())
        throw InputError(file + ": luminaires: none, so there is no light to balance");
    if (scene.environmentMap)
        throw InputError(
            file +
            ": environment: light from outside the room; a closed room has none (set it to null)");
    // Closed: every ray from each luminaire meets a surface from the side that faces it.
    EmbreeVisibility visibility(scene);
    RadiosityMesh mesh = RadiosityMesh::build(scene, RadiositySettings{patches, 0.0});
    const int kRays = 4096;
    for (const auto& l : scene.luminaires) {
        glm::dvec3 x, y, z;
        Pose emitter = l->emitterPose();
        emitter.frame(x, y, z);
        glm::dvec3 origin = emitter.position + 1e-3 * z;  // just in front of the opening
        int escaped = 0, backs = 0;
        glm::dvec3 firstEscape(0.0), firstBack(0.0);
        for (int i = 0; i < kRays; ++i) {
            // A Fibonacci sphere: directions spread evenly over all of it.
            double cz = 1.0 - (2.0 * i + 1.0) / kRays, r = std::sqrt(std::max(0.0, 1.0 - cz * cz));
            double phi = i * 2.39996322972865332;
            glm::dvec3 d(r * std::cos(phi), cz, r * std::sin(phi));
            // Its own body is no wall: the ray goes on through it (insideBody).
            EmbreeVisibility::Hit hit;
            glm::dvec3 from = origin;
            bool met = visibility.intersect(from, d, hit);
            for (int through = 0; met && through < 8; ++through) {
                const Mesh& m = scene.meshes[hit.mesh];
                if (!m.luminaireBody ||
                    !insideBody(origin, glm::dvec3(m.boundsMin), glm::dvec3(m.boundsMax)))
                    break;
                from += (hit.t + 1e-6) * d;
                met = visibility.intersect(from, d, hit);
            }
            if (!met) {
                if (escaped++ == 0) firstEscape = d;
                continue;
            }
            glm::dvec3 w;
            uint32_t p = mesh.patchAt(hit.mesh, hit.triangle, hit.u, hit.v, w);
            if (p != UINT32_MAX && glm::dot(mesh.patches[p].normal, d) > 0.0 && backs++ == 0)
                firstBack = d;
        }
        char where[96];
        if (escaped) {
            std::snprintf(where, sizeof where, "(%.2f, %.2f, %.2f)", firstEscape.x, firstEscape.y,
                          firstEscape.z);
            throw InputError(file + ": geometry: not a closed room: " + std::to_string(escaped) +
                             " of " + std::to_string(kRays) + " rays from luminaire \"" + l->name +
                             "\" escape (the first toward " + where + ")");
        }
        if (backs) {
            std::snprintf(where, sizeof where, "(%.2f, %.2f, %.2f)", firstBack.x, firstBack.y,
                          firstBack.z);
            throw InputError(file + ": geometry: " + std::to_string(backs) + " of " +
                             std::to_string(kRays) + " rays from luminaire \"" + l->name +
                             "\" reach the back of a surface (the first toward " + where +
                             "): a room's surfaces must face into it (a box with \"inside\": true, "
                             "planes' normals inwards)");
        }
    }
    InterreflectionOptions o;
    o.mesh.targetPatches = patches;
    Interreflection ir(scene, o);
    ir.compute();
    double absorbed = 0.0, flux = 0.0;
    for (size_t i = 0; i < ir.mesh().patches.size(); ++i) {
        const RadiosityMesh::Patch& p = ir.mesh().patches[i];
        absorbed +=
            p.area * luminance((glm::dvec3(1.0) - p.albedo) * (ir.direct()[i] + ir.indirect()[i]));
    }
    UnitSystem units = scene.units();
    for (const auto& l : scene.luminaires)
        flux += scene.lightScale(*l, units) * luminance(l->power());
    ValidationResult r;
    r.name = "closed-room";
    r.unit = units.photometric ? "lm" : "W";
    r.description =
        file + ": light absorbed by every surface, sum A (1 - rho) E, = the luminaires' flux";
    r.detail = std::to_string(ir.mesh().patches.size()) + " patches, " +
               std::to_string(ir.lastIterations()) + " iterations; closed: every one of " +
               std::to_string(kRays) +
               " rays from each luminaire meets a surface "
               "facing it";
    r = finish(r, flux, absorbed, 0.01);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return r;
}

double parallelRectangleFactor(double x0, double x1, double y0, double y1, double h) {
    // Howell C-11, element parallel to an a x b rectangle with a corner above it: with X = a/h,
    // Y = b/h, F = 1/(2 pi) [X/sqrt(1+X^2) atan(Y/sqrt(1+X^2)) + Y/sqrt(1+Y^2)
    // atan(X/sqrt(1+Y^2))], odd in a and in b, so signed corners add up to any rectangle.
    auto corner = [h](double a, double b) {
        double X = a / h, Y = b / h, sx = std::sqrt(1 + X * X), sy = std::sqrt(1 + Y * Y);
        return (X / sx * std::atan(Y / sx) + Y / sy * std::atan(X / sy)) / (2 * kPi);
    };
    return corner(x1, y1) - corner(x0, y1) - corner(x1, y0) + corner(x0, y0);
}

double perpendicularRectangleFactor(double y0, double y1, double z0, double z1, double c) {
    // Howell B-3: an element at the origin with normal +z, a rectangle in the plane x = c spanning
    // [0, a] along y and [0, b] along z (above the element's plane): with X = b/a, Y = c/a,
    // F = 1/(2 pi) [atan(1/Y) - Y/sqrt(X^2+Y^2) atan(1/sqrt(X^2+Y^2))]; odd in a, and F = 0 for
    // b = 0, so corners add up to [y0, y1] x [z0, z1] for z0 >= 0.
    auto corner = [c](double a, double b) {
        if (a == 0.0 || b <= 0.0) return 0.0;
        double s = a < 0.0 ? -1.0 : 1.0;
        a = std::abs(a);
        double X = b / a, Y = c / a, r = std::sqrt(X * X + Y * Y);
        return s * (std::atan(1.0 / Y) - Y / r * std::atan(1.0 / r)) / (2 * kPi);
    };
    return corner(y1, z1) - corner(y0, z1) - corner(y1, z0) + corner(y0, z0);
}

std::vector<std::string> validationCases() {
    std::vector<std::string> names;
    for (const char* source : {"point", "area", "lightfield"})
        for (const char* rho : {"0", "0.2", "0.5", "0.8"})
            names.push_back(std::string("cube-") + source + "-rho" + rho);
    for (const char* rho : {"0.2", "0.5", "0.8"}) names.push_back(std::string("sphere-rho") + rho);
    names.insert(names.end(), {"direct-point-plane", "direct-rect-parallel",
                               "direct-rect-perpendicular", "obstruction-table"});
    names.insert(names.end(), {"cie171-5.2-point", "cie171-5.3-area", "cie171-5.4-flux",
                               "cie171-5.6-reflection", "cie171-5.7-obstruction"});
    for (double rho : kCieReflectances) names.push_back("cie171-5.8-rho" + number(rho));
    return names;
}

ValidationResult runValidationCase(const std::string& name) {
    auto start = std::chrono::steady_clock::now();
    ValidationResult r;
    auto rhoOf = [&](const std::string& prefix) { return std::stod(name.substr(prefix.size())); };
    if (name.starts_with("cube-point-rho"))
        r = cube("point", rhoOf("cube-point-rho"));
    else if (name.starts_with("cube-area-rho"))
        r = cube("area", rhoOf("cube-area-rho"));
    else if (name.starts_with("cube-lightfield-rho"))
        r = cube("lightfield", rhoOf("cube-lightfield-rho"));
    else if (name.starts_with("sphere-rho"))
        r = sphere(rhoOf("sphere-rho"));
    else if (name == "direct-point-plane")
        r = directPointPlane();
    else if (name == "direct-rect-parallel")
        r = directRectangle(false);
    else if (name == "direct-rect-perpendicular")
        r = directRectangle(true);
    else if (name == "obstruction-table")
        r = obstruction();
    else if (name == "cie171-5.2-point")
        r = ciePointSource();
    else if (name == "cie171-5.3-area")
        r = cieAreaSource();
    else if (name == "cie171-5.4-flux")
        r = cieFlux();
    else if (name == "cie171-5.6-reflection")
        r = cieDiffuseReflection();
    else if (name == "cie171-5.7-obstruction")
        r = cieObstruction();
    else if (name.starts_with("cie171-5.8-rho") &&
             std::find_if(std::begin(kCieReflectances), std::end(kCieReflectances),
                          [&](double rho) { return "cie171-5.8-rho" + number(rho) == name; }) !=
                 std::end(kCieReflectances))
        r = cieCube(rhoOf("cie171-5.8-rho"));
    else {
        std::string known;
        for (const std::string& n : validationCases()) known += (known.empty() ? "" : ", ") + n;
        throw InputError("validate: unknown case \"" + name + "\" (known: " + known + ")");
    }
    r.name = name;
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return r;
}

}  // namespace candela
