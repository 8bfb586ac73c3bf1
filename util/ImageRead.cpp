#include "util/ImageRead.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <vector>

#include "util/Error.h"
#include "util/FileInput.h"

namespace candela {

namespace {

/// Reads a NUL-terminated name of at most 255 characters; false at the end of the file or for a
/// longer name (OpenEXR then reports the file itself).
bool readName(std::istream& in, std::string& name) {
    name.clear();
    for (char c; in.get(c);) {
        if (c == '\0') return true;
        if (name.size() == 255) return false;
        name += c;
    }
    return false;
}

/// `text` with each character that does not print replaced by '?', for a message.
std::string printable(const std::string& text) {
    std::string shown;
    for (char c : text) shown += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
    return shown;
}

int32_t le32(const unsigned char* b) {
    return int32_t(uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 |
                   uint32_t(b[3]) << 24);
}

/// Bytes OpenEXR 3.1 reads for a value of each fixed-size attribute type it knows, whatever size
/// the attribute declares (OpenEXR File Layout, "Predefined Attribute Types"); 0 for the others.
int64_t fixedValueSize(const std::string& type) {
    static const std::map<std::string, int64_t> sizes = {{"box2i", 16},
                                                         {"box2f", 16},
                                                         {"chromaticities", 32},
                                                         {"compression", 1},
                                                         {"deepImageState", 1},
                                                         {"double", 8},
                                                         {"envmap", 1},
                                                         {"float", 4},
                                                         {"int", 4},
                                                         {"keycode", 28},
                                                         {"lineOrder", 1},
                                                         {"m33d", 72},
                                                         {"m33f", 36},
                                                         {"m44d", 128},
                                                         {"m44f", 64},
                                                         {"rational", 8},
                                                         {"tiledesc", 9},
                                                         {"timecode", 8},
                                                         {"v2d", 16},
                                                         {"v2f", 8},
                                                         {"v2i", 8},
                                                         {"v3d", 24},
                                                         {"v3f", 12},
                                                         {"v3i", 12}};
    auto it = sizes.find(type);
    return it == sizes.end() ? 0 : it->second;
}

/// Why OpenEXR 3.1 would read a value of `type` other than as the `bytes` that `value` holds
/// (empty when it reads exactly those). It reads a fixed-size type's own size, a channel list up
/// to its empty name and a preview as large as its width and height say, not the declared size:
/// a file whose declarations disagree desynchronises it, and what it then reads as the next
/// attribute is no longer what this walk checked.
std::string valueMismatch(const std::string& type, const std::string& value) {
    const int64_t bytes = int64_t(value.size());
    const auto* v = reinterpret_cast<const unsigned char*>(value.data());
    if (int64_t fixed = fixedValueSize(type))
        return fixed == bytes ? std::string()
                              : "declares " + std::to_string(bytes) + " bytes where a " + type +
                                    " holds " + std::to_string(fixed);
    if (type == "chlist") {  // per channel a NUL-terminated name and 16 bytes; an empty name ends
        size_t at = 0;
        while (at < value.size() && value[at] != '\0') {
            size_t nul = value.find('\0', at);
            if (nul == std::string::npos) break;
            at = nul + 1 + 16;
        }
        return at + 1 == value.size() && value[at] == '\0'
                   ? std::string()
                   : "is a channel list that does not end at its " + std::to_string(bytes) +
                         " bytes";
    }
    if (type == "preview") {  // width and height (unsigned 32-bit), then 4 bytes a pixel
        if (bytes < 8) return "is a preview of " + std::to_string(bytes) + " bytes";
        const uint64_t w = uint32_t(le32(v)), h = uint32_t(le32(v + 4));
        return w * h == uint64_t(bytes - 8) / 4 && (bytes - 8) % 4 == 0
                   ? std::string()
                   : "is a " + std::to_string(w) + "x" + std::to_string(h) + " preview in " +
                         std::to_string(bytes) + " bytes";
    }
    if (type == "stringvector") {  // per string a 32-bit length and its characters
        int64_t at = 0;
        while (at + 4 <= bytes) {
            int64_t n = le32(v + at);
            if (n < 0 || n > bytes - at - 4) break;
            at += 4 + n;
        }
        return at == bytes ? std::string()
                           : "is a string list that does not end at its " + std::to_string(bytes) +
                                 " bytes";
    }
    if (type == "floatvector" && bytes % 4 != 0)
        return "declares " + std::to_string(bytes) + " bytes for 4-byte floats";
    return {};  // string, idmanifest and unknown types: OpenEXR reads the declared bytes
}

/// OpenEXR 3.1 allocates (and clears) the size a header attribute declares before reading it, and
/// tables as long as the data window is high, so a 100-byte file can make it allocate gigabytes
/// or spend half a minute (fuzzing found both). Walks the header(s) as the file layout specifies
/// ("OpenEXR File Layout": magic number, version field whose bit 12 marks multi-part files; per
/// attribute a name and a type name, NUL-terminated, an int32 size and the value; an empty name
/// ends a header, an empty header ends a multi-part file's list) and refuses an attribute larger
/// than what is left of the file, one whose value OpenEXR would read as a different number of
/// bytes (valueMismatch), and a data window (box2i) wider or higher than `maxSide`.
/// Anything else malformed is left to OpenEXR.
void checkExrHeader(const std::string& path, const std::string& context, int maxSide) {
    std::ifstream in(path, std::ios::binary);
    unsigned char head[8];
    if (!in.read(reinterpret_cast<char*>(head), 8) || head[0] != 0x76 || head[1] != 0x2f ||
        head[2] != 0x31 || head[3] != 0x01)
        return;
    const bool multiPart = (head[5] & 0x10) != 0;  // bit 12 of the little-endian version field
    in.seekg(0, std::ios::end);
    const int64_t size = int64_t(in.tellg());
    in.seekg(8);
    std::string name, type, value;
    for (bool firstHeader = true;; firstHeader = false) {
        int attributes = 0;
        while (readName(in, name) && !name.empty() && readName(in, type)) {
            unsigned char b[4];
            if (!in.read(reinterpret_cast<char*>(b), 4)) return;
            int64_t bytes = le32(b);
            int64_t at = int64_t(in.tellg());
            if (bytes < 0 || bytes > size - at)
                throw InputError(context + ": cannot read image: its header attribute \"" +
                                 printable(name) + "\" declares " + std::to_string(bytes) +
                                 " bytes, more than the " + std::to_string(size - at) +
                                 " left in the file");
            value.resize(size_t(bytes));
            if (!in.read(value.data(), bytes)) return;
            std::string why = valueMismatch(type, value);
            if (!why.empty())
                throw InputError(context + ": cannot read image: its header attribute \"" +
                                 printable(name) + "\" (" + printable(type) + ") " + why);
            if (name == "dataWindow" && type == "box2i") {
                const auto* v = reinterpret_cast<const unsigned char*>(value.data());
                int64_t w = int64_t(le32(v + 8)) - le32(v) + 1,
                        h = int64_t(le32(v + 12)) - le32(v + 4) + 1;
                if (w < 1 || h < 1 || w > maxSide || h > maxSide)
                    throw InputError(context + ": image size " + std::to_string(w) + "x" +
                                     std::to_string(h) + " out of range (1.." +
                                     std::to_string(maxSide) + " per side)");
            }
            ++attributes;
        }
        if (!in || !multiPart || (attributes == 0 && !firstHeader)) return;
    }
}

}  // namespace

struct ImageFileReader::Input {
    /// The bytes read from memory (declared first: `in` reads through it until it is closed).
    std::unique_ptr<OIIO::Filesystem::IOMemReader> memory;
    std::unique_ptr<OIIO::ImageInput> in;
};

ImageFileReader::ImageFileReader(const std::string& path, const std::string& context, int maxSide)
    : mInput(std::make_unique<Input>()), mContext(context) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    try {
        checkInputFile(path, "image", kMaxImageBytes);
    } catch (const InputError& e) {
        throw InputError(context + ": cannot read image: " + e.what());
    }
    if (ext == ".exr") checkExrHeader(path, context, maxSide);
    auto& in = mInput->in;
    in = OIIO::ImageInput::create(ext.size() > 1 ? ext.substr(1) : std::string("none"));
    OIIO::ImageSpec opened;
    if (!in || !in->open(path, opened))
        throw InputError(context +
                         ": cannot read image: " + (in ? in->geterror() : OIIO::geterror()));
    takeSize(maxSide);
}

ImageFileReader::ImageFileReader(InMemory, const std::string& bytes, const std::string& format,
                                 const std::string& context, int maxSide)
    : mInput(std::make_unique<Input>()), mContext(context) {
    if (format != "png" && format != "jpeg")
        throw InputError(context + ": cannot read image: " + format +
                         " is not read from memory (png and jpeg are)");
    if (bytes.size() > kMaxImageBytes)
        throw InputError(context + ": cannot read image: " + std::to_string(bytes.size()) +
                         " bytes, more than the " + std::to_string(kMaxImageBytes) + " allowed");
    auto& in = mInput->in;
    in = OIIO::ImageInput::create(format);
    mInput->memory = std::make_unique<OIIO::Filesystem::IOMemReader>(bytes.data(), bytes.size());
    OIIO::ImageSpec opened;
    if (!in || !in->supports("ioproxy") || !in->set_ioproxy(mInput->memory.get()) ||
        !in->open("image." + format, opened))
        throw InputError(context +
                         ": cannot read image: " + (in ? in->geterror() : OIIO::geterror()));
    takeSize(maxSide);
}

void ImageFileReader::takeSize(int maxSide) {
    const OIIO::ImageSpec& spec = mInput->in->spec();
    mWidth = spec.width;
    mHeight = spec.height;
    mChannels = spec.nchannels;
    if (mWidth < 1 || mHeight < 1 || mWidth > maxSide || mHeight > maxSide)
        throw InputError(mContext + ": image size " + std::to_string(mWidth) + "x" +
                         std::to_string(mHeight) + " out of range (1.." + std::to_string(maxSide) +
                         " per side)");
}

ImageFileReader::~ImageFileReader() = default;

std::unique_ptr<float[]> ImageFileReader::readPixels(int channels) {
    channels = std::clamp(channels, 1, mChannels);
    OIIO::ImageInput& in = *mInput->in;
    const OIIO::ImageSpec& spec = in.spec();
    // Not cleared (make_unique_for_overwrite): it is filled a band of rows at a time, so only the
    // pages of rows that decoded are ever touched.
    const size_t rowValues = size_t(mWidth) * size_t(channels);
    auto pixels = std::make_unique_for_overwrite<float[]>(rowValues * size_t(mHeight));
    // Bands of rows are read in the file's own channel formats and converted here. Asked for
    // float, OpenImageIO 2.4 converts through a buffer of about 64 MB whatever the image's size
    // (ImageInput::read_scanlines sizes it from 64 MB over the row's bytes, not from the rows
    // asked for): every small map paid for 64 MB of allocation. A band holds about 4 MB of the
    // file's pixels, whole tiles high.
    const size_t pixelBytes = spec.pixel_bytes(0, channels, true);
    const size_t rowBytes = pixelBytes * size_t(mWidth);
    const int rowsPerStep = spec.tile_width > 0 ? std::max(1, spec.tile_height) : 1;
    const int band = std::min(
        mHeight, rowsPerStep * int(std::max<size_t>(1, (4u << 20) / (rowBytes * rowsPerStep))));
    std::vector<std::byte> raw(rowBytes * size_t(band));
    const OIIO::stride_t floatPixel = OIIO::stride_t(channels * sizeof(float));
    for (int y0 = 0; y0 < mHeight; y0 += band) {
        const int y1 = std::min(mHeight, y0 + band);
        bool ok =
            spec.tile_width > 0
                ? in.read_tiles(0, 0, spec.x, spec.x + mWidth, spec.y + y0, spec.y + y1, spec.z,
                                spec.z + 1, 0, channels, OIIO::TypeDesc::UNKNOWN, raw.data())
                : in.read_scanlines(0, 0, spec.y + y0, spec.y + y1, spec.z, 0, channels,
                                    OIIO::TypeDesc::UNKNOWN, raw.data());
        if (!ok) throw InputError(mContext + ": cannot read pixels: " + in.geterror());
        // Channel by channel: an OpenEXR file may give each channel its own format.
        size_t offset = 0;
        for (int c = 0; c < channels; ++c) {
            const OIIO::TypeDesc format = spec.channelformat(c);
            if (!OIIO::convert_image(
                    1, mWidth, y1 - y0, 1, raw.data() + offset, format, OIIO::stride_t(pixelBytes),
                    OIIO::stride_t(rowBytes), OIIO::AutoStride,
                    pixels.get() + size_t(y0) * rowValues + size_t(c), OIIO::TypeDesc::FLOAT,
                    floatPixel, floatPixel * mWidth, OIIO::AutoStride))
                throw InputError(mContext + ": cannot read pixels: no conversion from " +
                                 format.c_str() + " to float");
            offset += format.size();
        }
    }
    return pixels;
}

}  // namespace candela
