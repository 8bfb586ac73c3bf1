#include "renderer/FramePlan.h"

#include <glm/gtc/matrix_transform.hpp>
#include <sstream>

#include "renderer/ProgramVariants.h"
#include "renderer/passes/SourcePass.h"
#include "scene/Occlusion.h"
#include "util/Error.h"

namespace candela {

glm::mat4 cameraViewProj(const Camera& c, double aspect) {
    glm::dvec3 forward = c.target - c.position;
    glm::dvec3 up(0.0, 1.0, 0.0);
    if (glm::length(glm::cross(forward, up)) < 1e-9 * glm::length(forward)) up = {0.0, 0.0, -1.0};
    glm::dmat4 view = glm::lookAt(c.position, c.target, up);
    glm::dmat4 proj = glm::perspective(glm::radians(c.fovDeg), aspect, 0.01, 1000.0);
    return glm::mat4(proj * view);
}

std::string shadowPassName(const ShadeStep& step) {
    return "shadow:" + step.name.substr(step.name.find(':') + 1,
                                        step.name.rfind(':') - step.name.find(':') - 1);
}

bool FramePlan::progressive() const {
    for (const auto& s : shading)
        if (s.progressive) return true;
    return false;
}

std::vector<std::string> FramePlan::passNames() const {
    std::vector<std::string> names = {"gbuffer"};
    // Renderer::runShading prepares and shades each step in turn.
    for (const auto& s : shading) {
        names.insert(names.end(), s.prepasses.begin(), s.prepasses.end());
        if (s.shadowMaps) names.push_back(shadowPassName(s));
        names.push_back(s.name);
    }
    names.push_back("resolve");
    names.push_back("tonemap");
    return names;
}

const ShadeStep* FramePlan::stepOf(const Luminaire* source) const {
    for (const ShadeStep& s : shading)
        if (s.source == source) return &s;
    return nullptr;
}

const ShadeStep* FramePlan::stepOfKind(LuminaireKind kind) const {
    for (const ShadeStep& s : shading)
        if (s.technique->kind == kind) return &s;
    return nullptr;
}

std::string overrideFor(const std::string& techniqueOverride, LuminaireKind kind) {
    std::istringstream list(techniqueOverride);
    for (std::string name; std::getline(list, name, ',');) {
        // "KIND=NAME" applies to that kind only.
        if (size_t eq = name.find('='); eq != std::string::npos) {
            LuminaireKind named;
            if (!kindNamed(std::string_view(name).substr(0, eq), named) || named != kind) continue;
            name = name.substr(eq + 1);
        }
        if (findTechnique(kind, name) != nullptr) return name;
    }
    return {};
}

void checkTechniqueList(const std::string& techniqueOverride) {
    std::string kinds;
    for (const LuminaireKindInfo& k : sourceKinds())
        kinds += (kinds.empty() ? "" : ", ") + std::string(k.name);
    std::istringstream list(techniqueOverride);
    for (std::string item; std::getline(list, item, ',');) {
        size_t eq = item.find('=');
        std::string kind = eq == std::string::npos ? std::string() : item.substr(0, eq);
        std::string name = eq == std::string::npos ? item : item.substr(eq + 1);
        if (eq != std::string::npos) {
            const LuminaireKindInfo* found = findKind(kind);
            if (!found)
                throw InputError("technique list \"" + techniqueOverride + "\": unknown kind \"" +
                                 kind + "\" in \"" + item + "\" (kinds: " + kinds + ")");
            if (!findTechnique(found->kind, name))
                throw InputError("technique list \"" + techniqueOverride + "\": " + kind +
                                 " has no technique \"" + name +
                                 "\" (available: " + techniqueNames(found->kind) + ")");
            continue;
        }
        bool known = false;
        for (const LuminaireKindInfo& k : sourceKinds())
            known = known || findTechnique(k.kind, name) != nullptr;
        if (!known)
            throw InputError("technique list \"" + techniqueOverride +
                             "\": no kind has a technique \"" + name + "\"");
    }
}

namespace {

/// "luminaire \"Panel\"" or "environment", for messages.
std::string described(const Luminaire& source) {
    return source.atInfinity() ? std::string(kindName(source.kind()))
                               : "luminaire \"" + source.name + "\"";
}

/// The technique a source is shaded with: the list's, else its own.
const TechniqueInfo& chosenTechnique(const Luminaire& source,
                                     const std::string& techniqueOverride) {
    std::string name = overrideFor(techniqueOverride, source.kind());
    if (name.empty()) name = source.technique;
    const TechniqueInfo* t = findTechnique(source.kind(), name);
    if (!t)
        throw InputError(described(source) + ": unknown technique \"" + name + "\" for " +
                         std::string(kindName(source.kind())) +
                         " (available: " + techniqueNames(source.kind()) + ")");
    if (t->shader.empty())
        throw InputError(
            described(source) + ": technique \"" + name + "\" of " +
            std::string(kindName(source.kind())) +
            " runs on the CPU only (`candela probe`, benches); pick another technique to render");
    return *t;
}

}  // namespace

FramePlan planFrame(const Scene& scene, const glm::mat4& viewProj,
                    const std::string& techniqueOverride, Quantity quantity) {
    checkTechniqueList(techniqueOverride);  // a typo would silently leave sources their own
    FramePlan plan;
    plan.glossy = quantity == Quantity::Radiance && scene.hasGlossy();
    std::vector<const Luminaire*> sources = scene.sources();
    UnitSystem units = scene.units();
    std::vector<bool> shadows = sourcesNeedingShadows(scene, viewProj);
    for (size_t i = 0; i < sources.size(); ++i) {
        const Luminaire& source = *sources[i];
        const TechniqueInfo& t = chosenTechnique(source, techniqueOverride);
        ShadeStep step;
        step.source = &source;
        step.atInfinity = source.atInfinity();
        step.technique = &t;
        step.shadows = shadows[i];
        step.shadowMaps = step.shadows && t.shadowMaps;
        bool rays = step.shadows && !step.shadowMaps;
        step.program = programs::shading(t, step.shadowMaps, rays, plan.glossy);
        // A source at infinity gets no stochastic visibility ratio: only what its technique does
        // refines (Havran's lights are a fixed set, their shadow rays included).
        step.progressive = t.progressive || (!source.atInfinity() && (rays || plan.glossy));
        step.name = "shade:" + source.name + ":" + std::string(t.name);
        step.unitScale = float(scene.lightScale(source, units));
        step.prepasses = sourcePrepasses(t);
        plan.needsBvh = plan.needsBvh || rays;
        plan.shading.push_back(std::move(step));
    }
    return plan;
}

}  // namespace candela
