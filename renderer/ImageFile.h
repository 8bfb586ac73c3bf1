#pragma once
// Image export through OpenImageIO: PNG (tone-mapped 8-bit) and EXR (linear float).

#include <string>
#include <vector>

namespace candela {

/// Writes RGB rows top to bottom through a temporary file and a rename (util/FileOutput.h). The
/// extension picks the format; throws InputError naming the file for an unsupported extension, a
/// write failure (the old file then stays as it was) or a protected input.
void writeImage8(const std::string& path, int width, int height,
                 const std::vector<unsigned char>& rgb);
void writeImageFloat(const std::string& path, int width, int height, const std::vector<float>& rgb);

/// RGB rows top to bottom from RGBA rows bottom to top (what glGetTextureImage and glReadPixels
/// return): the alpha channel dropped.
template <class T>
std::vector<T> rgbTopDown(const std::vector<T>& rgba, int width, int height) {
    std::vector<T> rgb(size_t(width) * size_t(height) * 3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c)
                rgb[(size_t(y) * size_t(width) + size_t(x)) * 3 + size_t(c)] =
                    rgba[(size_t(height - 1 - y) * size_t(width) + size_t(x)) * 4 + size_t(c)];
    return rgb;
}

/// Reads an image as float RGB through ImageFileReader, the reader its extension names (tests
/// compare images with it).
std::vector<float> readImageFloat(const std::string& path, int& width, int& height);

}  // namespace candela
