#include "renderer/ProgramVariants.h"

#include <set>

#include "luminaires/Registry.h"

namespace candela {

namespace programs {

ProgramKey gbuffer() {
    return {"gbuffer.vert", "gbuffer.frag", "", {}};
}
ProgramKey indirect() {
    return {"indirect.vert", "indirect.frag", "", {}};
}
ProgramKey resolve() {
    return {"fullscreen.vert", "resolve.frag", "", {}};
}
ProgramKey accumulate() {
    return {"fullscreen.vert", "accumulate.frag", "", {}};
}
ProgramKey tonemap() {
    return {"fullscreen.vert", "tonemap.frag", "", {}};
}
ProgramKey shadowDepth() {
    return {"shadow_depth.vert", "shadow_depth.frag", "", {}};
}

ProgramKey environmentTables(EnvironmentTables pass) {
    static const char* const kDefines[] = {"PASS_CUBE", "PASS_ENERGY", "PASS_ROWS", "PASS_COLUMNS",
                                           "PASS_SAMPLES"};
    return {"", "", "environment_cdf.comp", {kDefines[int(pass)]}};
}

ProgramKey shading(const TechniqueInfo& technique, bool shadowMaps, bool shadowRays, bool glossy) {
    ProgramKey key{"fullscreen.vert", std::string(technique.shader), "", {}};
    if (shadowMaps) key.defines.push_back("SHADOW_MAPS");
    if (shadowRays) key.defines.push_back("SHADOWS");
    if (glossy) key.defines.push_back("GLOSSY");
    return key;
}

}  // namespace programs

std::vector<ProgramKey> allProgramVariants() {
    std::set<ProgramKey> shading;  // techniques may share a shader (restricted-cdf, -raytraced)
    for (const TechniqueInfo& t : techniques()) {
        if (t.shader.empty()) continue;
        for (bool glossy : {false, true}) {
            shading.insert(programs::shading(t, false, false, glossy));
            // A technique that reads shadow maps is planned with them wherever it needs shadows,
            // any other with shadow rays (FramePlan.cpp).
            shading.insert(programs::shading(t, t.shadowMaps, !t.shadowMaps, glossy));
        }
    }
    std::vector<ProgramKey> keys(shading.begin(), shading.end());
    for (ProgramKey key : {programs::gbuffer(), programs::indirect(), programs::resolve(),
                           programs::accumulate(), programs::tonemap(), programs::shadowDepth()})
        keys.push_back(std::move(key));
    for (int pass = 0; pass <= int(programs::EnvironmentTables::Samples); ++pass)
        keys.push_back(programs::environmentTables(programs::EnvironmentTables(pass)));
    return keys;
}

std::vector<ShaderStageSource> allShaderStages(const ShaderLibrary& shaders) {
    std::vector<ShaderStageSource> out;
    for (const ProgramKey& key : allProgramVariants()) {
        for (const std::string& file : {key.vertex, key.fragment, key.compute}) {
            if (file.empty()) continue;
            std::string stage = std::filesystem::path(file).extension().string().substr(1);
            std::string label = key.label();
            if (file == key.vertex) label = file + " for " + label;
            ShaderStageSource s{label, stage, "", {}};
            s.text = shaders.source(key, file, &s.files);
            out.push_back(std::move(s));
        }
    }
    return out;
}

}  // namespace candela
