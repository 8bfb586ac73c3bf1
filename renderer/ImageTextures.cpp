#include "renderer/ImageTextures.h"

#include <stdexcept>

#include "renderer/gl/GlFunctions.h"

namespace candela {

void ImageTextures::upload(const std::string& key, int width, int height,
                           const std::vector<unsigned char>& rgb) {
    const size_t pixels = size_t(width) * size_t(height);
    if (width < 1 || height < 1 || rgb.size() != 3 * pixels)
        throw std::invalid_argument(
            "ImageTextures::upload: " + key + " has " + std::to_string(rgb.size()) + " bytes for " +
            std::to_string(width) + " x " + std::to_string(height) + " RGB pixels");
    std::vector<unsigned char> rgba(4 * pixels, 255);
    for (size_t i = 0; i < pixels; ++i)
        for (size_t c = 0; c < 3; ++c) rgba[4 * i + c] = rgb[3 * i + c];
    gl::Texture2D texture(width, height, GL_RGBA8);
    glTextureSubImage2D(texture.id(), 0, 0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE,
                        rgba.data());
    mTextures.insert_or_assign(key, std::move(texture));
}

ImageTextures::Shown ImageTextures::find(const std::string& key) const {
    auto found = mTextures.find(key);
    if (found == mTextures.end()) return {};
    return {uint64_t(found->second.id()), found->second.width(), found->second.height()};
}

}  // namespace candela
