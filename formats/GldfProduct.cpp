// What a designer and a client read about a GLDF product (formats/Gldf.h): its manufacturer,
// article number and description from product.xml, and its picture decoded from the container.
#include <algorithm>
#include <cmath>

#include "formats/Gldf.h"
#include "util/Error.h"
#include "util/ImageRead.h"
#include "util/TextEncoding.h"
#include "util/ZipArchive.h"

namespace candela {

GldfProductInfo gldfProductInfo(const GldfProduct& product, const std::string& variantId) {
    GldfProductInfo info;
    info.manufacturer = product.manufacturer;
    info.product = product.productName;
    info.articleNumber = product.productNumber;
    info.description = product.description;
    const GldfVariant* variant = variantId.empty() ? nullptr : product.variant(variantId);
    if (variant) {
        info.variant = variant->name;
        if (!variant->productNumber.empty()) info.articleNumber = variant->productNumber;
        if (!variant->description.empty()) info.description = variant->description;
    }
    // A picture in the container that can be decoded: PNG or JPEG.
    auto decodable = [&product](const GldfPicture& p) -> const GldfFile* {
        const GldfFile* f = product.file(p.fileId);
        return f && !f->url && (f->contentType == "image/png" || f->contentType == "image/jpg")
                   ? f
                   : nullptr;
    };
    const std::vector<GldfPicture> none;
    const std::vector<GldfPicture>* lists[] = {variant ? &variant->pictures : &none,
                                               &product.pictures};
    for (bool productPicture : {true, false})
        for (const std::vector<GldfPicture>* list : lists)
            for (const GldfPicture& p : *list)
                if ((p.imageType == "Product Picture") == productPicture && !info.picture)
                    info.picture = decodable(p);
    return info;
}

std::optional<GldfImage> gldfPicture(const std::string& bytes, const GldfProduct& product,
                                     const GldfProductInfo& info,
                                     std::vector<std::string>& warnings) {
    if (!info.picture) return std::nullopt;
    const std::string member = info.picture->member();
    const std::string context = product.path + ": " + member;
    try {
        ZipArchive archive(bytes, product.path, "a GLDF container");
        const int64_t index = archive.find(member);
        if (index < 0) throw InputError(context + ": not in the container");
        const std::string image = archive.read(index, member + " (picture)");
        const std::string format = info.picture->contentType == "image/png" ? "png" : "jpeg";
        ImageFileReader reader(ImageFileReader::InMemory{}, image, format, context,
                               kMaxGldfPictureSide);
        const int channels = std::min(reader.channels(), 4);
        std::unique_ptr<float[]> pixels = reader.readPixels(channels);
        GldfImage out;
        out.width = reader.width();
        out.height = reader.height();
        out.rgb.resize(size_t(out.width) * size_t(out.height) * 3);
        // Grey (1 channel) or grey and alpha (2) as grey; alpha over white.
        const bool grey = channels < 3, alpha = channels == 2 || channels == 4;
        for (size_t i = 0; i < size_t(out.width) * size_t(out.height); ++i) {
            const float* p = &pixels[i * size_t(channels)];
            const float a = alpha ? std::clamp(p[channels - 1], 0.0f, 1.0f) : 1.0f;
            for (int c = 0; c < 3; ++c) {
                const float v = std::clamp(p[grey ? 0 : c], 0.0f, 1.0f) * a + (1.0f - a);
                out.rgb[i * 3 + size_t(c)] = (unsigned char)std::lround(255.0f * v);
            }
        }
        return out;
    } catch (const InputError& e) {
        warnings.push_back(oneLine(e.what()) + "; the picture is left out");
        return std::nullopt;
    }
}

}  // namespace candela
