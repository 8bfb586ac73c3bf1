#include "luminaires/lightfield/ProceduralLuminaire.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <thread>

#include "luminaires/Random.h"
#include "shaders/shared/Constants.h"
#include "util/Error.h"
#include "util/Threads.h"

namespace candela {

namespace {

using gpu::kPi;
constexpr double kMm = 1e-3;              // metres per millimetre
constexpr uint64_t kChunkRays = 1 << 16;  // emitted rays per deterministic chunk
constexpr int kMaxBounces = 4;            // reflector hits before a ray counts as trapped

/// A small Lambertian square emitting into the hemisphere around `normal`.
struct Die {
    glm::dvec3 centre;   ///< metres, source frame (focus at the origin)
    glm::dvec3 normal;   ///< unit
    glm::dvec3 tangent;  ///< unit, perpendicular to normal
    double size;         ///< edge length, metres
    double flux;         ///< lm
};

enum class CoverKind { Stripes, Prisms };

struct Design {
    std::string name, description;
    double focal;         ///< Focal length of the paraboloid z = r^2 / (4 f) - f, metres.
    glm::dvec2 aperture;  ///< Half-widths of the rectangular aperture, metres.
    double reflectance;   ///< Of the reflector (no unit).
    std::vector<Die> dies;
    CoverKind cover;
    double period;  ///< Lenslet period (stripes) or prism cell size, metres.
    double stripe;  ///< Stripe height (stripes), metres.
    glm::ivec2 count, resolution;
    double delta;  ///< U (the cover) to S, metres.
    uint64_t defaultRays;
    double coverZ() const {  ///< The cover plane, through the reflector's corners, metres.
        return glm::dot(aperture, aperture) / (4.0 * focal) - focal;
    }
};

Design makeDesign(const std::string& name) {
    Design d;
    d.name = name;
    glm::dvec3 down(0, 0, -1), up(0, 1, 0), x(1, 0, 0);
    if (name == "bike-headlight") {
        d.description =
            "paraboloid f 10 mm, aperture 45 x 35 mm, two dies facing the reflector, "
            "cover with stripes of cylindrical lenslets";
        d.focal = 10 * kMm;
        d.aperture = {22.5 * kMm, 17.5 * kMm};
        d.reflectance = 0.85;
        d.dies = {{{0, 0, 0}, down, x, 1.0 * kMm, 220.0},
                  {{0, 1.0 * kMm, 0}, down, x, 0.7 * kMm, 80.0}};
        d.cover = CoverKind::Stripes;
        d.period = 4 * kMm;
        d.stripe = 5 * kMm;
        d.count = {9, 7};
        d.resolution = {300, 300};
        d.delta = 30 * kMm;
        d.defaultRays = 32'000'000;
    } else if (name == "car-headlight") {
        d.description =
            "paraboloid f 25 mm, aperture 150 x 110 mm, four dies on a vertical board, "
            "cover with a grid of prisms (some frosted, some opaque)";
        d.focal = 25 * kMm;
        d.aperture = {75 * kMm, 55 * kMm};
        d.reflectance = 0.88;
        d.dies = {{{-2.5 * kMm, 0, 0}, up, x, 1.0 * kMm, 400.0},
                  {{0, 0, 0}, up, x, 1.0 * kMm, 400.0},
                  {{2.5 * kMm, 0, 0}, up, x, 1.0 * kMm, 400.0},
                  {{0, -0.5 * kMm, 1.5 * kMm}, -up, x, 0.8 * kMm, 200.0}};
        d.cover = CoverKind::Prisms;
        d.period = 10 * kMm;
        d.stripe = 0.0;
        d.count = {11, 9};
        d.resolution = {256, 256};
        d.delta = 50 * kMm;
        d.defaultRays = 40'000'000;
    } else {
        throw InputError("unknown procedural luminaire \"" + name +
                         "\" (expected bike-headlight or car-headlight)");
    }
    return d;
}

double gaussian(Random& rng) {  // Box-Muller, one of the pair
    double a = std::max(rng.uniform(), 1e-300), b = rng.uniform();
    return std::sqrt(-2.0 * std::log(a)) * std::cos(2.0 * kPi * b);
}

/// The cover at aperture point (x, y): returns the transmittance and changes the slopes
/// (dx/dz, dy/dz) of the ray, the paraxial model of a thin lenslet or prism.
double coverAt(const Design& d, glm::dvec2 p, glm::dvec2& slope, Random& rng) {
    glm::dvec2 q = p + d.aperture;  // from the aperture's corner, metres
    if (d.cover == CoverKind::Stripes) {
        int stripe = int(std::floor(q.y / d.stripe));
        if (stripe % 2 == 0) return 0.92;  // clear stripe
        // Cylindrical lenslets along x spreading the beam horizontally by up to +-10 degrees.
        double local = q.x / d.period - std::floor(q.x / d.period) - 0.5;
        slope.x += 2.0 * local * std::tan(10.0 * kPi / 180.0);
        return 0.88;
    }
    int i = int(std::floor(q.x / d.period)), j = int(std::floor(q.y / d.period));
    if (i % 6 == 3 && j % 4 == 1) return 0.0;  // opaque cells (a logo)
    // Prisms: aim down by 1 to 4 degrees, and sideways by -6..6 degrees.
    slope.y -= std::tan((1.0 + 1.5 * double((i + 2 * j) % 3)) * kPi / 180.0);
    slope.x += std::tan(6.0 * kPi / 180.0) * double((i * 7 + j * 3) % 5 - 2) / 2.0;
    if ((i + j) % 4 == 0) {  // frosted: a Gaussian spread of 3 degrees
        double sigma = std::tan(3.0 * kPi / 180.0);
        slope += sigma * glm::dvec2(gaussian(rng), gaussian(rng));
        return 0.8;
    }
    return 0.9;
}

/// Distance along d to the paraboloid x^2 + y^2 = 4 f (z + f), nearest root beyond a small
/// offset; infinity when there is none.
double hitParaboloid(double f, const glm::dvec3& p, const glm::dvec3& d) {
    constexpr double kEps = 1e-9;  // metres: do not re-hit the point just left
    double a = d.x * d.x + d.y * d.y;
    double b = p.x * d.x + p.y * d.y - 2.0 * f * d.z;
    double c = p.x * p.x + p.y * p.y - 4.0 * f * (p.z + f);
    const double none = std::numeric_limits<double>::infinity();
    if (a < 1e-14) {  // parallel to the axis: linear
        if (std::abs(b) < 1e-300) return none;
        double t = -c / (2.0 * b);
        return t > kEps ? t : none;
    }
    double disc = b * b - a * c;
    if (disc < 0.0) return none;
    double root = std::sqrt(disc);
    double t0 = (-b - root) / a, t1 = (-b + root) / a;
    if (t0 > kEps) return t0;
    return t1 > kEps ? t1 : none;
}

/// Traces one ray from a die; true with `out` (local frame, the cover at z = 0) when it leaves
/// through the cover.
bool traceOne(const Design& d, const std::vector<double>& dieCdf, double rayFlux, Random& rng,
              EmittedRay& out) {
    double pick = rng.uniform();
    size_t k = size_t(std::lower_bound(dieCdf.begin(), dieCdf.end(), pick) - dieCdf.begin());
    const Die& die = d.dies[std::min(k, d.dies.size() - 1)];
    glm::dvec3 bitangent = glm::cross(die.normal, die.tangent);
    glm::dvec3 p = die.centre + die.size * ((rng.uniform() - 0.5) * die.tangent +
                                            (rng.uniform() - 0.5) * bitangent);
    // Cosine-weighted hemisphere around the die's normal (Lambertian).
    double r2 = rng.uniform(), phi = 2.0 * kPi * rng.uniform(), r = std::sqrt(r2);
    glm::dvec3 dir = r * std::cos(phi) * die.tangent + r * std::sin(phi) * bitangent +
                     std::sqrt(1.0 - r2) * die.normal;
    double flux = rayFlux, zc = d.coverZ();
    const double none = std::numeric_limits<double>::infinity();
    for (int bounce = 0; bounce <= kMaxBounces; ++bounce) {
        // Exit through the housing's side walls |x| = Ax, |y| = Ay (black).
        double wall = none;
        for (int a = 0; a < 2; ++a)
            if (dir[a] != 0.0)
                wall = std::min(wall,
                                ((dir[a] > 0.0 ? d.aperture[a] : -d.aperture[a]) - p[a]) / dir[a]);
        double cover = dir.z > 0.0 ? (zc - p.z) / dir.z : none;
        double mirror = hitParaboloid(d.focal, p, dir);
        if (mirror < wall && mirror < cover) {
            p += mirror * dir;
            glm::dvec3 n = glm::normalize(glm::dvec3(2.0 * p.x, 2.0 * p.y, -4.0 * d.focal));
            dir = glm::normalize(dir - 2.0 * glm::dot(dir, n) * n);
            flux *= d.reflectance;
            continue;
        }
        // The shield in front of the dies stops direct light; the walls absorb.
        if (!(cover <= wall) || bounce == 0) return false;
        p += cover * dir;
        glm::dvec2 slope = glm::dvec2(dir) / dir.z;
        double t = coverAt(d, glm::dvec2(p), slope, rng);
        if (t <= 0.0) return false;
        out.position = glm::dvec3(p.x, p.y, 0.0);
        out.direction = glm::normalize(glm::dvec3(slope, 1.0));
        out.flux = flux * t;
        return true;
    }
    return false;  // trapped between reflections
}

struct Tracer {
    const Design& design;
    std::vector<double> dieCdf;
    double rayFlux;  ///< Flux of every emitted ray, lm.
    uint64_t seed;

    Tracer(const Design& d, uint64_t rays, uint64_t s) : design(d), seed(s) {
        double total = 0.0;
        for (const Die& die : d.dies) dieCdf.push_back(total += die.flux);
        for (double& c : dieCdf) c /= total;
        rayFlux = total / double(rays);
    }
    /// Rays [first, first + n) of the stream: one generator per chunk, so the result does not
    /// depend on how chunks are spread over threads.
    void chunk(uint64_t index, uint64_t n, std::vector<EmittedRay>& out) const {
        Random rng(seed * 0x9E3779B97F4A7C15ull + index * 0xD1B54A32D192ED03ull + 1);
        out.clear();
        EmittedRay ray;
        for (uint64_t k = 0; k < n; ++k)
            if (traceOne(design, dieCdf, rayFlux, rng, ray)) out.push_back(ray);
    }
};

/// Traces `rays` in chunks on `threads` threads, handing every chunk to `sink` in order.
template <class Sink>
void traceAll(const Tracer& tracer, uint64_t rays, int threads,
              const std::function<void(double)>& progress, Sink&& sink) {
    uint64_t chunks = (rays + kChunkRays - 1) / kChunkRays;
    std::vector<std::vector<EmittedRay>> batch(static_cast<size_t>(threads));
    for (uint64_t first = 0; first < chunks; first += uint64_t(threads)) {
        uint64_t inBatch = std::min<uint64_t>(uint64_t(threads), chunks - first);
        auto run = [&](uint64_t t) {
            uint64_t c = first + t;
            tracer.chunk(c, std::min(kChunkRays, rays - c * kChunkRays), batch[size_t(t)]);
        };
        runSlices(int(inBatch), [&](int t) { run(uint64_t(t)); });
        for (uint64_t t = 0; t < inBatch; ++t) sink(batch[size_t(t)]);
        if (progress) progress(double(first + inBatch) / double(chunks));
    }
}

}  // namespace

const std::vector<std::string>& proceduralPresets() {
    static const std::vector<std::string> names = {"bike-headlight", "car-headlight"};
    return names;
}

std::string proceduralDescription(const std::string& preset) {
    if (std::find(proceduralPresets().begin(), proceduralPresets().end(), preset) ==
        proceduralPresets().end())
        return "";
    return makeDesign(preset).description;
}

ProceduralResult buildProceduralLuminaire(const std::string& preset,
                                          const ProceduralOptions& options) {
    auto start = std::chrono::steady_clock::now();
    Design design = makeDesign(preset);
    ProceduralResult result;
    uint64_t rays = options.rays > 0 ? options.rays : design.defaultRays;
    int threads = options.threads > 0 ? options.threads : int(std::thread::hardware_concurrency());
    threads = std::clamp(threads, 1, 8);

    // Pilot run (its own seed) for the image extent on S; U is the aperture, delta is fixed.
    uint64_t pilotRays = std::clamp<uint64_t>(rays / 8, 1, 400'000);
    Tracer pilot(design, pilotRays, options.seed ^ 0x5EED5EED5EEDull);
    std::vector<EmittedRay> pilotOut;
    traceAll(pilot, pilotRays, threads, {}, [&](const std::vector<EmittedRay>& c) {
        pilotOut.insert(pilotOut.end(), c.begin(), c.end());
    });
    LayoutOptions lo;
    lo.count = design.count;
    lo.resolution = design.resolution;
    lo.delta = design.delta;
    lo.uHalfWidth = design.aperture;
    lo.uPlaneZ = 0.0;
    lo.coverage = 0.998;  // the beam is compact: keep nearly all of it
    lo.what = preset;
    LayoutChoice choice = chooseLayout(pilotOut, lo);
    result.layout = choice.layout;

    Tracer tracer(design, rays, options.seed);
    LightFieldAccumulator acc(choice.layout);
    auto traceStart = std::chrono::steady_clock::now();
    traceAll(tracer, rays, threads, options.progress, [&](const std::vector<EmittedRay>& c) {
        for (const EmittedRay& r : c) {
            acc.add(r);
            result.exitFlux += r.flux;
        }
        result.exitRays += c.size();
    });
    auto traced = std::chrono::steady_clock::now();
    result.traceSeconds = std::chrono::duration<double>(traced - traceStart).count();
    result.emittedRays = rays;
    for (const Die& die : design.dies) result.emittedFlux += die.flux;
    result.data = acc.build("cd/m2");
    result.report = acc.report();
    auto end = std::chrono::steady_clock::now();
    result.report.seconds = std::chrono::duration<double>(end - traced).count();
    result.totalSeconds = std::chrono::duration<double>(end - start).count();
    return result;
}

}  // namespace candela
