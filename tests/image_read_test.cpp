// Reading user images (util/ImageRead.h) as fuzzing left it: only the reader the extension names,
// OpenEXR headers checked before OpenEXR allocates what they declare, channels beyond RGB never
// read, tiled files read like scanline ones.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "luminaires/environment/Environment.h"
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
    // A data window declaring 243 bytes: OpenEXR 3.1 reads a box2i's 16 whatever the declaration,
    // so it took the next bytes as an attribute of 1.7 GB that the walk had skipped.
    m = test::inputError([] { EnvironmentMap::load(regression("exr-box2i-size-desync.exr")); });
    EXPECT_NE(m.find("its header attribute \"dataWindow\" (box2i) declares 243 bytes where a "
                     "box2i holds 16"),
              std::string::npos)
        << m;
    m = test::inputError(
        [] { EnvironmentMap::load(regression("exr-channel-list-unterminated.exr")); });
    EXPECT_NE(m.find("its header attribute \"channels\" (chlist) is a channel list that does not "
                     "end at its 55 bytes"),
              std::string::npos)
        << m;
}

/// `v` as four little-endian bytes.
std::string le32Bytes(uint32_t v) {
    std::string s;
    for (int i = 0; i < 4; ++i) s += char(v >> (8 * i) & 0xff);
    return s;
}

/// `file` with one more attribute at the start of its header: NAME, TYPE, the declared size
/// `declared` and the bytes `value`.
std::string withAttribute(const std::string& file, const std::string& name, const std::string& type,
                          int32_t declared, const std::string& value) {
    std::ifstream in(file, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::string attribute = name + '\0' + type + '\0';
    attribute += le32Bytes(uint32_t(declared)) + value;
    bytes.insert(8, attribute);
    std::string out = file + "." + name + ".exr";
    std::ofstream(out, std::ios::binary) << bytes;
    return out;
}

/// The header walk reads each value as OpenEXR 3.1 does, so that what OpenEXR takes for the next
/// attribute is what the walk checked: a value of another size than OpenEXR reads is refused.
TEST(ImageRead, ExrValuesMustBeAsLongAsOpenExrReadsThem) {
    TempDir dir;
    writeImage(dir / "map.exr", 16, 8, 3);
    auto refusal = [](const std::string& path) {
        try {
            ImageFileReader r(path, "map.exr", 64);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    auto refusedFor = [&](const std::string& path, const std::string& why) {
        std::string m = refusal(path);
        EXPECT_NE(m.find("its header attribute"), std::string::npos) << path << ": " << m;
        EXPECT_NE(m.find(why), std::string::npos) << path << ": " << m;
    };
    auto headerPasses = [&](const std::string& path) {
        std::string m = refusal(path);
        EXPECT_EQ(m.find("its header attribute"), std::string::npos) << path << ": " << m;
    };
    std::string channel = std::string("Z") + '\0' + std::string(16, '\0');
    std::string preview2x2 = le32Bytes(2) + le32Bytes(2) + std::string(16, '\x7f');
    std::string strings = le32Bytes(2) + "ab" + le32Bytes(1) + "c";
    // Values as OpenEXR reads them pass the walk.
    headerPasses(withAttribute(dir / "map.exr", "a", "float", 4, "abcd"));
    headerPasses(withAttribute(dir / "map.exr", "b", "chlist", 19, channel + '\0'));
    headerPasses(withAttribute(dir / "map.exr", "c", "preview", 24, preview2x2));
    headerPasses(withAttribute(dir / "map.exr", "d", "stringvector", 11, strings));
    headerPasses(withAttribute(dir / "map.exr", "e", "mytype", 3, "xyz"));  // read as declared
    // Values of other sizes are refused, naming the attribute and its type.
    refusedFor(withAttribute(dir / "map.exr", "f", "float", 5, "abcde"),
               "\"f\" (float) declares 5 bytes where a float holds 4");
    refusedFor(withAttribute(dir / "map.exr", "g", "chlist", 20, channel + '\0' + 'x'),
               "\"g\" (chlist) is a channel list that does not end at its 20 bytes");
    // Its last byte not the empty name that ends it (fuzzing's exr-channel-list-unterminated.exr):
    // OpenEXR read on past the declared bytes.
    refusedFor(withAttribute(dir / "map.exr", "g2", "chlist", 19, channel + 'x'),
               "\"g2\" (chlist) is a channel list that does not end at its 19 bytes");
    refusedFor(withAttribute(dir / "map.exr", "h", "preview", 24,
                             le32Bytes(3) + le32Bytes(2) + std::string(16, '\x7f')),
               "\"h\" (preview) is a 3x2 preview in 24 bytes");
    refusedFor(withAttribute(dir / "map.exr", "i", "preview", 24,
                             le32Bytes(65535) + le32Bytes(65535) + std::string(16, '\x7f')),
               "is a 65535x65535 preview in 24 bytes");
    refusedFor(withAttribute(dir / "map.exr", "j", "stringvector", 11,
                             le32Bytes(2) + "ab" + le32Bytes(1000) + "c"),
               "\"j\" (stringvector) is a string list that does not end at its 11 bytes");
    refusedFor(withAttribute(dir / "map.exr", "k", "floatvector", 6, "abcdef"),
               "declares 6 bytes for 4-byte floats");
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

/// A value that names its pixel and channel, an integer below 2048 so that half, float and the
/// unsigned integer formats all hold it exactly.
float pixelCode(int x, int y, int c) {
    return float((x + 3 * y + 7 * c) % 2048);
}

/// Writes `spec`'s image with pixelCode values in every channel.
void writeCoded(const std::string& path, const OIIO::ImageSpec& spec) {
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out) << path;
    std::vector<float> px(size_t(spec.width) * size_t(spec.height) * size_t(spec.nchannels));
    for (int y = 0; y < spec.height; ++y)
        for (int x = 0; x < spec.width; ++x)
            for (int c = 0; c < spec.nchannels; ++c)
                px[(size_t(y) * size_t(spec.width) + size_t(x)) * size_t(spec.nchannels) +
                   size_t(c)] = pixelCode(x, y, c);
    ASSERT_TRUE(out->open(path, spec)) << out->geterror();
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, px.data())) << out->geterror();
    out->close();
}

/// readPixels reads bands of rows in the file's own formats (about 4 MB each) and converts them
/// itself; every pixel must land where it was, across band edges, partial edge tiles and
/// channels of different formats.
TEST(ImageRead, BandsOfRowsKeepEveryPixelInPlace) {
    TempDir dir;
    struct Case {
        std::string name;
        OIIO::ImageSpec spec;
    };
    std::vector<Case> cases;
    // Three half channels of four: 9 000 bytes a row, 466 rows a band, two bands.
    cases.push_back({"half.exr", OIIO::ImageSpec(1500, 700, 4, OIIO::TypeDesc::HALF)});
    // 64-pixel tiles, partial at the right and bottom edges: 5 tile rows a band, three bands.
    cases.push_back({"tiled.exr", OIIO::ImageSpec(1000, 700, 3, OIIO::TypeDesc::FLOAT)});
    cases.back().spec.tile_width = cases.back().spec.tile_height = 64;
    // A format per channel, as OpenEXR allows.
    cases.push_back({"mixed.exr", OIIO::ImageSpec(300, 200, 4, OIIO::TypeDesc::FLOAT)});
    cases.back().spec.channelformats = {OIIO::TypeDesc::HALF, OIIO::TypeDesc::FLOAT,
                                        OIIO::TypeDesc::HALF, OIIO::TypeDesc::FLOAT};
    for (const Case& k : cases) {
        writeCoded(dir / k.name, k.spec);
        auto written = OIIO::ImageInput::open(dir / k.name);
        ASSERT_TRUE(written);
        EXPECT_EQ(written->spec().channelformats.size(), k.spec.channelformats.size()) << k.name;
        EXPECT_EQ(written->spec().tile_width, k.spec.tile_width) << k.name;
        ImageFileReader in(dir / k.name, k.name, 4096);
        ASSERT_EQ(in.channels(), k.spec.nchannels) << k.name;
        std::unique_ptr<float[]> px = in.readPixels(3);
        size_t wrong = 0;
        for (int y = 0; y < k.spec.height; ++y)
            for (int x = 0; x < k.spec.width; ++x)
                for (int c = 0; c < 3; ++c)
                    if (px[(size_t(y) * size_t(k.spec.width) + size_t(x)) * 3 + size_t(c)] !=
                        pixelCode(x, y, c))
                        ++wrong;
        EXPECT_EQ(wrong, 0u) << k.name;
    }
    // Eight-bit channels read as value / 255, as OpenImageIO converts them.
    OIIO::ImageSpec png(40, 20, 3, OIIO::TypeDesc::UINT8);
    auto out = OIIO::ImageOutput::create(dir / "bytes.png");
    ASSERT_TRUE(out);
    std::vector<unsigned char> bytes(40 * 20 * 3);
    for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<unsigned char>(i * 7 % 256);
    ASSERT_TRUE(out->open(dir / "bytes.png", png)) << out->geterror();
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, bytes.data())) << out->geterror();
    out->close();
    ImageFileReader in(dir / "bytes.png", "bytes.png", 64);
    std::unique_ptr<float[]> px = in.readPixels(3);
    // One float rounding of v / 255.
    for (size_t i = 0; i < bytes.size(); ++i) ASSERT_NEAR(px[i], bytes[i] / 255.0, 1e-7) << i;
}

}  // namespace
}  // namespace candela
