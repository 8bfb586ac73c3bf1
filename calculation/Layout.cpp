#include "calculation/Layout.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "luminaires/photometric/PhotometricLuminaire.h"
#include "scene/LayoutGrid.h"
#include "scene/Scene.h"
#include "scene/SceneIo.h"
#include "shaders/shared/Constants.h"
#include "util/Error.h"

namespace candela {

namespace {

using gpu::kPi;

/// The most one spacing of a layout may be of the other: an even light needs the rows and the
/// columns about as far apart.
constexpr double kSpacingRatio = 1.5;

/// Share of a photometry's flux emitted at gamma below 90 degrees (downwards for a luminaire
/// aimed down): zones of one degree, the mean over C of each zone's middle times its solid angle.
double downwardShare(const PhotometricData& d) {
    constexpr int kZones = 180, kAzimuths = 144;
    double down = 0.0, all = 0.0;
    for (int z = 0; z < kZones; ++z) {
        const double g = (z + 0.5) * kPi / kZones;
        double mean = 0.0;
        for (int c = 0; c < kAzimuths; ++c) {
            const double phi = 2.0 * kPi * (c + 0.5) / kAzimuths;
            mean += d.intensity(
                {std::sin(g) * std::cos(phi), std::sin(g) * std::sin(phi), std::cos(g)});
        }
        const double flux = mean / kAzimuths * 2.0 * kPi *
                            (std::cos(z * kPi / kZones) - std::cos((z + 1) * kPi / kZones));
        all += flux;
        if (z < kZones / 2) down += flux;
    }
    return all > 0.0 ? down / all : 0.0;
}

/// The next grid of a chain of near-square spacings over `size` (x, z), one step up (a column or
/// a row more, whichever spacing is the longer) or down.
glm::ivec2 stepGrid(glm::ivec2 grid, const glm::dvec2& size, int direction) {
    const double sx = size.x / grid.x, sz = size.y / grid.y;
    if (direction > 0) {
        if (sx >= sz)
            ++grid.x;
        else
            ++grid.y;
    } else {
        // Remove from the denser direction, so the spacing stays near square.
        if ((sx <= sz && grid.x > 1) || grid.y == 1)
            --grid.x;
        else
            --grid.y;
    }
    return grid;
}

/// The grid of about `count` luminaires over `size` with near-square spacing.
glm::ivec2 gridFor(int count, const glm::dvec2& size) {
    int columns = std::max(1, int(std::lround(std::sqrt(count * size.x / size.y))));
    int rows = std::max(1, (count + columns - 1) / columns);
    return {columns, rows};
}

}  // namespace

LayoutResult proposeLayout(const Scene& scene, const LayoutRequest& request,
                           const std::function<void(const std::string&)>& status) {
    const std::string file = scene.path.empty() ? "the scene" : scene.path;
    const TaskArea* area = nullptr;
    for (const TaskArea& a : scene.taskAreas)
        if (request.area.empty() ? scene.taskAreas.size() == 1 : a.name == request.area) area = &a;
    if (!area) {
        std::string names;
        for (const TaskArea& a : scene.taskAreas)
            names += (names.empty() ? "\"" : ", \"") + a.name + "\"";
        throw InputError(file + ": " +
                         (request.area.empty()
                              ? "name the task area to light (the scene has " +
                                    (names.empty() ? std::string("none") : names) + ")"
                              : "no task area \"" + request.area + "\" (it has " +
                                    (names.empty() ? std::string("none") : names) + ")"));
    }
    if (area->plane.axis != 1 || area->plane.sign < 0.0 || area->cylindrical)
        throw InputError(file + ": task area \"" + area->name +
                         "\": a layout lights a horizontal task area facing up (y=HEIGHT)");
    LayoutResult r;
    r.area = area->name;
    r.targetEm = request.targetEm > 0.0 ? request.targetEm : area->required.em;
    r.targetU0 = request.targetU0 > 0.0 ? request.targetU0 : area->required.u0;
    if (!(r.targetEm > 0.0))
        throw InputError(file + ": task area \"" + area->name +
                         "\" requires no Em: give the target maintained illuminance in lx");

    // Where the luminaires go: the room around the area's middle, else the scene's bounds.
    const LayoutFrame frame = layoutFrame(scene, *area);
    r.lo = frame.lo;
    r.hi = frame.hi;
    r.floorY = frame.floorY;
    if (!(r.hi.x > r.lo.x && r.hi.y > r.lo.y))
        throw InputError(file + ": task area \"" + area->name +
                         "\": no room around it to spread luminaires over");
    const double mountY = r.floorY + request.mountingHeight;
    const double above = mountY - area->plane.offset;
    if (!(above > 0.0))
        throw InputError(file + ": a mounting height of " + std::to_string(request.mountingHeight) +
                         " m puts the luminaires at or below task area \"" + area->name + "\"");

    // The luminaire, and the lumen method's first guess.
    nlohmann::json entry = request.luminaire;
    entry["position"] = {0.0, mountY, 0.0};
    std::unique_ptr<Luminaire> prototype =
        parseLuminaire(entry, json::Where{scene.path, "the layout's luminaire"});
    const PhotometricLuminaire* photometry = photometricModel(*prototype);
    if (!photometry)
        throw InputError(
            "the layout's luminaire: a photometry (IES, LDT, TM-33) or a GLDF "
            "variant, got a " +
            std::string(kindName(prototype->kind())));
    r.flux = photometry->data->fluxFromTable() * photometry->scale;
    r.maintenanceFactor = scene.maintenanceFactorOf(*prototype);
    r.downwardShare = downwardShare(*photometry->data);
    const glm::dvec2 size = r.hi - r.lo;
    r.roomIndex = size.x * size.y / (above * (size.x + size.y));
    r.utilisationGuess = r.downwardShare * r.roomIndex / (r.roomIndex + 1.0);
    if (!(r.flux > 0.0) || !(r.utilisationGuess > 0.0))
        throw InputError("the layout's luminaire: it sends no light downwards");
    const double areaM2 = size.x * size.y;
    r.lumenMethodCount = std::max(
        1,
        int(std::ceil(r.targetEm * areaM2 / (r.flux * r.maintenanceFactor * r.utilisationGuess))));

    // The scene the candidates are computed in: this task area alone, without its surroundings,
    // and without the luminaires the layout replaces.
    Scene trial = scene.clone();
    trial.taskAreas = {*area};
    trial.taskAreas[0].surroundings = false;
    trial.calcPoints.clear();
    trial.luminaires.erase(std::remove_if(trial.luminaires.begin(), trial.luminaires.end(),
                                          [&r](const auto& l) {
                                              return !l->atInfinity() && r.covers(l->pose.position);
                                          }),
                           trial.luminaires.end());
    const size_t kept = trial.luminaires.size();
    GridSpec how;
    applyLightChoice(trial, LightChoice{}, how);

    auto evaluate = [&](glm::ivec2 grid) -> const LayoutCandidate& {
        for (const LayoutCandidate& c : r.tried)
            if (c.columns == grid.x && c.rows == grid.y) return c;
        LayoutCandidate c;
        c.columns = grid.x;
        c.rows = grid.y;
        c.spacing = {size.x / grid.x, size.y / grid.y};
        c.positions = layoutPositions(frame, grid.x, grid.y, request.mountingHeight);
        trial.luminaires.resize(kept);
        for (const glm::dvec3& p : c.positions) {
            auto l = prototype->clone();
            l->pose.position = p;
            trial.luminaires.push_back(std::move(l));
        }
        trial.updateBodies();
        SurfaceReport s = computeSurfaces(trial, how);
        const SurfaceResult& t = s.surfaces.at(0);
        c.em = t.summary.eAvg;
        c.u0 = t.summary.u0;
        c.eMin = t.summary.eMin;
        c.meets = c.em >= r.targetEm && (r.targetU0 <= 0.0 || c.u0 >= r.targetU0);
        r.light = s.light;
        if (status) {
            char line[160];
            std::snprintf(line, sizeof line, "%d x %d = %d luminaires: Em %.4g lx, U0 %.2f%s",
                          c.columns, c.rows, c.count(), c.em, c.u0, c.meets ? ", meets" : "");
            status(line);
        }
        r.tried.push_back(std::move(c));
        return r.tried.back();
    };

    glm::ivec2 grid = gridFor(r.lumenMethodCount, size);
    glm::ivec2 lowestMet(0), highestFailed(0);
    bool met = false;
    while (int(r.tried.size()) < request.maxTries) {
        const LayoutCandidate& c = evaluate(grid);
        if (c.meets) {
            lowestMet = grid;
            met = true;
            if (grid.x * grid.y == 1) break;
            glm::ivec2 down = stepGrid(grid, size, -1);
            if (down == highestFailed) break;
            grid = down;
        } else {
            highestFailed = grid;
            if (met) break;  // the next one up met: it is the smallest
            if (grid.x * grid.y >= request.maxLuminaires) break;
            // Short of Em: jump to the count the shortfall asks for (Em grows about as the
            // count); short of U0 alone: one step.
            const double need = c.em > 0.0 ? double(grid.x * grid.y) * r.targetEm / c.em
                                           : double(request.maxLuminaires);
            glm::ivec2 up = stepGrid(grid, size, +1);
            while (up.x * up.y < need && up.x * up.y < request.maxLuminaires)
                up = stepGrid(up, size, +1);
            grid = up;
        }
    }
    // Grids between the largest that failed and the smallest that met, with spacings within
    // kSpacingRatio of each other (a usual rule for an even layout), fewest first.
    if (met && highestFailed.x * highestFailed.y > 0) {
        const int low = highestFailed.x * highestFailed.y, high = lowestMet.x * lowestMet.y;
        std::vector<glm::ivec2> between;
        for (int columns = 1; columns <= high; ++columns)
            for (int rows = 1; columns * rows < high; ++rows) {
                if (columns * rows <= low) continue;
                double sx = size.x / columns, sz = size.y / rows;
                if (std::max(sx, sz) <= kSpacingRatio * std::min(sx, sz))
                    between.push_back({columns, rows});
            }
        std::sort(between.begin(), between.end(),
                  [](glm::ivec2 a, glm::ivec2 b) { return a.x * a.y < b.x * b.y; });
        for (glm::ivec2 g : between) {
            if (int(r.tried.size()) >= request.maxTries) break;
            if (evaluate(g).meets) {
                lowestMet = g;
                break;
            }
        }
    }
    if (met)
        for (size_t i = 0; i < r.tried.size(); ++i)
            if (r.tried[i].columns == lowestMet.x && r.tried[i].rows == lowestMet.y)
                r.chosen = int(i);
    return r;
}

nlohmann::json applyLayout(const Scene& scene, const LayoutRequest& request,
                           const LayoutResult& result) {
    const LayoutCandidate* best = result.best();
    if (!best) throw InputError("no layout met the target: nothing to apply");
    auto replaced = [&result](const nlohmann::json& position) {
        return result.covers({position[0].get<double>(), 0.0, position[2].get<double>()});
    };
    nlohmann::json doc = sceneToJson(scene);
    nlohmann::json luminaires = nlohmann::json::array(), layouts = nlohmann::json::array();
    for (const nlohmann::json& entry : doc["luminaires"])
        if (!entry.contains("position") || !replaced(entry["position"]))
            luminaires.push_back(entry);
    // The scene's layouts written back (sceneToJson keeps those still as placed) go where any
    // of their luminaires is replaced.
    if (doc.contains("layouts"))
        for (const nlohmann::json& source : doc["layouts"]) {
            bool keep = true;
            for (const LayoutItem& layout : scene.layouts)
                if (layout.source == source)
                    for (const nlohmann::json& placed : layout.placed)
                        keep = keep && !replaced(placed["position"]);
            if (keep) layouts.push_back(source);
        }
    layouts.push_back({{"name", request.name},
                       {"area", result.area},
                       {"grid", {best->columns, best->rows}},
                       {"height", request.mountingHeight},
                       {"luminaire", request.luminaire}});
    doc["luminaires"] = luminaires;
    doc["layouts"] = layouts;
    return doc;
}

}  // namespace candela
