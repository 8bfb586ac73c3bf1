#include "renderer/RenderSettings.h"

namespace candela {

std::string techniqueList(const RenderSettings& settings) {
    if (settings.environmentTechnique.empty()) return settings.techniqueOverride;
    std::string list = "environment=" + settings.environmentTechnique;
    return settings.techniqueOverride.empty() ? list : list + "," + settings.techniqueOverride;
}

}  // namespace candela
