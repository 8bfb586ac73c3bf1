#include "renderer/passes/SourcePass.h"

#include "renderer/passes/EnvironmentPass.h"
#include "renderer/passes/LuminairePass.h"

namespace candela {

namespace {

/// The kinds whose GPU shading needs more than a record and shadow maps. A kind not listed is
/// served by LuminairePass.
struct KindPass {
    LuminaireKind kind;
    std::unique_ptr<SourcePass> (*make)();
    std::vector<std::string> (*prepasses)(const TechniqueInfo&);
};

const KindPass kKindPasses[] = {
    {LuminaireKind::Environment,
     [] { return std::unique_ptr<SourcePass>(std::make_unique<EnvironmentPass>()); },
     &EnvironmentPass::prepassNames},
};

const KindPass* kindPass(LuminaireKind kind) {
    for (const KindPass& k : kKindPasses)
        if (k.kind == kind) return &k;
    return nullptr;
}

}  // namespace

std::unique_ptr<SourcePass> makeSourcePass(LuminaireKind kind) {
    if (const KindPass* k = kindPass(kind)) return k->make();
    return std::make_unique<LuminairePass>();
}

std::vector<std::string> sourcePrepasses(const TechniqueInfo& technique) {
    const KindPass* k = kindPass(technique.kind);
    return k ? k->prepasses(technique) : std::vector<std::string>{};
}

}  // namespace candela
