#include "renderer/ImageFile.h"

#include <OpenImageIO/imageio.h>

#include <filesystem>

#include "util/Error.h"

namespace candela {

template <class T>
static void write(const std::string& path, int width, int height, const std::vector<T>& rgb,
                  OIIO::TypeDesc type) {
    auto out = OIIO::ImageOutput::create(path);
    if (!out)
        throw InputError(path + ": cannot write images of this type (use .png or .exr): " +
                         OIIO::geterror());
    OIIO::ImageSpec spec(width, height, 3, type);
    // Write to a temporary name and rename, so a failure never leaves half an image.
    std::string tmp = path + ".tmp" + std::filesystem::path(path).extension().string();
    if (!out->open(tmp, spec) || !out->write_image(type, rgb.data()) || !out->close())
        throw InputError(path + ": write failed: " + out->geterror());
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) throw InputError(path + ": write failed: " + ec.message());
}

void writeImage8(const std::string& path, int width, int height,
                 const std::vector<unsigned char>& rgb) {
    write(path, width, height, rgb, OIIO::TypeDesc::UINT8);
}

void writeImageFloat(const std::string& path, int width, int height, const std::vector<float>& rgb) {
    write(path, width, height, rgb, OIIO::TypeDesc::FLOAT);
}

std::vector<float> readImageFloat(const std::string& path, int& width, int& height) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw InputError(path + ": cannot read image: " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    width = spec.width;
    height = spec.height;
    int channels = spec.nchannels;
    std::vector<float> all(size_t(width) * size_t(height) * size_t(channels));
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, all.data()))
        throw InputError(path + ": cannot read image: " + in->geterror());
    std::vector<float> rgb(size_t(width) * size_t(height) * 3);
    for (size_t i = 0; i < size_t(width) * size_t(height); ++i)
        for (size_t c = 0; c < 3; ++c)
            rgb[i * 3 + c] = all[i * size_t(channels) + std::min(c, size_t(channels - 1))];
    return rgb;
}

}  // namespace candela
