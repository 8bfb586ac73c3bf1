#include "renderer/ImageFile.h"

#include <algorithm>
#include <memory>

#include "util/Error.h"
#include "util/FileOutput.h"
#include "util/ImageRead.h"

namespace candela {

namespace {

template <class T>
void checkSize(const std::string& path, int width, int height, const std::vector<T>& rgb) {
    if (width <= 0 || height <= 0 || rgb.size() < size_t(width) * size_t(height) * 3)
        throw InputError(path + ": " + std::to_string(rgb.size()) + " values for a " +
                         std::to_string(width) + "x" + std::to_string(height) + " RGB image");
}

}  // namespace

void writeImage8(const std::string& path, int width, int height,
                 const std::vector<unsigned char>& rgb) {
    checkSize(path, width, height, rgb);
    writeImageAtomically(path, width, height, 3, rgb.data());
}

void writeImageFloat(const std::string& path, int width, int height,
                     const std::vector<float>& rgb) {
    checkSize(path, width, height, rgb);
    writeImageAtomically(path, width, height, 3, rgb.data());
}

std::vector<float> readImageFloat(const std::string& path, int& width, int& height) {
    ImageFileReader in(path, path, 1 << 16);
    width = in.width();
    height = in.height();
    const int channels = std::min(in.channels(), 3);
    std::unique_ptr<float[]> read = in.readPixels(channels);
    std::vector<float> rgb(size_t(width) * size_t(height) * 3);
    for (size_t i = 0; i < size_t(width) * size_t(height); ++i)
        for (size_t c = 0; c < 3; ++c)  // grey images repeat their one channel
            rgb[i * 3 + c] = read[i * size_t(channels) + std::min(c, size_t(channels - 1))];
    return rgb;
}

}  // namespace candela
