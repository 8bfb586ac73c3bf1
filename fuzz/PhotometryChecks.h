#pragma once
// What the IES, EULUMDAT and TM-33 targets check of every input: the parser loads a valid table or
// throws InputError with a one-line UTF-8 message naming the file; strict mode loads exactly the
// files that load without warnings, with the same table.

#include <optional>

#include "formats/Photometry.h"
#include "fuzz/FuzzSupport.h"
#include "util/Error.h"

namespace candela::fuzz {

/// The invariants Photometry.h promises of a loaded table.
inline void checkTable(const PhotometricData& d) {
    const size_t nv = d.vertical.size(), nh = d.horizontal.size();
    if (nv == 0 || nh == 0 || d.candela.size() != nv * nh) violated("table sizes do not match");
    for (size_t i = 1; i < nv; ++i)
        if (!(d.vertical[i] > d.vertical[i - 1])) violated("vertical angles not ascending");
    for (size_t i = 1; i < nh; ++i)
        if (!(d.horizontal[i] > d.horizontal[i - 1])) violated("horizontal angles not ascending");
    checkFinite(d.vertical, "vertical angles", -90.0, 180.0);
    checkFinite(d.horizontal, "horizontal angles", -180.0, 360.0);
    checkFinite(d.candela, "candela", 0.0, kMaxCandela);
    checkFinite(std::vector<double>{d.fluxFromTable(), d.maxIntensity(), d.declaredFlux()},
                "fluxes", 0.0);
    checkFinite(
        std::vector<double>{d.opening.length, d.opening.width, d.opening.height, d.opening.area()},
        "opening", 0.0, kMaxOpening * kMaxOpening);
    for (const glm::dvec3& w :
         {glm::dvec3(0, 0, 1), glm::dvec3(0.3, -0.4, 0.8), glm::dvec3(1, 0, 0),
          glm::dvec3(0, -1, -1e-9), glm::dvec3(-0.2, 0.1, -0.9)})
        checkFinite(std::vector<double>{d.intensity(w)}, "intensity", 0.0, kMaxCandela);
    for (const std::string& w : d.warnings) checkMessage(w, d.path);
    if (!isValidUtf8(d.name)) violated("luminaire name is not valid UTF-8");
}

/// The photometry formats a target reads.
enum class PhotometryFormat { Ies, Ldt, Tm33 };

inline void checkPhotometry(const uint8_t* data, size_t size, PhotometryFormat format) {
    const std::string path = format == PhotometryFormat::Ldt ? "/nonexistent-candela-fuzz/fuzz.ldt"
                             : format == PhotometryFormat::Ies
                                 ? "/nonexistent-candela-fuzz/fuzz.ies"
                                 : "/nonexistent-candela-fuzz/fuzz.xml";
    const std::string text(reinterpret_cast<const char*>(data), size);
    auto parse = [&](bool strict) {
        PhotometryOptions options{.strict = strict};
        switch (format) {
            case PhotometryFormat::Ldt:
                return parseEulumdat(text, path, options);
            case PhotometryFormat::Ies:
                return parseIes(text, path, options);
            case PhotometryFormat::Tm33:
                break;
        }
        return parseTm33(text, path, options);
    };
    std::optional<PhotometricData> lenient;
    try {
        lenient = parse(false);
    } catch (const InputError& e) {
        checkMessage(e.what(), path);
    }
    if (lenient) checkTable(*lenient);
    try {
        PhotometricData strict = parse(true);
        if (!lenient) violated("strict mode loads a file that lenient mode refuses");
        if (!lenient->warnings.empty())
            violated("strict mode loads a file with warnings: " + lenient->warnings[0]);
        if (strict.candela != lenient->candela) violated("strict and lenient tables differ");
    } catch (const InputError& e) {
        checkMessage(e.what(), path);
        if (lenient && lenient->warnings.empty())
            violated("strict mode refuses a file without warnings");
    }
}

}  // namespace candela::fuzz
