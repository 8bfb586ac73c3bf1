#pragma once
// What a luminaire kind does besides its physics (luminaires/Luminaire.h: LuminaireModel): how its
// scene-file entry is read and written, the record and tables its GPU passes read, the line that
// describes it, the files it was read from, its shadow maps, its body and the placements one
// entry makes. Each kind defines one adapter in its own folder; the registry's table of kinds
// (luminaires/Registry.cpp) holds them, and the functions below dispatch on a luminaire's kind,
// so no code outside a kind's files needs to know its class.

#include <cstddef>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "luminaires/GpuTable.h"
#include "luminaires/Luminaire.h"
#include "util/JsonRead.h"

namespace candela {

struct LuminaireAdapter {
    /// Builds a placed luminaire from its scene-file entry: the model from the kind-specific
    /// fields, and what the kind decides of the placement (a GLDF product's maintenance factor);
    /// name, pose and technique are read by the caller. Null for a kind that is not placed.
    std::unique_ptr<Luminaire> (*parse)(const nlohmann::json& entry, const json::Where& where);
    /// One with default parameters (the editor's "Add"); null for a kind that is not placed.
    std::unique_ptr<Luminaire> (*create)();
    /// Kind-specific fields of the scene-file entry (pose, name, technique are common).
    void (*writeJson)(const LuminaireModel& model, nlohmann::json& out);
    /// Packed std430 record for this kind's GPU passes (layout in shaders/shared/); empty: none.
    std::vector<std::byte> (*gpuData)(const Luminaire& luminaire);
    /// The tables its shaders read from textures, made once per model and shared: the same
    /// object comes back until the model changes. Null function or result: none.
    std::shared_ptr<const GpuTables> (*gpuTables)(const LuminaireModel& model);
    /// One line for `candela info` and the editor.
    std::string (*describe)(const LuminaireModel& model);
    /// The files its data was read from, so commands never write onto them. Null: none.
    std::vector<std::string> (*sourceFiles)(const LuminaireModel& model);
    /// The shadow maps its shading reads for about `count` maps (0: the kind's natural count).
    /// Null: none (a kind that traces shadow rays instead).
    ShadowLights (*shadowLights)(const Luminaire& luminaire, int count);
    /// Its body (L3D housing or luminous box). Null: none.
    LuminaireBody (*body)(const Luminaire& luminaire);
    /// The other luminaires its scene entry makes (a GLDF variant placing several emitters),
    /// with this one's pose, technique and maintenance factor. Null: none.
    std::vector<std::unique_ptr<Luminaire>> (*companions)(const Luminaire& luminaire);
    /// Radiance the viewport shows on the emitting surface, W/(m2 sr). Null: what leaves the
    /// emitter's centre along its aim (exact for Lambertian emitters).
    glm::dvec3 (*displayRadiance)(const Luminaire& luminaire);
};

/// The adapter of a kind (from the registry's table).
const LuminaireAdapter& adapterOf(LuminaireKind kind);

void writeJson(const Luminaire& luminaire, nlohmann::json& out);
std::vector<std::byte> gpuData(const Luminaire& luminaire);
std::shared_ptr<const GpuTables> gpuTables(const Luminaire& luminaire);
std::string describe(const Luminaire& luminaire);
std::vector<std::string> sourceFiles(const Luminaire& luminaire);
ShadowLights shadowLights(const Luminaire& luminaire, int count);
LuminaireBody body(const Luminaire& luminaire);
std::vector<std::unique_ptr<Luminaire>> companions(const Luminaire& luminaire);
glm::dvec3 displayRadiance(const Luminaire& luminaire);

/// A placed luminaire of a new model (a kind's parse and create).
template <class Model>
std::unique_ptr<Luminaire> placed(std::shared_ptr<Model> model) {
    return std::make_unique<Luminaire>(std::shared_ptr<const LuminaireModel>(std::move(model)));
}

}  // namespace candela
