#pragma once
// Image export through OpenImageIO: PNG (tone-mapped 8-bit) and EXR (linear float).

#include <string>
#include <vector>

namespace candela {

/// Writes RGB rows top to bottom. The extension picks the format; throws InputError naming the
/// file for an unsupported extension or a write failure.
void writeImage8(const std::string& path, int width, int height,
                 const std::vector<unsigned char>& rgb);
void writeImageFloat(const std::string& path, int width, int height, const std::vector<float>& rgb);

/// Reads any OpenImageIO format as float RGB (tests compare images with it).
std::vector<float> readImageFloat(const std::string& path, int& width, int& height);

}  // namespace candela
