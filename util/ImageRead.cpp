#include "util/ImageRead.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>

#include "util/Error.h"

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

int32_t le32(const unsigned char* b) {
    return int32_t(uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 |
                   uint32_t(b[3]) << 24);
}

/// OpenEXR 3.1 allocates (and clears) the size a header attribute declares before reading it, and
/// tables as long as the data window is high, so a 100-byte file can make it allocate gigabytes
/// or spend half a minute (fuzzing found both). Walks the header(s) as the file layout specifies
/// ("OpenEXR File Layout": magic number, version field whose bit 12 marks multi-part files; per
/// attribute a name and a type name, NUL-terminated, an int32 size and the value; an empty name
/// ends a header, an empty header ends a multi-part file's list) and refuses an attribute larger
/// than what is left of the file, and a data window (box2i) wider or higher than `maxSide`.
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
    std::string name, type;
    for (bool firstHeader = true;; firstHeader = false) {
        int attributes = 0;
        while (readName(in, name) && !name.empty() && readName(in, type)) {
            unsigned char b[16];
            if (!in.read(reinterpret_cast<char*>(b), 4)) return;
            int64_t bytes = le32(b);
            int64_t at = int64_t(in.tellg());
            if (bytes < 0 || bytes > size - at) {
                std::string shown;
                for (char c : name) shown += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
                throw InputError(context + ": cannot read image: its header attribute \"" + shown +
                                 "\" declares " + std::to_string(bytes) + " bytes, more than the " +
                                 std::to_string(size - at) + " left in the file");
            }
            if (name == "dataWindow" && type == "box2i" && bytes == 16 &&
                in.read(reinterpret_cast<char*>(b), 16)) {
                int64_t w = int64_t(le32(b + 8)) - le32(b) + 1,
                        h = int64_t(le32(b + 12)) - le32(b + 4) + 1;
                if (w < 1 || h < 1 || w > maxSide || h > maxSide)
                    throw InputError(context + ": image size " + std::to_string(w) + "x" +
                                     std::to_string(h) + " out of range (1.." +
                                     std::to_string(maxSide) + " per side)");
            }
            in.seekg(at + bytes);
            ++attributes;
        }
        if (!in || !multiPart || (attributes == 0 && !firstHeader)) return;
    }
}

}  // namespace

struct ImageFileReader::Input {
    std::unique_ptr<OIIO::ImageInput> in;
};

ImageFileReader::ImageFileReader(const std::string& path, const std::string& context, int maxSide)
    : mInput(std::make_unique<Input>()), mContext(context) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (ext == ".exr") checkExrHeader(path, context, maxSide);
    auto& in = mInput->in;
    in = OIIO::ImageInput::create(ext.size() > 1 ? ext.substr(1) : std::string("none"));
    OIIO::ImageSpec opened;
    if (!in || !in->open(path, opened))
        throw InputError(context +
                         ": cannot read image: " + (in ? in->geterror() : OIIO::geterror()));
    const OIIO::ImageSpec& spec = in->spec();
    mWidth = spec.width;
    mHeight = spec.height;
    mChannels = spec.nchannels;
    if (mWidth < 1 || mHeight < 1 || mWidth > maxSide || mHeight > maxSide)
        throw InputError(context + ": image size " + std::to_string(mWidth) + "x" +
                         std::to_string(mHeight) + " out of range (1.." + std::to_string(maxSide) +
                         " per side)");
}

ImageFileReader::~ImageFileReader() = default;

std::unique_ptr<float[]> ImageFileReader::readPixels(int channels) {
    channels = std::clamp(channels, 1, mChannels);
    // Not cleared (make_unique_for_overwrite): OpenImageIO decodes a band of rows at a time into
    // it, so only the pages of rows that decoded are ever touched.
    auto pixels = std::make_unique_for_overwrite<float[]>(size_t(mWidth) * size_t(mHeight) *
                                                          size_t(channels));
    if (!mInput->in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, pixels.get()))
        throw InputError(mContext + ": cannot read pixels: " + mInput->in->geterror());
    return pixels;
}

}  // namespace candela
