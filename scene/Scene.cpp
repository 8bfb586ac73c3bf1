#include "scene/Scene.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>

#include "luminaires/environment/Environment.h"
#include "luminaires/environment/EnvironmentLight.h"
#include "util/Error.h"

namespace candela {

float Material::phongExponent() const {
    // alpha = roughness^2 (glTF perceptual roughness). Walter et al. 2007, "Microfacet Models
    // for Refraction", match a Phong exponent to a Beckmann width alpha as n = 2 / alpha^2 - 2.
    // alpha is kept at or above 1e-3 so a roughness of 0 gives a large but finite exponent
    // (about 2e6).
    float alpha = std::max(roughness * roughness, 1e-3f);
    return std::max(2.f / (alpha * alpha) - 2.f, 0.f);
}

void Mesh::computeBounds() {
    if (positions.empty()) {
        boundsMin = boundsMax = glm::vec3(0.f);
        return;
    }
    boundsMin = boundsMax = positions[0];
    for (const glm::vec3& p : positions) {
        boundsMin = glm::min(boundsMin, p);
        boundsMax = glm::max(boundsMax, p);
    }
}

Scene Scene::clone() const {
    Scene copy;
    copy.path = path;
    copy.geometry = geometry;
    copy.meshes = meshes;
    copy.materials = materials;
    copy.luminaires.reserve(luminaires.size());
    for (const auto& luminaire : luminaires) copy.luminaires.push_back(luminaire->clone());
    copy.layouts = layouts;
    copy.environment = environment;
    copy.environmentMap = environmentMap;  // immutable, shared
    copy.environmentSequence = environmentSequence;
    copy.mEnvironmentLight = mEnvironmentLight;  // immutable, shared: the same source
    copy.camera = camera;
    copy.project = project;
    copy.maintenanceFactor = maintenanceFactor;
    copy.taskAreas = taskAreas;
    copy.calcPoints = calcPoints;
    copy.glareObservers = glareObservers;
    return copy;
}

std::vector<std::string> Scene::inputFiles() const {
    std::vector<std::string> files;
    if (!path.empty()) files.push_back(path);
    for (const GeometryItem& item : geometry)
        files.insert(files.end(), item.files.begin(), item.files.end());
    for (const auto& luminaire : luminaires) {
        std::vector<std::string> own = sourceFiles(*luminaire);
        files.insert(files.end(), own.begin(), own.end());
    }
    if (environmentSequence) {
        const std::vector<std::string>& frames = environmentSequence->files();
        files.insert(files.end(), frames.begin(), frames.end());
    } else if (environmentMap && environment.is_object() && environment.contains("file")) {
        files.push_back(environmentMap->source());  // the resolved file (a sky has no file)
    }
    return files;
}

bool Scene::updateBodies(size_t maxTriangles) {
    std::vector<Mesh> bodies;
    std::vector<double> reflectances;  ///< Of each body, for its material.
    size_t triangleTotal = 0;
    for (const Mesh& m : meshes)
        if (!m.luminaireBody) triangleTotal += m.triangleCount();
    for (const auto& l : luminaires) {
        LuminaireBody source = body(*l);
        triangleTotal += source.triangles.size() / 3;
        if (triangleTotal > maxTriangles)
            throw InputError((path.empty() ? std::string("the scene") : path) + ": luminaire \"" +
                             l->name + "\": the geometry and the luminaires' bodies make more " +
                             "than " + std::to_string(maxTriangles) +
                             " triangles; leave bodies out (\"body\": false) or use fewer");
        Mesh body;
        body.name = l->name + " (body)";
        body.luminaireBody = true;
        body.hidden = !source.drawn;
        // A luminous box (a polygon swept straight, or flat) cannot shadow itself.
        if (body.hidden) body.shape = MeshShape::Convex;
        const std::vector<glm::dvec3>& triangles = source.triangles;
        for (size_t t = 0; t + 2 < triangles.size(); t += 3) {
            glm::dvec3 a = triangles[t], b = triangles[t + 1], c = triangles[t + 2];
            glm::dvec3 n = glm::cross(b - a, c - a);
            double length = glm::length(n);
            if (!(length > 0.0)) continue;  // degenerate: nothing to draw or hit
            auto base = uint32_t(body.positions.size());
            for (const glm::dvec3& p : {a, b, c}) {
                body.positions.push_back(glm::vec3(p));
                body.normals.push_back(glm::vec3(n / length));
                body.indices.push_back(base++);
            }
        }
        if (body.indices.empty()) continue;
        body.computeBounds();
        bodies.push_back(std::move(body));
        reflectances.push_back(source.reflectance);
    }
    // Neither L3D nor the photometric formats hold a housing's material: "luminaire housing"
    // (black) unless the scene entry gives a reflectance, one material per reflectance.
    for (size_t b = 0; b < bodies.size(); ++b) {
        std::string name = "luminaire housing";
        if (reflectances[b] > 0.0) {
            char text[32];
            std::snprintf(text, sizeof text, " %.3g", reflectances[b]);
            name += text;
        }
        auto found = std::find_if(materials.begin(), materials.end(),
                                  [&](const Material& m) { return m.name == name; });
        if (found == materials.end()) {
            Material m;
            m.name = name;
            m.albedo = glm::vec3(float(reflectances[b]));
            m.specular = glm::vec3(0.f);
            materials.push_back(m);
            found = materials.end() - 1;
        }
        bodies[b].material = uint32_t(found - materials.begin());
    }
    // Unchanged (an edit of another luminaire, or of none with a body): the geometry stays.
    std::vector<const Mesh*> old;
    for (const Mesh& m : meshes)
        if (m.luminaireBody) old.push_back(&m);
    bool same = old.size() == bodies.size();
    for (size_t i = 0; same && i < bodies.size(); ++i)
        same = old[i]->name == bodies[i].name && old[i]->positions == bodies[i].positions &&
               old[i]->material == bodies[i].material && old[i]->hidden == bodies[i].hidden;
    if (same) return false;
    // Out with the old bodies, keeping the geometry entries' mesh indices right (an entry added
    // after a body came in after it); in with the new ones, after every entry's meshes.
    std::vector<uint32_t> newIndex(meshes.size(), 0);
    std::vector<Mesh> kept;
    kept.reserve(meshes.size() + bodies.size());
    for (size_t m = 0; m < meshes.size(); ++m) {
        newIndex[m] = uint32_t(kept.size());
        if (!meshes[m].luminaireBody) kept.push_back(std::move(meshes[m]));
    }
    for (GeometryItem& item : geometry)
        for (uint32_t& m : item.meshes) m = newIndex[m];
    for (Mesh& body : bodies) kept.push_back(std::move(body));
    meshes = std::move(kept);
    return true;
}

bool Scene::hasSurfaces() const {
    return std::any_of(meshes.begin(), meshes.end(),
                       [](const Mesh& m) { return !m.luminaireBody && m.triangleCount() > 0; });
}

size_t Scene::bodyCount() const {
    return size_t(
        std::count_if(meshes.begin(), meshes.end(), [](const Mesh& m) { return m.luminaireBody; }));
}

glm::vec3 Scene::boundsMin() const {
    bool any = false;
    glm::vec3 lo(0.f);
    for (const Mesh& mesh : meshes) {
        if (mesh.positions.empty()) continue;
        lo = any ? glm::min(lo, mesh.boundsMin) : mesh.boundsMin;
        any = true;
    }
    return lo;
}

glm::vec3 Scene::boundsMax() const {
    bool any = false;
    glm::vec3 hi(0.f);
    for (const Mesh& mesh : meshes) {
        if (mesh.positions.empty()) continue;
        hi = any ? glm::max(hi, mesh.boundsMax) : mesh.boundsMax;
        any = true;
    }
    return hi;
}

UnitSystem Scene::units() const {
    bool photometric = false, radiometric = false;
    auto count = [&](Quantities q) {
        (q == Quantities::Photometric ? photometric : radiometric) = true;
    };
    for (const auto& l : luminaires) count(l->quantities());
    if (!environment.is_null()) count(environmentQuantities(environment));
    return unitSystemOf(photometric, radiometric);
}

double Scene::unitScale(const Luminaire& luminaire) const {
    return unitScale(luminaire, units());
}

double Scene::unitScale(const Luminaire& luminaire, const UnitSystem& units) const {
    return units.scale(luminaire.quantities());
}

double Scene::maintenanceFactorOf(const Luminaire& source) const {
    return source.atInfinity() ? 1.0 : source.maintenanceFactor.value_or(maintenanceFactor);
}

bool Scene::maintained() const {
    for (const auto& l : luminaires)
        if (maintenanceFactorOf(*l) < 1.0) return true;
    return false;
}

std::string Scene::bodiesNote() const {
    size_t boxes = 0, housings = 0;
    bool black = true;
    for (const Mesh& m : meshes) {
        if (!m.luminaireBody) continue;
        ++(m.hidden ? boxes : housings);
        black = black && m.material < materials.size() &&
                materials[m.material].albedo == glm::vec3(0.f);
    }
    if (boxes + housings == 0) return "luminaire bodies: none (no luminaire has a body)";
    std::string kinds;
    if (boxes) kinds = std::to_string(boxes) + " luminous box" + (boxes > 1 ? "es" : "");
    if (housings)
        kinds += (kinds.empty() ? "" : ", ") + std::to_string(housings) + " L3D housing" +
                 (housings > 1 ? "s" : "");
    return "luminaire bodies: " + kinds + ", opaque and " +
           (black ? "black" : "of the reflectance their entries give") +
           ", block other luminaires' light and the reflected light";
}

std::string Scene::maintenanceNote() const {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%g", maintenanceFactor);
    if (!maintained()) return std::string("maintenance factor ") + buffer + " (initial values)";
    std::string note = std::string("maintained values: maintenance factor ") + buffer;
    std::string own;
    for (const auto& l : luminaires) {
        if (!l->maintenanceFactor || *l->maintenanceFactor == maintenanceFactor) continue;
        std::snprintf(buffer, sizeof buffer, "%g", *l->maintenanceFactor);
        own += (own.empty() ? "" : ", ") + ("\"" + l->name + "\" ") + buffer;
    }
    return own.empty() ? note : note + " (own factors: " + own + ")";
}

double Scene::lightScale(const Luminaire& source) const {
    return lightScale(source, units());
}

double Scene::lightScale(const Luminaire& source, const UnitSystem& units) const {
    return unitScale(source, units) * maintenanceFactorOf(source);
}

double Scene::environmentUnitScale() const {
    return environment.is_null() ? 1.0 : units().scale(environmentQuantities(environment));
}

const Luminaire* Scene::environmentLight() const {
    if (!environmentMap) return nullptr;
    const EnvironmentLight* light =
        mEnvironmentLight ? environmentModel(*mEnvironmentLight) : nullptr;
    if (!light || light->sharedMap() != environmentMap ||
        light->quantities() != environmentQuantities(environment))
        mEnvironmentLight = placedEnvironment(
            std::make_shared<EnvironmentLight>(environmentMap, environmentQuantities(environment)));
    return mEnvironmentLight.get();
}

std::vector<const Luminaire*> Scene::sources() const {
    std::vector<const Luminaire*> out;
    if (const Luminaire* environment = environmentLight()) out.push_back(environment);
    for (const auto& l : luminaires) out.push_back(l.get());
    return out;
}

bool Scene::hasGlossy() const {
    // Only materials some mesh uses count: an unused glossy material changes no pixel.
    for (const Mesh& mesh : meshes)
        if (mesh.material < materials.size() && materials[mesh.material].isGlossy()) return true;
    return false;
}

}  // namespace candela
