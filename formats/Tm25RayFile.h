#pragma once
// Reader of IES TM-25-13 binary ray files (`.TM25RAY`), as documented in
// shared/formats/TM25.md: little-endian, a fixed 36 288-byte prefix (header, known-data flags,
// nine UTF-32 description strings), spectral tables padded to 32 bytes, additional-item labels
// and text, then packed f32 ray records. Every malformed input throws InputError naming the file
// and what was wrong; nothing is trusted before it is bounds-checked.

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace candela {

/// Known-data flags (4.7.2); each is 0 or 1 in the file.
struct Tm25Flags {
    bool position = false;       ///< x y z (must be set).
    bool direction = false;      ///< kx ky kz (must be set).
    bool radiantFlux = false;    ///< Per-ray radiant flux, W.
    bool wavelength = false;     ///< Per-ray wavelength, nm.
    bool luminousFlux = false;   ///< Per-ray luminous flux, lm.
    bool stokes = false;         ///< S1 S2 S3 (+ PolX PolY PolZ in the reference layout).
    bool tristimulus = false;    ///< X Z (Y is the luminous flux).
    bool spectrumIndex = false;  ///< 1-based index into the spectral tables.
};

/// One spectral table (4.7.4): pairs of wavelength and relative weight.
struct Tm25Spectrum {
    std::vector<float> wavelength;  ///< nm, > 0.
    std::vector<float> weight;      ///< Relative spectral weight, >= 0 (no unit).
};

/// Everything before the ray records.
struct Tm25Header {
    int version = 0;            ///< Always 2013 once read.
    int creationMethod = 0;     ///< 0 simulation, 1 measurement (other values give a warning).
    double luminousFlux = 0.0;  ///< Total luminous flux Phi_v from the header, lm; NaN = not given.
    double radiantFlux = 0.0;   ///< Total radiant flux Phi from the header, W; NaN = not given.
    uint64_t rayCount = 0;
    std::string dateTime;        ///< As stored (ISO 8601 intended), may be empty.
    int startPosition = 0;       ///< Ray start position code (0 = unknown).
    int spectralId = 0;          ///< 0..4 (TM25.md Sec. 3).
    double wavelength = 0.0;     ///< Single wavelength for identifier 1, nm (NaN or 0 when unused).
    double wavelengthMin = 0.0;  ///< nm.
    double wavelengthMax = 0.0;  ///< nm.
    int spectralTableCount = 0;
    int additionalItemCount = 0;
    int additionalTextBytes = 0;
    Tm25Flags flags;
    int stokesItems = 0;  ///< 6 (reference layout) or 3 (Boxler's), whichever fits the file size.
    int itemCount = 0;    ///< f32 items per ray record.
    uint64_t rayDataOffset = 0;              ///< Bytes from the start of the file.
    uint64_t fileSize = 0;                   ///< Bytes.
    std::array<std::string, 9> description;  ///< 4.7.3.1 .. 4.7.3.9, decoded to UTF-8.
    std::vector<Tm25Spectrum> spectra;
    std::vector<std::string> additionalLabels;  ///< UTF-8.
    std::string additionalText;                 ///< UTF-8.
};

/// Name of description field i (0..8), e.g. "name of the light source".
const char* tm25DescriptionName(int i);

struct Tm25Ray {
    glm::dvec3 position{0.0};   ///< Start point, metres (the file stores millimetres).
    glm::dvec3 direction{0.0};  ///< Unit direction of travel.
    double radiantFlux = 0.0;   ///< W; NaN when the file has no radiant flux item.
    double luminousFlux = 0.0;  ///< lm; NaN when the file has no luminous flux item.
    float wavelength = 0.0f;    ///< nm; NaN when the file has no wavelength item.
    int spectrumIndex = 0;      ///< 1-based spectral table, 0 when the file has none.
};

struct Tm25RayFile {
    Tm25Header header;
    std::vector<Tm25Ray> rays;
    /// Things a reader should tell the user but that do not make the file unusable (odd creation
    /// method, renormalised directions, ...).
    std::vector<std::string> warnings;
    uint64_t renormalisedDirections = 0;  ///< Rays whose |k|^2 was off by more than 10 FLT_EPSILON.

    double rayLuminousFlux() const;  ///< Sum over the rays, lm (0 without the item).
    double rayRadiantFlux() const;   ///< Sum over the rays, W (0 without the item).
};

/// Called while rays are read: (rays read so far, rays in the file).
using Tm25Progress = std::function<void(uint64_t done, uint64_t total)>;

/// Reads and checks the header and the blocks before the rays, and the file-size rule.
Tm25Header readTm25Header(const std::filesystem::path& file);
/// Reads the whole file. Throws InputError naming the file on any malformed content.
Tm25RayFile readTm25(const std::filesystem::path& file, const Tm25Progress& progress = {});

}  // namespace candela
