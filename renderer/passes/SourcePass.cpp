#include "renderer/passes/SourcePass.h"

#include "renderer/passes/EnvironmentPass.h"
#include "renderer/passes/LuminairePass.h"

namespace candela {

namespace {

/// The kinds whose GPU shading needs more than a record and shadow maps. A kind not listed is
/// served by LuminairePass.
struct KindPass {
    std::string_view kind;
    std::unique_ptr<SourcePass> (*make)();
    std::vector<std::string> (*prepasses)(const TechniqueInfo&);
};

const KindPass kKindPasses[] = {
    {"environment", [] { return std::unique_ptr<SourcePass>(std::make_unique<EnvironmentPass>()); },
     &EnvironmentPass::prepassNames},
};

const KindPass* kindPass(std::string_view kind) {
    for (const KindPass& k : kKindPasses)
        if (k.kind == kind) return &k;
    return nullptr;
}

}  // namespace

std::unique_ptr<SourcePass> makeSourcePass(std::string_view kind) {
    if (const KindPass* k = kindPass(kind)) return k->make();
    return std::make_unique<LuminairePass>();
}

std::vector<std::string> sourcePrepasses(const TechniqueInfo& technique) {
    const KindPass* k = kindPass(technique.kind);
    return k ? k->prepasses(technique) : std::vector<std::string>{};
}

}  // namespace candela
