#include "formats/Tm25RayFile.h"

#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>

#include "util/Error.h"
#include "util/FileInput.h"

namespace candela {

namespace {

namespace fs = std::filesystem;

constexpr uint64_t kPrefixBytes = 36288;  // header 256 + flags 32 + description 9 x 4000
constexpr uint64_t kFlagsOffset = 256;
constexpr uint64_t kDescriptionOffset = 288;
constexpr uint64_t kDescriptionUnits = 1000;  // UTF-32 code units per description field
constexpr uint64_t kLabelUnits = 128;         // UTF-32 code units per additional-item label
constexpr uint64_t kSpectralAlign = 32;       // the spectral block is padded to this, bytes
constexpr int kVersion = 2013;
constexpr uint64_t kRaysPerChunk = 1 << 16;

const char* const kDescriptionNames[9] = {"name of the light source",
                                          "manufacturer",
                                          "creator of the source model",
                                          "creator of the ray file",
                                          "measurement equipment or simulation software",
                                          "camera or detector",
                                          "operating conditions",
                                          "additional information",
                                          "data reference"};

const char* const kFlagNames[8] = {"position",      "direction", "radiant flux", "wavelength",
                                   "luminous flux", "Stokes",    "tristimulus",  "spectrum index"};

uint32_t le32(const unsigned char* p) {
    return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}
int32_t i32(const unsigned char* p) {
    return std::bit_cast<int32_t>(le32(p));
}
/// Bit copy: a signalling NaN stays a NaN and never traps (no arithmetic on it here).
float f32(const unsigned char* p) {
    return std::bit_cast<float>(le32(p));
}
uint64_t le64(const unsigned char* p) {
    return uint64_t(le32(p)) | uint64_t(le32(p + 4)) << 32;
}

std::string num(double v) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}

void appendUtf8(std::string& out, uint32_t c) {
    if (c > 0x10FFFF || (c >= 0xD800 && c <= 0xDFFF)) c = 0xFFFD;  // not a code point
    if (c < 0x80) {
        out += char(c);
    } else if (c < 0x800) {
        out += char(0xC0 | (c >> 6));
        out += char(0x80 | (c & 0x3F));
    } else if (c < 0x10000) {
        out += char(0xE0 | (c >> 12));
        out += char(0x80 | ((c >> 6) & 0x3F));
        out += char(0x80 | (c & 0x3F));
    } else {
        out += char(0xF0 | (c >> 18));
        out += char(0x80 | ((c >> 12) & 0x3F));
        out += char(0x80 | ((c >> 6) & 0x3F));
        out += char(0x80 | (c & 0x3F));
    }
}

/// UTF-32LE units up to the first zero unit or the end of the field, as UTF-8. Invalid code
/// points become U+FFFD: the text is descriptive and never worth rejecting a file for.
std::string utf32(const unsigned char* p, uint64_t units) {
    std::string out;
    for (uint64_t i = 0; i < units; ++i) {
        uint32_t c = le32(p + 4 * i);
        if (c == 0) break;
        appendUtf8(out, c);
    }
    return out;
}

/// The open file with bounds-checked reads; every failure names the file.
class Source {
  public:
    explicit Source(const fs::path& file) : mName(file.string()) {
        // A regular file only (a FIFO would block the open); streamed, so no size limit here.
        checkInputFile(mName, "TM-25 ray", kStreamed);
        mIn.open(file, std::ios::binary);
        if (!mIn) fail("cannot open TM-25 ray file");
        mIn.seekg(0, std::ios::end);
        std::streamoff end = mIn.tellg();
        if (end < 0) fail("cannot read TM-25 ray file");
        mSize = uint64_t(end);
    }
    [[noreturn]] void fail(const std::string& what) const { throw InputError(mName + ": " + what); }
    uint64_t size() const { return mSize; }
    /// Reads n bytes at offset; `what` names the block for the truncation message.
    void read(uint64_t offset, uint64_t n, unsigned char* out, const char* what) {
        if (offset > mSize || n > mSize - offset)
            fail(std::string("truncated: the ") + what + " needs bytes " + std::to_string(offset) +
                 ".." + std::to_string(offset + n) + " but the file has " + std::to_string(mSize));
        mIn.clear();
        mIn.seekg(std::streamoff(offset));
        mIn.read(reinterpret_cast<char*>(out), std::streamsize(n));
        if (!mIn) fail(std::string("read error in the ") + what);
    }

  private:
    std::string mName;
    std::ifstream mIn;
    uint64_t mSize = 0;
};

void checkMagic(Source& src) {
    unsigned char magic[8] = {};
    if (src.size() < 4)
        src.fail("truncated: " + std::to_string(src.size()) +
                 " bytes, not even the 4-byte \"TM25\" file type");
    src.read(0, 4, magic, "file type");
    if (std::memcmp(magic, "TM25", 4) != 0) {
        std::string shown;
        for (int i = 0; i < 4; ++i)
            shown += (magic[i] >= 32 && magic[i] < 127) ? char(magic[i]) : '.';
        std::string hint =
            std::memcmp(magic, "LTRF", 4) == 0 ? " (a LightTools binary ray file?)" : "";
        src.fail("not a TM-25 ray file: it starts with \"" + shown + "\"" + hint +
                 ", expected the file type \"TM25\"");
    }
    if (src.size() >= 8) {
        src.read(4, 4, magic + 4, "version");
        int version = i32(magic + 4);
        if (version != kVersion)
            src.fail("unsupported TM-25 version " + std::to_string(version) +
                     " (offset 4), expected " + std::to_string(kVersion));
    }
    if (src.size() < kPrefixBytes)
        src.fail("truncated: " + std::to_string(src.size()) + " bytes, shorter than the " +
                 std::to_string(kPrefixBytes) + "-byte fixed part of a TM-25 file");
}

void readFixedFields(Source& src, const unsigned char* b, Tm25Header& h,
                     std::vector<std::string>& warnings) {
    h.version = i32(b + 4);
    h.creationMethod = i32(b + 8);
    if (h.creationMethod != 0 && h.creationMethod != 1)
        warnings.push_back("creation method " + std::to_string(h.creationMethod) +
                           " is neither 0 (simulation) nor 1 (measurement)");
    h.luminousFlux = f32(b + 12);
    h.radiantFlux = f32(b + 16);
    auto checkTotal = [&](double v, const char* name, int offset) {
        if (!std::isnan(v) && (v < 0.0 || std::isinf(v)))
            src.fail(std::string("total ") + name + " (offset " + std::to_string(offset) +
                     ") must be >= 0 or NaN (not given), got " + num(v));
    };
    checkTotal(h.luminousFlux, "luminous flux", 12);
    checkTotal(h.radiantFlux, "radiant flux", 16);
    h.rayCount = le64(b + 20);  // unaligned on purpose (TM25.md Sec. 1)
    for (int i = 0; i < 28 && b[28 + i] != 0; ++i) h.dateTime += char(b[28 + i]);
    h.startPosition = i32(b + 56);
    if (h.startPosition < 0 || h.startPosition > 7)
        warnings.push_back("ray start position code " + std::to_string(h.startPosition) +
                           " is outside 0..7");
    h.spectralId = i32(b + 60);
    h.wavelength = f32(b + 64);
    h.wavelengthMin = f32(b + 68);
    h.wavelengthMax = f32(b + 72);
    h.spectralTableCount = i32(b + 76);
    h.additionalItemCount = i32(b + 80);
    h.additionalTextBytes = i32(b + 84);
    if (h.rayCount == 0) src.fail("the header declares 0 rays (offset 20)");
    if (h.spectralId < 0 || h.spectralId > 4)
        src.fail("spectral data identifier " + std::to_string(h.spectralId) +
                 " (offset 60) must be 0..4");
    if (h.spectralTableCount < 0)
        src.fail("number of spectral tables " + std::to_string(h.spectralTableCount) +
                 " (offset 76) is negative");
    if (h.additionalItemCount < 0)
        src.fail("number of additional per-ray items " + std::to_string(h.additionalItemCount) +
                 " (offset 80) is negative");
    if (h.additionalTextBytes < 0)
        src.fail("additional text size " + std::to_string(h.additionalTextBytes) +
                 " (offset 84) is negative");
    if (h.additionalTextBytes % 32 != 0)
        warnings.push_back("additional text size " + std::to_string(h.additionalTextBytes) +
                           " is not a multiple of 32 bytes (the reference reader requires it)");
}

void readFlags(Source& src, const unsigned char* b, Tm25Header& h) {
    bool* fields[8] = {&h.flags.position,    &h.flags.direction,    &h.flags.radiantFlux,
                       &h.flags.wavelength,  &h.flags.luminousFlux, &h.flags.stokes,
                       &h.flags.tristimulus, &h.flags.spectrumIndex};
    for (int i = 0; i < 8; ++i) {
        int32_t v = i32(b + kFlagsOffset + 4 * i);
        if (v != 0 && v != 1)
            src.fail(std::string("known-data flag \"") + kFlagNames[i] + "\" (offset " +
                     std::to_string(kFlagsOffset + 4 * i) + ") must be 0 or 1, got " +
                     std::to_string(v));
        *fields[i] = v == 1;
    }
}

/// The consistency rules of TM25.md Sec. 4 and the spectral identifier's requirements (Sec. 3).
void checkConsistency(Source& src, const Tm25Header& h, std::vector<std::string>& warnings) {
    const Tm25Flags& f = h.flags;
    std::string id = "spectral identifier " + std::to_string(h.spectralId);
    if (!f.position) src.fail("the position flag (offset 256) must be 1: rays need start points");
    if (!f.direction) src.fail("the direction flag (offset 260) must be 1: rays need directions");
    if (!f.radiantFlux && !f.luminousFlux)
        src.fail(
            "neither the radiant flux flag nor the luminous flux flag is set: rays carry no flux");
    if (f.stokes && !f.radiantFlux) src.fail("the Stokes flag requires the radiant flux flag");
    if (f.tristimulus && !f.luminousFlux)
        src.fail("the tristimulus flag requires the luminous flux flag (Y is the luminous flux)");
    if (f.tristimulus && h.spectralId != 0)
        src.fail("the tristimulus flag requires spectral identifier 0, got " +
                 std::to_string(h.spectralId));
    if (f.spectrumIndex != (h.spectralId == 4))
        src.fail(f.spectrumIndex ? "the spectrum index flag is set but the " + id + " is not 4"
                                 : "spectral identifier 4 requires the spectrum index flag");
    if (h.spectralId == 2 && !f.wavelength)
        src.fail("spectral identifier 2 (a wavelength per ray) requires the wavelength flag");
    if ((h.spectralId == 2 || h.spectralId == 4) && (!f.radiantFlux || f.luminousFlux))
        src.fail(id + " requires the radiant flux flag set and the luminous flux flag clear");
    if (h.spectralId == 1 && !(h.wavelength > 0.0 && std::isfinite(h.wavelength)))
        src.fail("spectral identifier 1 requires a positive single wavelength (offset 64), got " +
                 num(h.wavelength));
    if ((h.spectralId == 3 || h.spectralId == 4) && h.spectralTableCount < 1)
        src.fail(id + " requires at least one spectral table (offset 76), got " +
                 std::to_string(h.spectralTableCount));
    if (h.spectralId >= 2 && !(h.wavelengthMin > 0.0 && h.wavelengthMax >= h.wavelengthMin))
        warnings.push_back("wavelength range [" + num(h.wavelengthMin) + ", " +
                           num(h.wavelengthMax) + "] nm is not a positive range (expected for " +
                           id + ")");
}

/// Spectral tables, labels and text; returns the offset of the first ray record.
uint64_t readVariableBlocks(Source& src, Tm25Header& h) {
    uint64_t at = kPrefixBytes;
    unsigned char word[8];
    for (int j = 0; j < h.spectralTableCount; ++j) {
        std::string where = "spectral table " + std::to_string(j + 1);
        src.read(at, 4, word, "spectral tables");
        int32_t n = i32(word);
        if (n <= 0)
            src.fail(where + " (offset " + std::to_string(at) + ") has " + std::to_string(n) +
                     " entries, expected at least 1");
        if (uint64_t(n) * 8 > src.size())
            src.fail("truncated: " + where + " declares " + std::to_string(n) + " entries");
        std::vector<unsigned char> pairs(size_t(8) * size_t(n));
        src.read(at + 4, pairs.size(), pairs.data(), "spectral tables");
        Tm25Spectrum spectrum;
        spectrum.wavelength.resize(size_t(n));
        spectrum.weight.resize(size_t(n));
        for (int k = 0; k < n; ++k) {
            float lambda = f32(&pairs[8 * size_t(k)]), weight = f32(&pairs[8 * size_t(k) + 4]);
            if (!(lambda > 0.0f) || !std::isfinite(lambda) || !(weight >= 0.0f) ||
                !std::isfinite(weight))
                src.fail(where + " entry " + std::to_string(k + 1) + ": wavelength " + num(lambda) +
                         " nm and weight " + num(weight) +
                         ", expected a positive wavelength and a "
                         "weight >= 0");
            spectrum.wavelength[size_t(k)] = lambda;
            spectrum.weight[size_t(k)] = weight;
        }
        h.spectra.push_back(std::move(spectrum));
        at += 4 + pairs.size();
    }
    // Zero padding of the whole block to a multiple of 32 bytes (none when there is no table).
    uint64_t block = at - kPrefixBytes;
    at = kPrefixBytes + (block + kSpectralAlign - 1) / kSpectralAlign * kSpectralAlign;

    uint64_t labelBytes = kLabelUnits * 4;
    if (uint64_t(h.additionalItemCount) > src.size() / labelBytes)
        src.fail("truncated: " + std::to_string(h.additionalItemCount) +
                 " additional-item labels (offset 80) cannot fit in the file");
    std::vector<unsigned char> buf(labelBytes);
    for (int a = 0; a < h.additionalItemCount; ++a) {
        src.read(at, labelBytes, buf.data(), "additional-item labels");
        h.additionalLabels.push_back(utf32(buf.data(), kLabelUnits));
        at += labelBytes;
    }
    if (uint64_t(h.additionalTextBytes) > src.size() - std::min(at, src.size()))
        src.fail("truncated: the additional text (" + std::to_string(h.additionalTextBytes) +
                 " bytes, offset 84) does not fit in the file");
    buf.resize(size_t(h.additionalTextBytes));
    src.read(at, buf.size(), buf.data(), "additional text");
    h.additionalText = utf32(buf.data(), buf.size() / 4);
    at += buf.size();
    return at;
}

/// Picks the Stokes layout (6 items, else 3) whose record size makes the file size exact.
void checkFileSize(Source& src, Tm25Header& h) {
    const Tm25Flags& f = h.flags;
    int base = 6 + f.radiantFlux + f.wavelength + f.luminousFlux + 2 * f.tristimulus +
               f.spectrumIndex + h.additionalItemCount;
    std::vector<int> layouts = f.stokes ? std::vector<int>{6, 3} : std::vector<int>{0};
    std::string expected;
    for (int stokes : layouts) {
        uint64_t record = 4 * uint64_t(base + stokes);
        uint64_t limit = (std::numeric_limits<uint64_t>::max() - h.rayDataOffset) / record;
        if (h.rayCount > limit)
            src.fail("the ray count " + std::to_string(h.rayCount) +
                     " (offset 20) is impossibly large");
        uint64_t want = h.rayDataOffset + h.rayCount * record;
        if (want == src.size()) {
            h.stokesItems = stokes;
            h.itemCount = base + stokes;
            return;
        }
        expected += (expected.empty() ? "" : " or ") + std::to_string(want);
    }
    src.fail("file size " + std::to_string(src.size()) +
             " bytes does not match the header, which "
             "implies " +
             expected + " (ray data at offset " + std::to_string(h.rayDataOffset) + " + " +
             std::to_string(h.rayCount) + " rays x " + std::to_string(base) +
             (f.stokes ? "+Stokes" : "") +
             " items x 4 bytes): truncated, or a wrong ray count or flag");
}

Tm25Header readHeader(Source& src, std::vector<std::string>& warnings) {
    checkMagic(src);
    std::vector<unsigned char> prefix(kPrefixBytes);
    src.read(0, kPrefixBytes, prefix.data(), "fixed header");
    Tm25Header h;
    h.fileSize = src.size();
    readFixedFields(src, prefix.data(), h, warnings);
    readFlags(src, prefix.data(), h);
    checkConsistency(src, h, warnings);
    for (int i = 0; i < 9; ++i)
        h.description[size_t(i)] =
            utf32(prefix.data() + kDescriptionOffset + 4 * kDescriptionUnits * uint64_t(i),
                  kDescriptionUnits);
    h.rayDataOffset = readVariableBlocks(src, h);
    checkFileSize(src, h);
    return h;
}

std::vector<std::string> itemNames(const Tm25Header& h) {
    std::vector<std::string> names = {"x", "y", "z", "kx", "ky", "kz"};
    const Tm25Flags& f = h.flags;
    if (f.radiantFlux) names.push_back("radiant flux");
    if (f.wavelength) names.push_back("wavelength");
    if (f.luminousFlux) names.push_back("luminous flux");
    const char* stokes[6] = {"S1", "S2", "S3", "PolX", "PolY", "PolZ"};
    for (int i = 0; i < h.stokesItems; ++i) names.push_back(stokes[i]);
    if (f.tristimulus) {
        names.push_back("X");
        names.push_back("Z");
    }
    if (f.spectrumIndex) names.push_back("spectrum index");
    for (int a = 0; a < h.additionalItemCount; ++a)
        names.push_back("additional item " + std::to_string(a + 1) + " (\"" +
                        h.additionalLabels[size_t(a)] + "\")");
    return names;
}

/// Decodes and checks one record of h.itemCount floats.
void parseRay(Source& src, const Tm25Header& h, const std::vector<std::string>& names,
              const float* v, uint64_t index, Tm25Ray& ray, uint64_t& renormalised) {
    auto bad = [&](const std::string& what) {
        src.fail("ray " + std::to_string(index + 1) + " of " + std::to_string(h.rayCount) + ": " +
                 what);
    };
    for (int i = 0; i < h.itemCount; ++i)
        if (!std::isfinite(v[i]))
            bad("item \"" + names[size_t(i)] + "\" is " + (std::isnan(v[i]) ? "NaN" : "infinite"));
    constexpr double kMmToM = 1e-3;  // positions are stored in millimetres
    ray.position = glm::dvec3(v[0], v[1], v[2]) * kMmToM;
    glm::dvec3 k(v[3], v[4], v[5]);
    double k2 = glm::dot(k, k);
    if (k2 < 1e-12) bad("zero direction (" + num(k.x) + ", " + num(k.y) + ", " + num(k.z) + ")");
    // The reference reader's tolerance for a unit vector; beyond it, renormalise and count.
    if (std::abs(k2 - 1.0) > 10.0 * FLT_EPSILON) ++renormalised;
    ray.direction = k / std::sqrt(k2);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    int at = 6;
    const Tm25Flags& f = h.flags;
    ray.radiantFlux = f.radiantFlux ? v[at++] : nan;
    ray.wavelength = f.wavelength ? v[at++] : std::numeric_limits<float>::quiet_NaN();
    ray.luminousFlux = f.luminousFlux ? v[at++] : nan;
    if (ray.radiantFlux < 0.0) bad("negative radiant flux " + num(ray.radiantFlux) + " W");
    if (ray.luminousFlux < 0.0) bad("negative luminous flux " + num(ray.luminousFlux) + " lm");
    if (f.wavelength && !(ray.wavelength > 0.0f))
        bad("wavelength " + num(ray.wavelength) + " nm is not positive");
    if (h.stokesItems > 0) {
        double s1 = v[at], s2 = v[at + 1], s3 = v[at + 2];
        // Normalised Stokes parameters: each in [-1, 1] and a degree of polarisation <= 1, with a
        // float rounding allowance of 1e-5.
        if (std::abs(s1) > 1.0 || std::abs(s2) > 1.0 || std::abs(s3) > 1.0 ||
            s1 * s1 + s2 * s2 + s3 * s3 > 1.0 + 1e-5)
            bad("Stokes parameters (" + num(s1) + ", " + num(s2) + ", " + num(s3) +
                ") are not normalised (each in [-1, 1], S1^2 + S2^2 + S3^2 <= 1)");
        at += h.stokesItems;
    }
    if (f.tristimulus) at += 2;
    ray.spectrumIndex = 0;
    if (f.spectrumIndex) {
        float idx = v[at++];
        if (idx != std::floor(idx) || idx < 1.0f || idx > float(h.spectralTableCount))
            bad("spectrum index " + num(idx) + " is not a table number in 1.." +
                std::to_string(h.spectralTableCount));
        ray.spectrumIndex = int(idx);
    }
}

}  // namespace

const char* tm25DescriptionName(int i) {
    return (i >= 0 && i < 9) ? kDescriptionNames[i] : "?";
}

double Tm25RayFile::rayLuminousFlux() const {
    if (!header.flags.luminousFlux) return 0.0;
    double sum = 0.0;
    for (const Tm25Ray& r : rays) sum += r.luminousFlux;
    return sum;
}

double Tm25RayFile::rayRadiantFlux() const {
    if (!header.flags.radiantFlux) return 0.0;
    double sum = 0.0;
    for (const Tm25Ray& r : rays) sum += r.radiantFlux;
    return sum;
}

Tm25Header readTm25Header(const fs::path& file) {
    Source src(file);
    std::vector<std::string> warnings;
    return readHeader(src, warnings);
}

Tm25RayFile readTm25(const fs::path& file, const Tm25Progress& progress) {
    Source src(file);
    Tm25RayFile out;
    out.header = readHeader(src, out.warnings);
    const Tm25Header& h = out.header;
    std::vector<std::string> names = itemNames(h);
    out.rays.resize(size_t(h.rayCount));
    uint64_t record = 4 * uint64_t(h.itemCount);
    std::vector<unsigned char> bytes;
    std::vector<float> values(size_t(h.itemCount));
    for (uint64_t first = 0; first < h.rayCount; first += kRaysPerChunk) {
        uint64_t n = std::min(kRaysPerChunk, h.rayCount - first);
        bytes.resize(size_t(n * record));
        src.read(h.rayDataOffset + first * record, bytes.size(), bytes.data(), "ray data");
        for (uint64_t r = 0; r < n; ++r) {
            const unsigned char* p = bytes.data() + r * record;
            for (int i = 0; i < h.itemCount; ++i) values[size_t(i)] = f32(p + 4 * i);
            parseRay(src, h, names, values.data(), first + r, out.rays[size_t(first + r)],
                     out.renormalisedDirections);
        }
        if (progress) progress(first + n, h.rayCount);
    }
    if (out.renormalisedDirections > 0)
        out.warnings.push_back(std::to_string(out.renormalisedDirections) +
                               " ray directions were not unit vectors and were renormalised");
    return out;
}

}  // namespace candela
