#include "renderer/FramePlan.h"

#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

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
    return "shadow:" + step.name.substr(step.name.find(':') + 1, step.name.rfind(':') - step.name.find(':') - 1);
}

bool FramePlan::progressive() const {
    for (const auto& s : shading)
        if (s.progressive) return true;
    return environment && environment->progressive;
}

std::vector<std::string> FramePlan::passNames() const {
    std::vector<std::string> names = {"gbuffer"};
    for (const auto& s : shading)
        if (s.shadowMaps) names.push_back(shadowPassName(s));
    if (environment && environmentTechnique->tables == EnvironmentTechniqueInfo::Tables::Cube) {
        names.push_back("env:cdf");
        names.push_back("env:samples");
    }
    // Renderer::runShading shades the environment first, then each luminaire.
    if (environment && environment->shadowMaps) names.push_back("shadow:environment");
    if (environment) names.push_back(environment->name);
    for (const auto& s : shading) names.push_back(s.name);
    names.push_back("resolve");
    names.push_back("tonemap");
    return names;
}

std::string overrideFor(const std::string& techniqueOverride, std::string_view kind) {
    std::istringstream list(techniqueOverride);
    for (std::string name; std::getline(list, name, ',');) {
        // "KIND=NAME" applies to that kind only ("environment" for the environment).
        if (size_t eq = name.find('='); eq != std::string::npos) {
            std::string_view scope = std::string_view(name).substr(0, eq);
            if (scope != (kind.empty() ? std::string_view("environment") : kind)) continue;
            name = name.substr(eq + 1);
        }
        if (kind.empty() ? findEnvironmentTechnique(name) != nullptr : findTechnique(kind, name) != nullptr)
            return name;
    }
    return {};
}

void checkTechniqueList(const std::string& techniqueOverride) {
    std::istringstream list(techniqueOverride);
    for (std::string item; std::getline(list, item, ',');) {
        size_t eq = item.find('=');
        std::string kind = eq == std::string::npos ? std::string() : item.substr(0, eq);
        std::string name = eq == std::string::npos ? item : item.substr(eq + 1);
        if (eq != std::string::npos) {
            bool environment = kind == "environment";
            if (!environment && !findKind(kind))
                throw InputError("technique list \"" + techniqueOverride + "\": unknown kind \"" + kind + "\" in \"" +
                                 item + "\" (kinds: lambertian-rect, lightfield, photometric, environment)");
            if (environment ? !findEnvironmentTechnique(name) : !findTechnique(kind, name))
                throw InputError("technique list \"" + techniqueOverride + "\": " + kind + " has no technique \"" + name +
                                 "\" (available: " + (environment ? environmentTechniqueNames() : techniqueNames(kind)) + ")");
            continue;
        }
        bool known = findEnvironmentTechnique(name) != nullptr;
        for (const LuminaireKindInfo& k : luminaireKinds()) known = known || findTechnique(k.kind, name) != nullptr;
        if (!known) throw InputError("technique list \"" + techniqueOverride + "\": no kind has a technique \"" + name + "\"");
    }
}

FramePlan planFrame(const Scene& scene, const glm::mat4& viewProj,
                    const std::string& techniqueOverride, Quantity quantity,
                    const std::string& environmentTechnique) {
    FramePlan plan;
    plan.glossy = quantity == Quantity::Radiance && scene.hasGlossy();
    std::vector<bool> shadows = luminairesNeedingShadows(scene, viewProj);
    for (size_t i = 0; i < scene.luminaires.size(); ++i) {
        const Luminaire& lum = *scene.luminaires[i];
        std::string name = overrideFor(techniqueOverride, lum.kind());
        if (name.empty()) name = lum.technique;
        const TechniqueInfo* t = findTechnique(lum.kind(), name);
        if (!t)
            throw InputError("luminaire \"" + lum.name + "\": unknown technique \"" + name +
                             "\" for " + std::string(lum.kind()) + " (available: " +
                             techniqueNames(lum.kind()) + ")");
        if (t->shader.empty())
            throw InputError("luminaire \"" + lum.name + "\": technique \"" + name + "\" of " +
                             std::string(lum.kind()) +
                             " runs on the CPU only (`candela probe`, benches); pick another technique to render");
        ShadeStep step;
        step.luminaire = int(i);
        step.technique = t;
        step.shadows = shadows[i];
        step.shadowMaps = step.shadows && t->shadowMaps;
        bool rays = step.shadows && !step.shadowMaps;
        step.program.vertex = "fullscreen.vert";
        step.program.fragment = std::string(t->shader);
        step.program.defines.push_back(std::string(t->define));
        if (step.shadowMaps) step.program.defines.push_back("SHADOW_MAPS");
        if (rays) step.program.defines.push_back("SHADOWS");
        if (plan.glossy) step.program.defines.push_back("GLOSSY");
        step.progressive = t->progressive || rays || plan.glossy;
        step.name = "shade:" + lum.name + ":" + name;
        step.unitScale = float(scene.unitScale(lum));
        plan.needsBvh = plan.needsBvh || rays;
        plan.shading.push_back(std::move(step));
    }
    if (scene.environmentMap) {
        std::string name = environmentTechnique;
        if (name.empty()) name = overrideFor(techniqueOverride, {});
        if (name.empty()) name = "balanced";
        const EnvironmentTechniqueInfo* t = findEnvironmentTechnique(name);
        if (!t)
            throw InputError("environment: unknown technique \"" + name + "\" (available: " +
                             environmentTechniqueNames() + ")");
        if (t->define.empty())
            throw InputError("environment: technique \"" + name +
                             "\" runs on the CPU only (`candela probe`, benches); pick another "
                             "technique to render");
        ShadeStep step;
        step.shadows = environmentNeedsShadows(scene, viewProj);
        step.shadowMaps = step.shadows && t->shadowMaps;
        bool rays = step.shadows && !step.shadowMaps;
        step.program.vertex = "fullscreen.vert";
        step.program.fragment = "environment_shade.frag";
        // A technique's define may name several macros, separated by spaces.
        std::istringstream macros{std::string(t->define)};
        for (std::string macro; macros >> macro;) step.program.defines.push_back(macro);
        if (step.shadowMaps) step.program.defines.push_back("SHADOW_MAPS");
        if (rays) step.program.defines.push_back("SHADOWS");
        if (plan.glossy) step.program.defines.push_back("GLOSSY");
        // The Havran lights are a fixed set: every light (and its shadow ray) each frame.
        step.progressive = t->progressive;
        step.name = "shade:environment:" + name;
        step.unitScale = float(scene.environmentUnitScale());
        plan.needsBvh = plan.needsBvh || rays;
        plan.environment = std::move(step);
        plan.environmentTechnique = t;
    }
    return plan;
}

}  // namespace candela
