#include "tests/hardcases/HardCases.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "luminaires/lambertian/LambertianRect.h"
#include "luminaires/lightfield/LightField.h"
#include "luminaires/photometric/PhotometricLuminaire.h"
#include "shaders/shared/Constants.h"
#include "tests/TestUtil.h"

namespace candela::hard {

namespace {

using gpu::kPi;

const char* const kClassNames[] = {"ordinary", "contact", "on-plane",     "grazing",      "behind",
                                   "far",      "tiny",    "huge",         "segment",      "point",
                                   "spike",    "zero",    "single-value", "bright-pixel", "table"};

// --- The test's own closed forms ------------------------------------------------------------

/// Keeps the part of the polygon (vectors from the receiver) where dot(n, v) >= 0.
std::vector<glm::dvec3> clipAtHorizon(const std::vector<glm::dvec3>& in, const glm::dvec3& n) {
    std::vector<glm::dvec3> out;
    for (size_t i = 0; i < in.size(); ++i) {
        const glm::dvec3& a = in[i];
        const glm::dvec3& b = in[(i + 1) % in.size()];
        double da = glm::dot(n, a), db = glm::dot(n, b);
        if (da >= 0.0) out.push_back(a);
        if ((da >= 0.0) != (db >= 0.0)) out.push_back(a + (da / (da - db)) * (b - a));
    }
    return out;
}

/// Lambert's formula, written with the edge's angle as asin of the cross product's length
/// (accurate for tiny and for nearly opposite edges alike through atan2).
double lambert(const std::vector<glm::dvec3>& poly, const glm::dvec3& n) {
    if (poly.size() < 3) return 0.0;
    double sum = 0.0;
    for (size_t i = 0; i < poly.size(); ++i) {
        glm::dvec3 a = glm::normalize(poly[i]), b = glm::normalize(poly[(i + 1) % poly.size()]);
        glm::dvec3 c = glm::cross(a, b);
        double s = glm::length(c);
        if (s == 0.0) continue;
        double angle = std::atan2(s, glm::dot(a, b));
        sum += angle * glm::dot(n, c) / s;
    }
    return std::abs(sum) / (2.0 * kPi);
}

/// Corners of the rectangle [-a, a] x [-b, b] in the plane y = kH (x along world x, b along z).
std::vector<glm::dvec3> rectangle(double a, double b) {
    return {{-a, kH, -b}, {a, kH, -b}, {a, kH, b}, {-a, kH, b}};
}

/// Uniform quadratic B-spline (support [-1.5, 1.5] node spacings), the test's own.
double bspline(double t) {
    t = std::abs(t);
    if (t < 0.5) return 0.75 - t * t;
    if (t < 1.5) return 0.5 * (1.5 - t) * (1.5 - t);
    return 0.0;
}

/// Gauss-Legendre nodes on [0, 1] (8 points).
constexpr double kGx[8] = {0.0198550717512319, 0.1016667612931866, 0.2372337950418355,
                           0.4082826787521751, 0.5917173212478249, 0.7627662049581645,
                           0.8983332387068134, 0.9801449282487681};
constexpr double kGw[8] = {0.0506142681451881, 0.1111905172266872, 0.1568533229389436,
                           0.1813418916891810, 0.1813418916891810, 0.1568533229389436,
                           0.1111905172266872, 0.0506142681451881};

/// Integral of f over [x0, x1] x [y0, y1], Gauss-Legendre 8 x 8 on each cell of a grid whose
/// lines are the given breakpoints (the integrand must be smooth within each cell).
double gauss2(const std::function<double(double, double)>& f, std::vector<double> bx,
              std::vector<double> by) {
    std::sort(bx.begin(), bx.end());
    std::sort(by.begin(), by.end());
    double sum = 0.0;
    for (size_t j = 0; j + 1 < by.size(); ++j)
        for (size_t i = 0; i + 1 < bx.size(); ++i) {
            double w = bx[i + 1] - bx[i], h = by[j + 1] - by[j];
            if (!(w > 0.0 && h > 0.0)) continue;
            for (int a = 0; a < 8; ++a)
                for (int c = 0; c < 8; ++c)
                    sum += kGw[a] * kGw[c] * w * h * f(bx[i] + kGx[a] * w, by[j] + kGx[c] * h);
        }
    return sum;
}

/// Breakpoints from lo to hi: evenly `count` cells, plus `extra` points inside.
std::vector<double> breaks(double lo, double hi, int count, std::vector<double> extra = {}) {
    std::vector<double> out;
    for (int i = 0; i <= count; ++i) out.push_back(lo + (hi - lo) * i / count);
    for (double e : extra)
        if (e > lo && e < hi) out.push_back(e);
    return out;
}

/// Graded breakpoints around `centre` within [lo, hi]: distances 1e-12 .. size, doubling.
std::vector<double> graded(double lo, double hi, double centre) {
    std::vector<double> out = {lo, hi};
    if (centre > lo && centre < hi) out.push_back(centre);
    for (double d = 1e-12 * (hi - lo); d < hi - lo; d *= 2.0) {
        if (centre - d > lo) out.push_back(centre - d);
        if (centre + d < hi) out.push_back(centre + d);
    }
    return out;
}

// --- The emitters --------------------------------------------------------------------------

/// An IES LM-63 text of a rotationally symmetric table (one C plane) and its opening in metres.
std::string iesText(const std::vector<double>& gamma, const std::vector<double>& candela,
                    double length, double width) {
    char head[160];
    std::snprintf(
        head, sizeof head,
        "IESNA:LM-63-2002\n[TEST] hard case\nTILT=NONE\n1 -1 1 %zu 1 1 2 %.9g %.9g 0\n1 1 0\n",
        gamma.size(), width, length);
    std::string text = head;
    for (double g : gamma) text += std::to_string(g) + " ";
    text += "\n0\n";
    for (double c : candela) text += std::to_string(c) + " ";
    return text + "\n";
}

/// A photometric light 2 m up, aiming down, C0 along +x: its table and its opening
/// (length along x, width along z; zero width: a segment; both zero: a point).
std::shared_ptr<Luminaire> photometric(const std::string& ies, double length, double width) {
    auto model = std::make_shared<PhotometricLuminaire>();
    model->data = std::make_shared<const PhotometricData>(parseIes(ies, "hard-case.ies"));
    model->openingOverride = {length, width};
    if (length == 0.0 && width == 0.0) model->openingOverride = {0.0, 0.0};
    model->updateOpening();
    auto light = std::make_shared<Luminaire>(model);
    light->pose.position = {0, kH, 0};
    light->pose.aim = {0, -1, 0};
    light->pose.c0 = {1, 0, 0};
    light->technique = "reference";
    return light;
}

/// The cosine table (Lambertian emitter): I = 1000 cos(gamma) cd down, nothing up.
std::string lambertTable(double length, double width) {
    std::vector<double> g, c;
    for (int i = 0; i <= 90; ++i) {
        g.push_back(i);
        c.push_back(1000.0 * std::cos(i * kPi / 180.0));
    }
    return iesText(g, c, length, width);
}
std::string isotropicTable(double length, double width) {
    return iesText({0, 90, 180}, {1000, 1000, 1000}, length, width);
}

std::shared_ptr<Luminaire> rect(double a, double b, double L) {
    auto model = std::make_shared<LambertianRect>();
    model->size = {2 * a, 2 * b};
    model->emitted = glm::dvec3(L);
    model->luminous = true;
    auto light = std::make_shared<Luminaire>(model);
    light->pose.position = {0, kH, 0};
    light->pose.aim = {0, -1, 0};
    light->pose.c0 = {1, 0, 0};
    light->technique = "analytic";
    return light;
}

constexpr double kLfDelta = 0.05, kLfSpacing = 0.05, kLfHalf = 0.1;
constexpr int kLfNodes = 9;  ///< Nodes -0.2 .. 0.2: the B-splines sum to one on [-0.175, 0.175].

/// A light field, S at y = kH ([-0.1, 0.1]^2, delta 0.05), U above; images of 4 x 4 pixels of
/// value `value`, or (bright) zero but for one pixel of the centre image.
std::shared_ptr<Luminaire> lightField(double value, bool bright) {
    auto lf = std::make_shared<LightFieldData>();
    lf->delta = kLfDelta;
    lf->spacing = {kLfSpacing, kLfSpacing};
    lf->count = {kLfNodes, kLfNodes};
    lf->origin = glm::dvec2(-0.5 * (kLfNodes - 1) * kLfSpacing);
    lf->imageMin = glm::dvec2(-kLfHalf);
    lf->imageMax = glm::dvec2(kLfHalf);
    lf->width = lf->height = 4;
    lf->unit = "cd/m2";
    lf->images.resize(size_t(kLfNodes * kLfNodes));
    for (size_t m = 0; m < lf->images.size(); ++m) {
        lf->images[m].luminance.assign(16, bright ? 0.f : float(value));
        if (bright && m == size_t(kLfNodes * kLfNodes / 2))
            lf->images[m].luminance[5] = float(value);
    }
    lf->validate("hard-case light field");
    lf->precompute();
    auto model = std::make_shared<LightFieldLuminaire>();
    model->data = lf;
    auto light = std::make_shared<Luminaire>(model);
    light->pose.position = {0, kH + kLfDelta, 0};  // S at y = kH
    light->pose.aim = {0, -1, 0};
    light->pose.c0 = {1, 0, 0};
    light->technique = "reference";
    return light;
}

/// A light field's irradiance at p (normal n) by the test's own quadrature over U: the ray from
/// u through p crosses S at s(u); radiance C(s) sum_m Phi_m(u) (images of value `value`, or the
/// bright pixel alone); solid angle of du at p: dU cos_U / R^2.
double lightFieldQuadrature(const glm::dvec3& p, const glm::dvec3& n, double value, bool bright) {
    // Local frame: U at height kH + delta, S at kH; the luminaire's local x = world x, local y =
    // aim x c0 = (0,-1,0) x (1,0,0) = (0,0,1): world z.
    double hU = kH + kLfDelta - p.y, hS = kH - p.y;  // heights of U and S above p
    if (!(hS > 0.0)) return 0.0;
    double pixel = 2.0 * kLfHalf / 4.0;
    auto radiance = [&](double ux, double uz) {
        // Where the line from p to u crosses S.
        double f = hS / hU;
        double sx = p.x + (ux - p.x) * f, sz = p.z + (uz - p.z) * f;
        if (std::abs(sx) > kLfHalf || std::abs(sz) > kLfHalf) return 0.0;
        if (bright) {
            // Pixel 5 = row 1, column 1 (rows along s_y = world z, from the smallest).
            int i = int((sx + kLfHalf) / pixel), j = int((sz + kLfHalf) / pixel);
            if (i != 1 || j != 1) return 0.0;
            double cx = 0.0, cz = 0.0;  // the centre image's node
            return value * bspline((ux - cx) / kLfSpacing) * bspline((uz - cz) / kLfSpacing);
        }
        double w = 0.0, wx = 0.0, wz = 0.0;
        for (int k = 0; k < kLfNodes; ++k) {
            double node = -0.5 * (kLfNodes - 1) * kLfSpacing + k * kLfSpacing;
            wx += bspline((ux - node) / kLfSpacing);
            wz += bspline((uz - node) / kLfSpacing);
        }
        w = wx * wz;
        return value * w;
    };
    auto integrand = [&](double ux, double uz) {
        glm::dvec3 d(ux - p.x, hU, uz - p.z);
        double R2 = glm::dot(d, d), R = std::sqrt(R2);
        double cosP = glm::dot(n, d) / R;
        if (!(cosP > 0.0)) return 0.0;
        return radiance(ux, uz) * cosP * (hU / R) / R2;
    };
    // Breakpoints: the knots of every B-spline, the pixel edges mapped back to U (s = p + (u -
    // p) f, so u = p + (s - p) / f), and a grading around the foot of p on U.
    double lo = -0.5 * (kLfNodes - 1) * kLfSpacing - 1.5 * kLfSpacing, hi = -lo;
    std::vector<double> kx, kz;
    for (int k = 0; k <= 2 * kLfNodes + 2; ++k) {
        kx.push_back(lo + 0.5 * k * kLfSpacing);
        kz.push_back(lo + 0.5 * k * kLfSpacing);
    }
    double f = hS / hU;
    for (int k = 0; k <= 4; ++k) {
        double s = -kLfHalf + k * pixel;
        kx.push_back(p.x + (s - p.x) / f);
        kz.push_back(p.z + (s - p.z) / f);
    }
    std::vector<double> gx = graded(lo, hi, p.x), gz = graded(lo, hi, p.z);
    kx.insert(kx.end(), gx.begin(), gx.end());
    kz.insert(kz.end(), gz.begin(), gz.end());
    auto clip = [&](std::vector<double> v) {
        std::vector<double> out;
        for (double x : v)
            if (x >= lo && x <= hi) out.push_back(x);
        out.push_back(lo);
        out.push_back(hi);
        std::sort(out.begin(), out.end());
        out.erase(std::unique(out.begin(), out.end()), out.end());
        return out;
    };
    return gauss2(integrand, clip(kx), clip(kz));
}

}  // namespace

double areaForm(const glm::dvec3& p, const glm::dvec3& n, double a, double b,
                const std::function<double(double)>& intensity, std::vector<double> extraX,
                std::vector<double> extraZ) {
    auto f = [&](double x, double z) {
        glm::dvec3 v(x - p.x, kH - p.y, z - p.z);
        double r2 = glm::dot(v, v), r = std::sqrt(r2);
        double cosP = glm::dot(n, v) / r;
        if (!(cosP > 0.0)) return 0.0;
        double gamma = std::acos(std::clamp(v.y / r, -1.0, 1.0));  // from straight down
        return intensity(gamma) * cosP / r2;
    };
    std::vector<double> bx = graded(-a, a, std::clamp(p.x, -a, a)),
                        bz = graded(-b, b, std::clamp(p.z, -b, b));
    for (double e : breaks(-a, a, 16, extraX)) bx.push_back(e);
    for (double e : breaks(-b, b, 16, extraZ)) bz.push_back(e);
    return gauss2(f, bx, bz) / (4.0 * a * b);
}

namespace {

// --- The cases ------------------------------------------------------------------------------

/// The table of cases as it is built, group by group; the photometric groups set the table and
/// opening that add() gives the cases after them.
struct CaseBuilder {
    std::vector<Case> out;
    std::function<double(double)> table;  // the photometric cases' intensity, set per group
    std::vector<glm::dvec3> opening;      // and their opening (for the upper bound)
    double lMax = 0.0;                    // brightest radiance of the opening, cd/m2
    const glm::dvec3 up{0, 1, 0}, down{0, -1, 0}, side{1, 0, 0};

    void add(std::string name, LuminaireKind kind, Class cls,
             std::shared_ptr<const Luminaire> light, glm::dvec3 p, glm::dvec3 n, double expected,
             std::string how) {
        Case c;
        c.name = std::move(name);
        c.kind = kind;
        c.cls = cls;
        c.light = std::move(light);
        c.p = p;
        c.n = glm::normalize(n);
        c.expected = expected;
        c.how = std::move(how);
        // Float keeps about 7 digits of the emitter's 2 m: 1e-6 m is its last.
        c.belowFloat = std::abs(kH - p.y) < 1e-5 && std::abs(kH - p.y) > 0.0;
        if (c.kind == LuminaireKind::Photometric) {
            c.intensity = table;
            c.upperBound =
                opening.size() >= 3 ? kPi * lMax * polygonFormFactor(c.p, c.n, opening) : 0.0;
        }
        out.push_back(std::move(c));
    }
    void photometricLambert();
    void photometricSizes();
    void photometricSegment();
    void photometricPoint();
    void photometricTables();
    void photometricBox();
    void lambertianRect();
    void lightFields();
};

/// The cosine table's intensity, cd: 1000 cos(gamma) down, nothing up.
double cosine(double gamma) {
    return gamma <= kPi / 2 ? 1000.0 * std::cos(gamma) : 0.0;
}
/// The isotropic table's intensity, cd.
double isotropic(double) {
    return 1000.0;
}

/// Photometric, the cosine table on a 0.6 x 0.3 m opening: a Lambertian emitter of L = I0 / A.
void CaseBuilder::photometricLambert() {
    const double a = 0.3, b = 0.15, L = 1000.0 / (4 * a * b);
    table = cosine;
    opening = rectangle(a, b);
    lMax = L;
    auto light = photometric(lambertTable(2 * a, 2 * b), 2 * a, 2 * b);
    auto form = [&](glm::dvec3 p, glm::dvec3 n) {
        return kPi * L * polygonFormFactor(p, n, rectangle(a, b));
    };
    std::string lam = "pi L F (Lambert's polygon formula)";
    add("photometric/lambert/ordinary", LuminaireKind::Photometric, Class::Ordinary, light,
        {0.4, 1.0, 0.3}, up, form({0.4, 1.0, 0.3}, up), lam);
    for (double d : {1e-9, 1e-6, 1e-3}) {
        char name[64];
        std::snprintf(name, sizeof name, "photometric/lambert/contact-%g", d);
        add(name, LuminaireKind::Photometric, Class::Contact, light, {0, kH - d, 0}, up,
            form({0, kH - d, 0}, up), lam);
    }
    add("photometric/lambert/contact-1e-6-off-centre", LuminaireKind::Photometric, Class::Contact,
        light, {0.2, kH - 1e-6, 0.1}, up, form({0.2, kH - 1e-6, 0.1}, up), lam);
    add("photometric/lambert/on-plane-inside", LuminaireKind::Photometric, Class::OnPlane, light,
        {0, kH, 0}, up, kPi * L,
        "the front limit pi L (a receiver on the emitter: any value in [0, pi L])");
    add("photometric/lambert/in-plane-beside", LuminaireKind::Photometric, Class::OnPlane, light,
        {0.5, kH, 0}, {-1, 0, 0}, 0.0, "0: the opening is seen edge-on");
    add("photometric/lambert/grazing-contact", LuminaireKind::Photometric, Class::Grazing, light,
        {0, kH - 1e-9, 0}, side, form({0, kH - 1e-9, 0}, side), lam + ": pi L / 2");
    glm::dvec3 graze = glm::normalize(glm::dvec3(1, 1e-6, 0));
    add("photometric/lambert/grazing-normal-1m", LuminaireKind::Photometric, Class::Grazing, light,
        {-0.5, 1.0, 0}, graze, form({-0.5, 1.0, 0}, graze), lam);
    add("photometric/lambert/behind", LuminaireKind::Photometric, Class::Behind, light, {0, 2.5, 0},
        down, 0.0, "0: the table sends nothing up");
    double r = std::sqrt(1e10 + 9e8);
    add("photometric/lambert/far-1e5", LuminaireKind::Photometric, Class::Far, light,
        {3e4, kH - 1e5, 0}, up, 1000.0 * std::pow(1e5 / r, 2) / (r * r), "I cos(gamma) cos / r^2");
}

/// Tiny and huge openings.
void CaseBuilder::photometricSizes() {
    table = cosine;
    opening = rectangle(0.5e-6, 0.5e-6);
    lMax = 1000.0 / 1e-12;
    auto tiny = photometric(lambertTable(1e-6, 1e-6), 1e-6, 1e-6);
    glm::dvec3 p(0.3, 0.0, 0.2);
    glm::dvec3 v = glm::dvec3(0, kH, 0) - p;
    double r = glm::length(v), c = v.y / r;
    add("photometric/tiny-1e-6/at-2m", LuminaireKind::Photometric, Class::Tiny, tiny, p, up,
        1000.0 * c * c / (r * r), "the point law I cos / r^2 (the opening's size is 1e-6 of r)");
    p = {0.03, kH - 0.1, 0.02};
    v = glm::dvec3(0, kH, 0) - p;
    r = glm::length(v);
    c = v.y / r;
    add("photometric/tiny-1e-6/at-0.1m", LuminaireKind::Photometric, Class::Tiny, tiny, p, up,
        1000.0 * c * c / (r * r), "the point law I cos / r^2");
    auto huge = photometric(lambertTable(100, 100), 100, 100);
    const double L = 1000.0 / 1e4;
    opening = rectangle(50, 50);
    lMax = L;
    add("photometric/huge-100m/contact-1e-9", LuminaireKind::Photometric, Class::Huge, huge,
        {0, kH - 1e-9, 0}, up,
        kPi * L * polygonFormFactor({0, kH - 1e-9, 0}, up, rectangle(50, 50)), "pi L F");
    add("photometric/huge-100m/at-1m", LuminaireKind::Photometric, Class::Huge, huge,
        {10, kH - 1.0, -5}, up,
        kPi * L * polygonFormFactor({10, kH - 1.0, -5}, up, rectangle(50, 50)), "pi L F");
}

/// A segment (zero width) 0.6 m long, centred: the point law averaged along it, in closed form.
void CaseBuilder::photometricSegment() {
    opening.clear();
    auto lam = photometric(lambertTable(0.6, 0.0), 0.6, 0.0);
    auto iso = photometric(isotropicTable(0.6, 0.0), 0.6, 0.0);
    for (double d : {1e-9, 1e-3, 1.0}) {
        // Below its middle: cosine table I0 d^2 / r^4, isotropic I0 d / r^3, over x in [-0.3, 0.3].
        auto lamInt = [d](double x) {
            return 0.5 / d * (d * x / (x * x + d * d) + std::atan(x / d));
        };
        auto isoInt = [d](double x) { return x / (d * std::sqrt(x * x + d * d)); };
        char name[64];
        table = cosine;
        std::snprintf(name, sizeof name, "photometric/segment-cosine/below-%g", d);
        add(name, LuminaireKind::Photometric, Class::Segment, lam, {0, kH - d, 0}, up,
            1000.0 / 0.6 * (lamInt(0.3) - lamInt(-0.3)),
            "the line integral of I0 cos cos / r^2 (closed form)");
        table = isotropic;
        std::snprintf(name, sizeof name, "photometric/segment-isotropic/below-%g", d);
        add(name, LuminaireKind::Photometric, Class::Segment, iso, {0, kH - d, 0}, up,
            1000.0 / 0.6 * (isoInt(0.3) - isoInt(-0.3)),
            "the line integral of I0 cos / r^2 (closed form)");
    }
}

/// A point: the isotropic table.
void CaseBuilder::photometricPoint() {
    table = isotropic;
    auto point = photometric(isotropicTable(0.0, 0.0), 0.0, 0.0);
    for (double d : {1e-9, 1e-3, 1.0}) {
        char name[64];
        std::snprintf(name, sizeof name, "photometric/point/below-%g", d);
        add(name, LuminaireKind::Photometric, Class::Point, point, {0, kH - d, 0}, up,
            1000.0 / (d * d), "I / d^2");
    }
    // A normal 1e-6 rad above perpendicular to the light's direction: cos = sin(1e-6).
    glm::dvec3 toLight = glm::normalize(glm::dvec3(-1, 1, 0)),
               across = glm::normalize(glm::dvec3(1, 1, 0));
    glm::dvec3 n = std::cos(1e-6) * across + std::sin(1e-6) * toLight;
    add("photometric/point/grazing", LuminaireKind::Photometric, Class::Grazing, point,
        {1.0, 1.0, 0}, n, 1000.0 * std::sin(1e-6) / 2.0, "I cos / r^2 with cos = sin(1e-6)");
}

/// A 1e9 cd spike 0.5 degrees wide on the axis over 100 cd elsewhere, on a point and on a
/// 0.6 x 0.3 m opening; a table of zeros; a table with one non-zero value (on a point).
void CaseBuilder::photometricTables() {
    std::vector<double> g = {0, 0.5, 1, 2, 5, 10, 20, 40, 60, 90},
                        c = {1e9, 100, 100, 100, 100, 100, 100, 100, 100, 100};
    auto spike = [&](double gamma) {
        double deg = gamma * 180.0 / kPi;
        if (deg > 90.0) return 0.0;
        if (deg < 0.5) return 1e9 + (100.0 - 1e9) * deg / 0.5;
        return 100.0;
    };
    table = spike;
    auto point = photometric(iesText(g, c, 0, 0), 0, 0);
    add("photometric/spike-point/below-1m", LuminaireKind::Photometric, Class::Spike, point,
        {0, kH - 1.0, 0}, up, 1e9, "I / d^2");
    add("photometric/spike-point/off-axis", LuminaireKind::Photometric, Class::Spike, point,
        {0.5, kH - 1.0, 0}, up, 100.0 * (1.0 / std::sqrt(1.25)) / 1.25,
        "I cos / r^2 (100 cd there)");
    auto wide = photometric(iesText(g, c, 0.6, 0.3), 0.6, 0.3);
    opening = rectangle(0.3, 0.15);
    lMax = 1e9 / 0.18;
    // The spike's cone meets the opening within 1 m tan(0.5 deg) = 8.7 mm of the foot point.
    double w = std::tan(0.5 * kPi / 180.0);
    add("photometric/spike-opening/below-1m", LuminaireKind::Photometric, Class::Spike, wide,
        {0.05, kH - 1.0, 0.02}, up,
        areaForm({0.05, kH - 1.0, 0.02}, up, 0.3, 0.15, spike, {0.05 - w, 0.05 + w},
                 {0.02 - w, 0.02 + w}),
        "the area form by the test's graded quadrature");
    table = [](double) { return 0.0; };
    lMax = 0.0;
    auto zeros = photometric(iesText({0, 90, 180}, {0, 0, 0}, 0.6, 0.3), 0.6, 0.3);
    add("photometric/zeros/below-1m", LuminaireKind::Photometric, Class::Zero, zeros, {0.1, 1.0, 0},
        up, 0.0, "0");
    std::vector<double> g1 = {0, 20, 25, 30, 35, 40, 90}, c1 = {0, 0, 0, 500, 0, 0, 0};
    opening.clear();
    table = [](double gamma) {
        double deg = gamma * 180.0 / kPi;
        if (deg > 25.0 && deg < 30.0) return 500.0 * (deg - 25.0) / 5.0;
        if (deg >= 30.0 && deg < 35.0) return 500.0 * (35.0 - deg) / 5.0;
        return 0.0;
    };
    auto ring = photometric(iesText(g1, c1, 0, 0), 0, 0);
    double gamma = 28.0 * kPi / 180.0, h = 1.0, x = h * std::tan(gamma), r = h / std::cos(gamma);
    add("photometric/single-value/at-28deg", LuminaireKind::Photometric, Class::SingleValue, ring,
        {x, kH - h, 0}, up, 500.0 * (3.0 / 5.0) * std::cos(gamma) / (r * r),
        "I (linear between 25 and 30 deg) cos / r^2");
}

/// The up-and-down luminaire's table, cd at gamma (radians from straight down): a batwing down
/// (1500 cd at 35 degrees) and a wider one up (2600 cd at 125 degrees), light out of the sides,
/// tabulated every 5 degrees and linear between, as the estimators read a table.
double boxTabulated(double deg) {
    double r = deg * kPi / 180.0;
    if (deg < 90.0)
        return 900.0 * std::pow(std::cos(r), 0.6) * (1.0 + 1.4 * std::pow(std::sin(r), 2));
    double u = (180.0 - deg) * kPi / 180.0;
    return 700.0 * std::sqrt(std::cos(u)) * (1.0 + 2.5 * std::pow(std::sin(u), 2)) +
           120.0 * std::pow(std::sin(r), 8);
}
double boxTable(double gamma) {
    double deg = std::clamp(gamma * 180.0 / kPi, 0.0, 180.0);
    double i = std::min(std::floor(deg / 5.0), 35.0), t = deg / 5.0 - i;
    return boxTabulated(5.0 * i) + t * (boxTabulated(5.0 * (i + 1.0)) - boxTabulated(5.0 * i));
}

/// A large up-and-down luminaire, 0.45 x 0.45 m, its opening emitting up, down and (near its
/// plane) sideways as a box-shaped one does: receivers 0.1 and 0.3 m from it and 2 and 5
/// opening diagonals away, each against the area form by the test's own graded quadrature.
void CaseBuilder::photometricBox() {
    const double a = 0.225;
    std::vector<double> g, c;
    for (int i = 0; i <= 36; ++i) {
        g.push_back(5.0 * i);
        c.push_back(boxTabulated(5.0 * i));
    }
    table = boxTable;
    opening.clear();  // no peak: no upper bound needed
    lMax = 0.0;
    auto light = photometric(iesText(g, c, 2 * a, 2 * a), 2 * a, 2 * a);
    auto add1 = [&](const char* name, glm::dvec3 p, glm::dvec3 n) {
        add(std::string("photometric/box-up-down/") + name, LuminaireKind::Photometric,
            Class::Table, light, p, n, areaForm(p, glm::normalize(n), a, a, boxTable),
            "the area form by the test's graded quadrature");
    };
    add1("above-0.3m", {0.0, kH + 0.3, 0.0}, down);
    add1("above-0.1m-corner", {a, kH + 0.1, a}, down);
    add1("below-0.1m", {0.05, kH - 0.1, 0.02}, up);
    add1("beside-0.1m", {a + 0.1, kH - 0.05, 0.0}, {-1, 0, 0});
    add1("beside-above-0.1m", {a + 0.1, kH + 0.05, 0.1}, {-1, 0.2, 0});
    add1("below-2-diagonals", {0.6, kH - 1.1, 0.3}, up);
    add1("below-5-diagonals", {1.8, kH - 2.5, 0.9}, up);
}

/// The Lambertian rectangle 0.6 x 0.3 m.
void CaseBuilder::lambertianRect() {
    const double a = 0.3, b = 0.15, L = 1000.0;
    auto light = rect(a, b, L);
    auto form = [&](glm::dvec3 p, glm::dvec3 n) {
        return kPi * L * polygonFormFactor(p, n, rectangle(a, b));
    };
    std::string lam = "pi L F (Lambert's polygon formula)";
    add("lambertian-rect/ordinary", LuminaireKind::LambertianRect, Class::Ordinary, light,
        {0.4, 1.0, 0.3}, up, form({0.4, 1.0, 0.3}, up), lam);
    for (double d : {1e-9, 1e-6, 1e-3}) {
        char name[64];
        std::snprintf(name, sizeof name, "lambertian-rect/contact-%g", d);
        add(name, LuminaireKind::LambertianRect, Class::Contact, light, {0, kH - d, 0}, up,
            form({0, kH - d, 0}, up), lam);
    }
    add("lambertian-rect/on-plane-inside", LuminaireKind::LambertianRect, Class::OnPlane, light,
        {0, kH, 0}, up, kPi * L,
        "the front limit pi L (a receiver on the emitter: any value in [0, pi L])");
    add("lambertian-rect/grazing-contact", LuminaireKind::LambertianRect, Class::Grazing, light,
        {0, kH - 1e-9, 0}, side, form({0, kH - 1e-9, 0}, side), lam + ": pi L / 2");
    add("lambertian-rect/behind", LuminaireKind::LambertianRect, Class::Behind, light, {0, 2.5, 0},
        down, 0.0, "0: it emits down only");
    double r = std::sqrt(1e10 + 9e8);
    add("lambertian-rect/far-1e5", LuminaireKind::LambertianRect, Class::Far, light,
        {3e4, kH - 1e5, 0}, up, L * 4 * a * b * std::pow(1e5 / r, 2) / (r * r),
        "L A cos cos / r^2");
    auto tiny = rect(0.5e-6, 0.5e-6, L);
    glm::dvec3 p(0.3, 0.0, 0.2), v = glm::dvec3(0, kH, 0) - p;
    double rr = glm::length(v), c = v.y / rr;
    add("lambertian-rect/tiny-1e-6/at-2m", LuminaireKind::LambertianRect, Class::Tiny, tiny, p, up,
        L * 1e-12 * c * c / (rr * rr), "L A cos cos / r^2");
    auto huge = rect(50, 50, L);
    add("lambertian-rect/huge-100m/contact-1e-9", LuminaireKind::LambertianRect, Class::Huge, huge,
        {0, kH - 1e-9, 0}, up,
        kPi * L * polygonFormFactor({0, kH - 1e-9, 0}, up, rectangle(50, 50)), lam);
}

/// Light fields: a constant one (a Lambertian square on S where the B-splines sum to one) and
/// one with a single bright pixel; expected values from the test's quadrature over U.
void CaseBuilder::lightFields() {
    auto constant = lightField(1000.0, false);
    auto q = [](glm::dvec3 p, glm::dvec3 n) { return lightFieldQuadrature(p, n, 1000.0, false); };
    std::string how = "the test's quadrature over U";
    add("lightfield/ordinary", LuminaireKind::LightField, Class::Ordinary, constant,
        {0.3, 1.0, 0.1}, up, q({0.3, 1.0, 0.1}, up), how);
    for (double d : {1e-9, 1e-6, 1e-3}) {
        char name[64];
        std::snprintf(name, sizeof name, "lightfield/beyond-S-%g", d);
        add(name, LuminaireKind::LightField, Class::Contact, constant, {0.01, kH - d, 0.02}, up,
            q({0.01, kH - d, 0.02}, up), how);
    }
    add("lightfield/on-S", LuminaireKind::LightField, Class::OnPlane, constant, {0.01, kH, 0.02},
        up, q({0.01, kH - 1e-12, 0.02}, up), how + " (Eq. 9: the limit onto S)");
    add("lightfield/between-U-and-S", LuminaireKind::LightField, Class::Behind, constant,
        {0, kH + 0.025, 0}, up, 0.0, "0: inside the luminaire");
    add("lightfield/behind-U", LuminaireKind::LightField, Class::Behind, constant, {0, kH + 0.3, 0},
        down, 0.0, "0: behind it");
    add("lightfield/grazing-contact", LuminaireKind::LightField, Class::Grazing, constant,
        {0.01, kH - 1e-6, 0.02}, side, q({0.01, kH - 1e-6, 0.02}, side), how);
    double r = std::sqrt(1e10 + 9e8);
    add("lightfield/far-1e5", LuminaireKind::LightField, Class::Far, constant, {3e4, kH - 1e5, 0},
        up, 1000.0 * 0.04 * std::pow(1e5 / r, 2) / (r * r), "its far field: C A_S cos cos / r^2");
    auto bright = lightField(1e6, true);
    add("lightfield/bright-pixel/at-1m", LuminaireKind::LightField, Class::BrightPixel, bright,
        {-0.04, kH - 1.0, -0.03}, up, lightFieldQuadrature({-0.04, kH - 1.0, -0.03}, up, 1e6, true),
        how);
    add("lightfield/bright-pixel/near", LuminaireKind::LightField, Class::BrightPixel, bright,
        {-0.04, kH - 0.01, -0.03}, up,
        lightFieldQuadrature({-0.04, kH - 0.01, -0.03}, up, 1e6, true), how);
}

std::vector<Case> build() {
    CaseBuilder b;
    b.photometricLambert();
    b.photometricSizes();
    b.photometricSegment();
    b.photometricPoint();
    b.photometricTables();
    b.photometricBox();
    b.lambertianRect();
    b.lightFields();
    return std::move(b.out);
}

}  // namespace

const char* className(Class c) {
    return kClassNames[int(c)];
}

double pointLaw(const Case& c) {
    glm::dvec3 v = glm::dvec3(0, kH, 0) - c.p;
    double r = glm::length(v);
    double cosP = glm::dot(c.n, v) / r;
    if (!(cosP > 0.0) || !c.intensity) return 0.0;
    double gamma = std::acos(std::clamp(v.y / r, -1.0, 1.0));  // from straight down, the aim
    return c.intensity(gamma) * cosP / (r * r);
}

double polygonFormFactor(const glm::dvec3& p, const glm::dvec3& n,
                         const std::vector<glm::dvec3>& corners) {
    std::vector<glm::dvec3> rel;
    for (const glm::dvec3& c : corners) rel.push_back(c - p);
    return lambert(clipAtHorizon(rel, n), n);
}

const std::vector<Case>& cases() {
    static const std::vector<Case> all = build();
    return all;
}

}  // namespace candela::hard
