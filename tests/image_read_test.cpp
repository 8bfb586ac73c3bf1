// Reading user images (util/ImageRead.h) as fuzzing left it: only the reader the extension names,
// OpenEXR headers checked before OpenEXR allocates what they declare, channels beyond RGB never
// read, tiled files read like scanline ones.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "luminaires/Environment.h"
#include "tests/TestUtil.h"
#include "util/Error.h"
#include "util/ImageRead.h"

namespace candela {
namespace {

namespace fs = std::filesystem;

struct TempDir {
    fs::path path =
        fs::temp_directory_path() / ("candela_image_read_" + std::to_string(::getpid()));
    TempDir() { fs::create_directories(path); }
    ~TempDir() { fs::remove_all(path); }
    std::string operator/(const std::string& name) const { return (path / name).string(); }
};

/// Writes a width x height image with `channels` float channels, value (c + 1) / 10 in channel c;
/// tiled when tile > 0.
void writeImage(const std::string& path, int width, int height, int channels, int tile = 0) {
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out) << path;
    OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::FLOAT);
    if (tile > 0) spec.tile_width = spec.tile_height = tile;
    std::vector<float> px(size_t(width) * size_t(height) * size_t(channels));
    for (size_t i = 0; i < px.size(); ++i) px[i] = float(i % size_t(channels) + 1) / 10.f;
    ASSERT_TRUE(out->open(path, spec)) << out->geterror();
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, px.data())) << out->geterror();
    out->close();
}

std::string regression(const std::string& name) {
    return test::sourceDir() + "/fuzz/regressions/image/" + name;
}

TEST(ImageRead, OnlyTheReaderTheExtensionNames) {
    TempDir dir;
    writeImage(dir / "map.png", 16, 8, 3);
    ImageFileReader png(dir / "map.png", "map.png", 64);  // the file itself is a valid image
    EXPECT_EQ(png.width(), 16);
    fs::copy_file(dir / "map.png", dir / "map.exr");
    // OpenImageIO would have found the PNG reader for it and loaded it.
    std::string m = test::inputError([&] { EnvironmentMap::load(dir / "map.exr"); });
    EXPECT_NE(m.find("map.exr: cannot read image: "), std::string::npos) << m;
}

TEST(ImageRead, ExrHeadersCannotClaimMoreThanTheFile) {
    // Fuzzing's inputs: a string attribute declaring 2 GB (OpenEXR 3.1 allocated and cleared it)
    // and a data window 1e9 rows high (OpenEXR spent half a minute on its tables).
    std::string m =
        test::inputError([] { EnvironmentMap::load(regression("exr-string-attribute-2gb.exr")); });
    EXPECT_NE(m.find("its header attribute \"Exif:ImageHistory\" declares 1979711607 bytes, more "
                     "than the 681 left in the file"),
              std::string::npos)
        << m;
    m = test::inputError([] { EnvironmentMap::load(regression("exr-data-window-slow.exr")); });
    EXPECT_NE(m.find("out of range (1..16384 per side)"), std::string::npos) << m;
}

TEST(ImageRead, ChannelsBeyondRgbAreNotReadAndTiledFilesLoad) {
    TempDir dir;
    writeImage(dir / "five.exr", 16, 8, 5);
    auto map = EnvironmentMap::load(dir / "five.exr");
    glm::dvec3 t = map->texel(3, 2);
    // Float channels written as (c + 1) / 10; compared in float precision.
    EXPECT_NEAR(t.x, 0.1, 1e-7);
    EXPECT_NEAR(t.y, 0.2, 1e-7);
    EXPECT_NEAR(t.z, 0.3, 1e-7);
    writeImage(dir / "tiled.exr", 32, 16, 3, 8);
    ImageFileReader tiled(dir / "tiled.exr", "tiled.exr", 64);
    std::unique_ptr<float[]> px = tiled.readPixels(3);
    for (size_t i = 0; i < 32 * 16 * 3; ++i) ASSERT_EQ(px[i], float(i % 3 + 1) / 10.f) << i;
    std::string m = test::inputError([&] { ImageFileReader(dir / "tiled.exr", "tiled.exr", 16); });
    EXPECT_EQ(m, "tiled.exr: image size 32x16 out of range (1..16 per side)");
}

}  // namespace
}  // namespace candela
