#pragma once
// Which unit system a light source's numbers are in, and the one a scene reports in.
//
// A luminaire (or the environment) emits either radiometric quantities (W, W/sr, W/(m2 sr), so
// irradiance is W/m2) or photometric ones (lm, cd, cd/m2, so illuminance is lx). A scene whose
// sources all share one system reports in it. A mixed scene converts its radiometric sources at
// the stated luminous efficacy K_m = 683 lm/W (the definition of the candela at 555 nm; exact
// only for light of that wavelength), reports lx and says so beside every result: quantities of
// different units are never added silently.

#include <string>

namespace candela {

enum class Quantities { Radiometric, Photometric };

/// Luminous efficacy used to convert a mixed scene's radiometric sources, lm/W.
constexpr double kLuminousEfficacy = 683.0;

struct UnitSystem {
    bool photometric = false;  ///< Results in lx and cd/m2, else W/m2 and W/(m2 sr).
    bool converted = false;    ///< Mixed scene: radiometric sources multiplied by 683 lm/W.

    /// Irradiance or illuminance unit: "lx" or "W/m2".
    const char* irradiance() const { return photometric ? "lx" : "W/m2"; }
    /// Radiance or luminance unit: "cd/m2" or "W/(m2 sr)".
    const char* radiance() const { return photometric ? "cd/m2" : "W/(m2 sr)"; }
    /// Factor applied to a source emitting in `q` (683 for a radiometric one in a mixed scene).
    double scale(Quantities q) const {
        return converted && q == Quantities::Radiometric ? kLuminousEfficacy : 1.0;
    }
    /// "" or the conversion the results include, for printing beside them.
    std::string note() const {
        return converted ? "radiometric sources converted at 683 lm/W" : "";
    }
    /// The irradiance unit with the conversion note in parentheses when there is one.
    std::string irradianceLabel() const {
        return converted ? std::string(irradiance()) + " (" + note() + ")" : irradiance();
    }
};

/// The system a scene with these kinds of sources reports in (an empty scene: radiometric).
inline UnitSystem unitSystemOf(bool anyPhotometric, bool anyRadiometric) {
    UnitSystem u;
    u.photometric = anyPhotometric;
    u.converted = anyPhotometric && anyRadiometric;
    return u;
}

/// Flux unit of a source: "lm" or "W"; intensity "cd" or "W/sr"; radiance "cd/m2" or "W/(m2 sr)".
inline const char* fluxUnit(Quantities q) {
    return q == Quantities::Photometric ? "lm" : "W";
}
inline const char* intensityUnit(Quantities q) {
    return q == Quantities::Photometric ? "cd" : "W/sr";
}
inline const char* radianceUnit(Quantities q) {
    return q == Quantities::Photometric ? "cd/m2" : "W/(m2 sr)";
}

}  // namespace candela
