// What the editor's inspector and the report show of a GLDF product (formats/Gldf.h,
// gldfProductInfo and gldfPicture): the manufacturer, the article number (a variant's own
// ProductNumber over the product's), the description, and the picture decoded to RGB. The
// pictures are checked against decoders that are not the one under test: the gldf.net container's
// PNG against cairo's PNG reader (libpng), a JPEG written here against the colour it was written
// with. A picture that cannot be decoded is a warning, never a refusal.
#include <OpenImageIO/imageio.h>
#include <cairo.h>
#include <gtest/gtest.h>
#include <zip.h>

#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "formats/Gldf.h"
#include "tests/TempDir.h"

namespace candela {
namespace {

const std::string kData = CANDELA_TEST_DATA;

std::string complete() {
    return kData + "/gldf/GldfWithFilesComplete.gldf";
}

std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

/// A member's bytes read with libzip (not through the reader under test).
std::string memberOf(const std::string& path, const std::string& member) {
    int error = 0;
    zip_t* z = zip_open(path.c_str(), ZIP_RDONLY, &error);
    if (!z) throw std::runtime_error("cannot open " + path);
    zip_stat_t st;
    zip_file_t* f =
        zip_stat(z, member.c_str(), 0, &st) == 0 ? zip_fopen(z, member.c_str(), 0) : nullptr;
    if (!f) throw std::runtime_error("no " + member + " in " + path);
    std::string out(size_t(st.size), '\0');
    zip_int64_t n = zip_fread(f, out.data(), st.size);
    zip_fclose(f);
    zip_discard(z);
    if (n != zip_int64_t(st.size)) throw std::runtime_error("short read of " + member);
    return out;
}

/// Writes a container with libzip: (member name, bytes) pairs.
void writeZip(const std::string& path,
              const std::vector<std::pair<std::string, std::string>>& members) {
    int error = 0;
    zip_t* z = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
    ASSERT_NE(z, nullptr);
    for (const auto& [name, bytes] : members) {
        zip_source_t* s = zip_source_buffer(z, bytes.data(), bytes.size(), 0);
        ASSERT_NE(s, nullptr);
        ASSERT_GE(zip_file_add(z, name.c_str(), s, ZIP_FL_ENC_UTF_8), 0) << zip_strerror(z);
    }
    ASSERT_EQ(zip_close(z), 0);
}

/// A product.xml with two image files (a.jpg, b.png), the product's ProductNumber "P-1" and
/// Pictures `productPictures`, and variants v1 (its own ProductNumber "V1-ART", a description,
/// Pictures `variantPictures`) and v2 (neither).
std::string productXml(const std::string& productPictures, const std::string& variantPictures) {
    return R"(<?xml version="1.0" encoding="utf-8"?>
<Root>
  <Header><Manufacturer>Acme Lighting</Manufacturer><FormatVersion major="1" minor="0"/>
    <CreatedWithApplication>test</CreatedWithApplication>
    <GldfCreationTimeCode>2024-01-01T00:00:00Z</GldfCreationTimeCode><UniqueGldfId>x</UniqueGldfId>
  </Header>
  <GeneralDefinitions><Files>
    <File id="jpg" contentType="image/jpg" type="localFileName">a.jpg</File>
    <File id="png" contentType="image/png" type="localFileName">b.png</File>
    <File id="svg" contentType="image/svg" type="localFileName">c.svg</File>
  </Files></GeneralDefinitions>
  <ProductDefinitions>
    <ProductMetaData><UniqueProductId>u</UniqueProductId>
      <ProductNumber><Locale language="en">P-1</Locale></ProductNumber>
      <Name><Locale language="en">Panel</Locale></Name>
      <Description><Locale language="en">A square panel</Locale></Description>
      <Pictures>)" +
           productPictures + R"(</Pictures>
    </ProductMetaData>
    <Variants>
      <Variant id="v1"><ProductNumber><Locale language="en">V1-ART</Locale></ProductNumber>
        <Name><Locale language="en">Opal</Locale></Name>
        <Description><Locale language="en">Opal diffuser</Locale></Description>
        <Geometry/><Pictures>)" +
           variantPictures + R"(</Pictures></Variant>
      <Variant id="v2"><Name><Locale language="en">Prism</Locale></Name><Geometry/></Variant>
    </Variants>
  </ProductDefinitions>
</Root>
)";
}

/// A uniform JPEG of `width` x `height` in `rgb`, written by OpenImageIO to a file and read back.
std::string uniformJpeg(const test::TempDir& tmp, int width, int height, const unsigned char* rgb) {
    std::string path = tmp.file("uniform.jpg");
    std::vector<unsigned char> pixels(size_t(width) * size_t(height) * 3);
    for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = rgb[i % 3];
    auto out = OIIO::ImageOutput::create(path);
    if (!out) throw std::runtime_error("no JPEG writer");
    OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("Compression", "jpeg:95");
    if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::UINT8, pixels.data()) ||
        !out->close())
        throw std::runtime_error("cannot write " + path);
    return readBytes(path);
}

std::string pictureTag(const std::string& file, const std::string& type) {
    return R"(<Image fileId=")" + file + R"(" imageType=")" + type + R"("/>)";
}

// The gldf.net container: the header's manufacturer, the product's article number for both
// variants (neither has its own), the variant's description over the product's (it has none), and
// its one picture (the product's "Other", the second variant's "Technical Sketch": the same PNG).
TEST(GldfProductInfo, CompleteContainerNamesItsProduct) {
    GldfProduct p = loadGldf(complete());
    GldfProductInfo one = gldfProductInfo(p, "variant-1");
    EXPECT_EQ(one.manufacturer, "DIAL");
    EXPECT_EQ(one.product, "Product name");
    EXPECT_EQ(one.variant, "Variant name 1");
    EXPECT_EQ(one.articleNumber, "Product number");
    EXPECT_EQ(one.description, "Variant description 1");
    ASSERT_NE(one.picture, nullptr);
    EXPECT_EQ(one.picture->member(), "image/image.png");
    GldfProductInfo two = gldfProductInfo(p, "variant-2");
    EXPECT_EQ(two.articleNumber, "Product number");
    EXPECT_EQ(two.description, "");  // neither the variant nor the product has one
    ASSERT_NE(two.picture, nullptr);
    EXPECT_EQ(two.picture->id, "imageFile");
    ASSERT_EQ(p.variants[1].pictures.size(), 1u);
    EXPECT_EQ(p.variants[1].pictures[0].imageType, "Technical Sketch");
    ASSERT_EQ(p.pictures.size(), 1u);
    EXPECT_EQ(p.pictures[0].imageType, "Other");
}

// Its PNG (136 x 200, a palette image) decodes to the pixels libpng gives through cairo, exactly:
// both expand the palette to the same 8-bit values.
TEST(GldfProductInfo, CompleteContainerPictureDecodesAsLibpngReadsIt) {
    std::string bytes = readGldfBytes(complete());
    GldfProduct p = parseGldf(bytes, complete());
    std::vector<std::string> warnings;
    std::optional<GldfImage> image =
        gldfPicture(bytes, p, gldfProductInfo(p, "variant-1"), warnings);
    ASSERT_TRUE(image) << (warnings.empty() ? "" : warnings[0]);
    EXPECT_TRUE(warnings.empty());

    std::string png = memberOf(complete(), "image/image.png");
    struct Reader {
        const std::string* bytes;
        size_t at = 0;
    } reader{&png};
    cairo_surface_t* surface = cairo_image_surface_create_from_png_stream(
        [](void* closure, unsigned char* data, unsigned int length) {
            auto* r = static_cast<Reader*>(closure);
            if (r->at + length > r->bytes->size()) return CAIRO_STATUS_READ_ERROR;
            std::memcpy(data, r->bytes->data() + r->at, length);
            r->at += length;
            return CAIRO_STATUS_SUCCESS;
        },
        &reader);
    ASSERT_EQ(cairo_surface_status(surface), CAIRO_STATUS_SUCCESS);
    const int w = cairo_image_surface_get_width(surface),
              h = cairo_image_surface_get_height(surface);
    ASSERT_EQ(image->width, 136);
    ASSERT_EQ(image->height, 200);
    ASSERT_EQ(w, image->width);
    ASSERT_EQ(h, image->height);
    ASSERT_EQ(image->rgb.size(), size_t(w) * size_t(h) * 3);
    ASSERT_EQ(cairo_image_surface_get_format(surface), CAIRO_FORMAT_RGB24);  // no alpha in it
    const unsigned char* data = cairo_image_surface_get_data(surface);
    const int stride = cairo_image_surface_get_stride(surface);
    int differ = 0, distinct = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            uint32_t v;
            std::memcpy(&v, data + size_t(y) * size_t(stride) + size_t(x) * 4, 4);
            const unsigned char want[3] = {(unsigned char)(v >> 16), (unsigned char)(v >> 8),
                                           (unsigned char)v};
            const unsigned char* got = &image->rgb[(size_t(y) * size_t(w) + size_t(x)) * 3];
            differ += std::memcmp(want, got, 3) != 0;
            distinct += std::memcmp(got, image->rgb.data(), 3) != 0;
        }
    cairo_surface_destroy(surface);
    EXPECT_EQ(differ, 0);
    EXPECT_GT(distinct, 0);  // a picture, not one colour
}

// A variant's own article number overrides the product's; its "Product Picture" is taken before
// the product's, and the product's "Product Picture" before the variant's technical sketch; an
// SVG is not a picture to decode. A JPEG decodes to the colour it was written with.
TEST(GldfProductInfo, VariantArticleNumberAndPictureChoice) {
    test::TempDir tmp;
    const unsigned char colour[3] = {200, 120, 40};
    const std::string jpeg = uniformJpeg(tmp, 24, 16, colour);
    auto build = [&](const std::string& productPictures, const std::string& variantPictures) {
        std::string path = tmp.file("panel.gldf");
        writeZip(path, {{"product.xml", productXml(productPictures, variantPictures)},
                        {"image/a.jpg", jpeg},
                        {"image/b.png", "not a PNG"},
                        {"image/c.svg", "<svg/>"}});
        return path;
    };

    std::string path =
        build(pictureTag("png", "Product Picture"),
              pictureTag("svg", "Product Picture") + pictureTag("jpg", "Product Picture"));
    GldfProduct p = loadGldf(path);
    GldfProductInfo v1 = gldfProductInfo(p, "v1");
    EXPECT_EQ(v1.manufacturer, "Acme Lighting");
    EXPECT_EQ(v1.articleNumber, "V1-ART");
    EXPECT_EQ(v1.description, "Opal diffuser");
    ASSERT_NE(v1.picture, nullptr);
    EXPECT_EQ(v1.picture->id, "jpg");  // the variant's first decodable product picture
    GldfProductInfo v2 = gldfProductInfo(p, "v2");
    EXPECT_EQ(v2.articleNumber, "P-1");
    EXPECT_EQ(v2.description, "A square panel");
    ASSERT_NE(v2.picture, nullptr);
    EXPECT_EQ(v2.picture->id, "png");  // the product's

    std::vector<std::string> warnings;
    std::optional<GldfImage> image = gldfPicture(readGldfBytes(path), p, v1, warnings);
    ASSERT_TRUE(image) << (warnings.empty() ? "" : warnings[0]);
    EXPECT_EQ(image->width, 24);
    EXPECT_EQ(image->height, 16);
    // JPEG at quality 95 keeps a uniform colour within a few levels (chroma subsampling and the
    // YCbCr round trip round each channel; 4 of 255 allows for both).
    for (size_t i = 0; i < image->rgb.size(); ++i)
        ASSERT_NEAR(int(image->rgb[i]), int(colour[i % 3]), 4) << "byte " << i;

    // The product's product picture comes before the variant's technical sketch.
    p = loadGldf(
        build(pictureTag("jpg", "Product Picture"), pictureTag("png", "Technical Sketch")));
    EXPECT_EQ(gldfProductInfo(p, "v1").picture->id, "jpg");
    // Only an SVG: no picture.
    p = loadGldf(build(pictureTag("svg", "Product Picture"), pictureTag("svg", "Other")));
    EXPECT_EQ(gldfProductInfo(p, "v1").picture, nullptr);
}

// A picture that does not decode (a PNG file of other bytes), or is missing from the container,
// is a warning naming the container and the member; the product still loads and the result is
// empty. A picture naming a file the product lacks is left out at load, with a warning.
TEST(GldfProductInfo, UndecodablePictureIsAWarning) {
    test::TempDir tmp;
    std::string path = tmp.file("panel.gldf");
    writeZip(
        path,
        {{"product.xml",
          productXml(pictureTag("png", "Product Picture") + pictureTag("nofile", "Other"), "")},
         {"image/b.png", "not a PNG"}});
    GldfProduct p = loadGldf(path);
    ASSERT_EQ(p.pictures.size(), 1u);
    ASSERT_EQ(p.warnings.size(), 1u);
    EXPECT_NE(p.warnings[0].find("picture file \"nofile\""), std::string::npos) << p.warnings[0];
    GldfProductInfo info = gldfProductInfo(p, "v1");
    ASSERT_NE(info.picture, nullptr);
    std::vector<std::string> warnings;
    EXPECT_FALSE(gldfPicture(readGldfBytes(path), p, info, warnings));
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0].rfind(path + ": image/b.png: cannot read image", 0), 0u) << warnings[0];
    EXPECT_NE(warnings[0].find("the picture is left out"), std::string::npos) << warnings[0];

    // Missing from the container.
    writeZip(path, {{"product.xml", productXml(pictureTag("jpg", "Product Picture"), "")}});
    p = loadGldf(path);
    warnings.clear();
    EXPECT_FALSE(gldfPicture(readGldfBytes(path), p, gldfProductInfo(p, "v1"), warnings));
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("image/a.jpg"), std::string::npos) << warnings[0];
    EXPECT_NE(warnings[0].find("not in the container"), std::string::npos) << warnings[0];
}

}  // namespace
}  // namespace candela
