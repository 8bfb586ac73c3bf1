// `candela grid`: illuminance on a calculation grid over an axis-aligned plane, with its summary
// (Emin, Eavg, Emax, U0 = Emin / Eavg, Emin / Emax), from each luminaire's CPU estimator in the
// registry, so every luminaire kind present and future is measured by its own technique.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <memory>

#include "app/commands/Commands.h"
#include "luminaires/Registry.h"
#include "scene/Bvh.h"
#include "scene/SceneIo.h"
#include "util/Error.h"

namespace candela {

namespace {

constexpr double kMaxGridPoints = 1e6;  ///< Refuse grids larger than this (a typo in --spacing).

const char* const kAxisNames[] = {"x", "y", "z"};

int uAxis(int axis) {
    return axis == 0 ? 1 : 0;
}
int vAxis(int axis) {
    return axis == 2 ? 1 : 2;
}

double parseFinite(const std::string& flag, const std::string& text) {
    try {
        size_t used = 0;
        double v = std::stod(text, &used);
        if (used == text.size() && std::isfinite(v)) return v;
    } catch (const std::exception&) {
    }
    throw InputError(flag + ": expected a finite number, got \"" + text + "\"");
}

/// "x0,v0,x1,v1" in metres.
void parseExtent(const std::string& text, GridSpec& spec) {
    std::vector<double> values;
    size_t start = 0;
    while (true) {
        size_t comma = text.find(',', start);
        values.push_back(parseFinite("--extent", text.substr(start, comma - start)));
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    if (values.size() != 4)
        throw InputError("--extent: expected u0,v0,u1,v1 (four numbers in metres), got \"" + text +
                         "\"");
    spec.lo = {std::min(values[0], values[2]), std::min(values[1], values[3])};
    spec.hi = {std::max(values[0], values[2]), std::max(values[1], values[3])};
}

double luminanceOf(const glm::dvec3& c) {
    return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
}

void printGrid(const GridResult& r, const GridSummary& s) {
    const GridSpec& g = r.spec;
    const CalcPlane& p = g.plane;
    std::printf(
        "plane %s = %g m (normal %s%s), extent %s %g..%g m, %s %g..%g m, spacing %g m, "
        "%zu x %zu points\n",
        kAxisNames[p.axis], p.offset, p.sign > 0 ? "+" : "-", kAxisNames[p.axis], p.uName().c_str(),
        g.lo.x, g.hi.x, p.vName().c_str(), g.lo.y, g.hi.y, g.spacing, r.u.size(), r.v.size());
    std::printf(
        "illuminance E [lx] (W/m2 for radiometric luminaires); rows %s [m], columns %s [m]\n",
        p.vName().c_str(), p.uName().c_str());
    std::printf("%7s\\%s", p.vName().c_str(), p.uName().c_str());
    for (double u : r.u) std::printf(" %9.3f", u);
    std::printf("\n");
    for (size_t j = 0; j < r.v.size(); ++j) {
        std::printf("%9.3f", r.v[j]);
        for (size_t i = 0; i < r.u.size(); ++i) std::printf(" %9.4g", r.lux[j * r.u.size() + i]);
        std::printf("\n");
    }
    std::printf("points: %zu\n", s.count);
    std::printf("Emin: %.6g lx\nEavg: %.6g lx\nEmax: %.6g lx\n", s.eMin, s.eAvg, s.eMax);
    std::printf("U0 (Emin/Eavg): %.4f\nEmin/Emax: %.4f\n", s.u0, s.minOverMax);
}

void writeCsv(const std::string& path, const GridResult& r) {
    std::ofstream out(path);
    if (!out) throw InputError(path + ": cannot write the CSV file");
    out << "x,y,z,E_lx,E_stderr\n";
    char line[160];
    for (size_t j = 0; j < r.v.size(); ++j)
        for (size_t i = 0; i < r.u.size(); ++i) {
            glm::dvec3 q = r.spec.plane.point(r.u[i], r.v[j]);
            size_t k = j * r.u.size() + i;
            std::snprintf(line, sizeof line, "%.9g,%.9g,%.9g,%.10g,%.4g\n", q.x, q.y, q.z, r.lux[k],
                          r.stdError[k]);
            out << line;
        }
    if (!out) throw InputError(path + ": write failed");
}

}  // namespace

glm::dvec3 CalcPlane::normal() const {
    glm::dvec3 n(0.0);
    n[axis] = sign;
    return n;
}

glm::dvec3 CalcPlane::point(double u, double v) const {
    glm::dvec3 p(0.0);
    p[axis] = offset;
    p[uAxis(axis)] = u;
    p[vAxis(axis)] = v;
    return p;
}

std::string CalcPlane::uName() const {
    return kAxisNames[uAxis(axis)];
}
std::string CalcPlane::vName() const {
    return kAxisNames[vAxis(axis)];
}

CalcPlane parsePlane(const std::string& text) {
    CalcPlane plane;
    std::string t = text;
    if (!t.empty() && (t[0] == '+' || t[0] == '-')) {
        plane.sign = t[0] == '-' ? -1.0 : 1.0;
        t = t.substr(1);
    }
    size_t eq = t.find('=');
    std::string axis = t.substr(0, eq);
    if (eq == std::string::npos || (axis != "x" && axis != "y" && axis != "z"))
        throw InputError("--plane: expected [+|-]x|y|z=VALUE in metres (e.g. y=0.8), got \"" +
                         text + "\"");
    plane.axis = axis[0] - 'x';
    plane.offset = parseFinite("--plane", t.substr(eq + 1));
    return plane;
}

std::vector<double> gridCoordinates(double lo, double hi, double spacing) {
    double n = std::max(1.0, std::floor((hi - lo) / spacing + 1e-9));
    double first = 0.5 * (lo + hi) - 0.5 * (n - 1.0) * spacing;
    std::vector<double> out;
    for (int i = 0; i < int(n); ++i) out.push_back(first + i * spacing);
    return out;
}

GridSummary summariseGrid(const std::vector<double>& lux) {
    GridSummary s;
    s.count = lux.size();
    if (lux.empty()) return s;
    s.eMin = *std::min_element(lux.begin(), lux.end());
    s.eMax = *std::max_element(lux.begin(), lux.end());
    double sum = 0.0;
    for (double e : lux) sum += e;
    s.eAvg = sum / double(lux.size());
    s.u0 = s.eAvg > 0.0 ? s.eMin / s.eAvg : 0.0;
    s.minOverMax = s.eMax > 0.0 ? s.eMin / s.eMax : 0.0;
    return s;
}

void defaultGridExtent(const Scene& scene, GridSpec& spec) {
    glm::vec3 lo = scene.boundsMin(), hi = scene.boundsMax();
    int a = spec.plane.axis;
    if (scene.meshes.empty() || !(hi[uAxis(a)] > lo[uAxis(a)]) || !(hi[vAxis(a)] > lo[vAxis(a)]))
        throw InputError("the scene's geometry does not span the plane: give --extent u0,v0,u1,v1");
    spec.lo = {lo[uAxis(a)], lo[vAxis(a)]};
    spec.hi = {hi[uAxis(a)], hi[vAxis(a)]};
}

GridResult computeGrid(const Scene& scene, const GridSpec& spec) {
    if (!(spec.spacing > 0.0) || !std::isfinite(spec.spacing))
        throw InputError("--spacing: expected a positive number of metres");
    for (double x : {spec.lo.x, spec.lo.y, spec.hi.x, spec.hi.y})
        if (!std::isfinite(x)) throw InputError("--extent: expected finite coordinates");
    if (!(spec.hi.x > spec.lo.x) || !(spec.hi.y > spec.lo.y))
        throw InputError("--extent: expected u1 > u0 and v1 > v0 (an area, not a line)");
    double nu = std::floor((spec.hi.x - spec.lo.x) / spec.spacing) + 1.0;
    double nv = std::floor((spec.hi.y - spec.lo.y) / spec.spacing) + 1.0;
    if (nu * nv > kMaxGridPoints)
        throw InputError("--spacing: " + std::to_string(spec.spacing) + " m gives over 1e6 points");
    std::vector<const TechniqueInfo*> chosen;
    for (const auto& l : scene.luminaires) {
        std::string name = spec.technique.empty() ? l->technique : spec.technique;
        const TechniqueInfo* t = findTechnique(l->kind(), name);
        if (!t || !t->irradiance)
            throw InputError(
                "--technique: \"" + name + "\" is not a technique of " + std::string(l->kind()) +
                " with a CPU estimator (available: " + techniqueNames(l->kind()) + ")");
        chosen.push_back(t);
    }
    std::unique_ptr<Bvh> bvh;
    std::unique_ptr<BvhVisibility> vis;
    EstimateOptions options;
    options.spp = std::max(1, spec.spp);
    if (spec.visibility) {
        bvh = std::make_unique<Bvh>(Bvh::build(scene));
        vis = std::make_unique<BvhVisibility>(*bvh);
        options.visibility = vis.get();
    }

    GridResult r;
    r.spec = spec;
    r.u = gridCoordinates(spec.lo.x, spec.hi.x, spec.spacing);
    r.v = gridCoordinates(spec.lo.y, spec.hi.y, spec.spacing);
    glm::dvec3 n = spec.plane.normal();
    for (size_t j = 0; j < r.v.size(); ++j)
        for (size_t i = 0; i < r.u.size(); ++i) {
            glm::dvec3 p = spec.plane.point(r.u[i], r.v[j]);
            glm::dvec3 e(0.0), var(0.0);
            size_t index = j * r.u.size() + i;
            for (size_t k = 0; k < scene.luminaires.size(); ++k) {
                EstimateOptions o = options;
                o.seed = 1000003ull * index + k + 1;
                Estimate est = chosen[k]->irradiance(*scene.luminaires[k], p, n, o);
                e += est.irradiance;
                var += est.stdError * est.stdError;
            }
            r.lux.push_back(luminanceOf(e));
            r.stdError.push_back(luminanceOf(glm::sqrt(var)));
        }
    return r;
}

int cmdGrid(const Args& args) {
    std::string scenePath, csvPath;
    GridSpec spec;
    bool havePlane = false, haveExtent = false;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "--plane") {
            spec.plane = parsePlane(flagValue(args, i));
            havePlane = true;
        } else if (a == "--extent") {
            parseExtent(flagValue(args, i), spec);
            haveExtent = true;
        } else if (a == "--spacing")
            spec.spacing = parseFinite(a, flagValue(args, i));
        else if (a == "--spp")
            spec.spp = parseInt(a, flagValue(args, i), 1, 1 << 24);
        else if (a == "--technique")
            spec.technique = flagValue(args, i);
        else if (a == "--visibility")
            spec.visibility = true;
        else if (a == "--csv")
            csvPath = flagValue(args, i);
        else if (!a.empty() && a[0] == '-')
            throw InputError("grid: unknown option " + a);
        else if (scenePath.empty())
            scenePath = a;
        else
            throw InputError("grid: unexpected argument " + a);
    }
    if (scenePath.empty() || !havePlane)
        throw InputError(
            "usage: candela grid scene.json --plane y=0.8 [--extent u0,v0,u1,v1] "
            "[--spacing 0.25] [--spp N] [--technique T] [--visibility] [--csv out.csv]");
    if (!(spec.spacing > 0.0))
        throw InputError("--spacing: expected a positive number of metres, got " +
                         std::to_string(spec.spacing));
    Scene scene = loadScene(scenePath);
    if (!haveExtent) defaultGridExtent(scene, spec);
    GridResult result = computeGrid(scene, spec);
    GridSummary summary = summariseGrid(result.lux);
    printGrid(result, summary);
    if (!csvPath.empty()) {
        writeCsv(csvPath, result);
        std::printf("wrote %s\n", csvPath.c_str());
    }
    return 0;
}

}  // namespace candela
