// Light-field manifests: loading (with every check that keeps a malformed file from reaching
// the estimators), validation and saving. The model and its estimators are in LightField.cpp.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "luminaires/lightfield/LightField.h"
#include "util/Error.h"
#include "util/FileInput.h"
#include "util/FileOutput.h"
#include "util/ImageRead.h"
#include "util/JsonRead.h"

namespace candela {

namespace fs = std::filesystem;

namespace {

constexpr int kMaxImages = 4096;     // 64 x 64 basis functions
constexpr int kMaxImageSide = 8192;  // pixels
constexpr double kLumR = 0.2126, kLumG = 0.7152, kLumB = 0.0722;

std::string fmt(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}

void readImage(const fs::path& file, const std::string& where, int& w, int& h, int& channels,
               std::vector<float>& pixels) {
    ImageFileReader in(file.string(), where + ": " + file.string(),
                       kMaxImageSide);  // util/ImageRead.h
    w = in.width();
    h = in.height();
    channels = in.channels();
    if (w <= 0 || h <= 0 || w > kMaxImageSide || h > kMaxImageSide)
        throw InputError(where + ": " + file.string() + ": image size " + std::to_string(w) + "x" +
                         std::to_string(h) + " out of range (1.." + std::to_string(kMaxImageSide) +
                         ")");
    if (channels != 1 && channels != 3 && channels != 4)
        throw InputError(where + ": " + file.string() + ": " + std::to_string(channels) +
                         " channels; expected 1 (luminance), 3 (RGB) or 4 (RGBA)");
    std::unique_ptr<float[]> decoded = in.readPixels(channels);
    pixels.assign(decoded.get(), decoded.get() + size_t(w) * size_t(h) * size_t(channels));
}

std::string modelName(LightFieldData::Model m) {
    return m == LightFieldData::Model::Goesele ? "goesele" : "canned";
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Loading, validation, saving

void LightFieldData::validate(const std::string& what) const {
    auto bad = [&](const std::string& msg) { throw InputError(what + ": " + msg); };
    if (!(delta > 0.0) || !std::isfinite(delta))
        bad("delta must be a positive distance in metres, got " + fmt(delta));
    if (count.x < 1 || count.y < 1 || count.x * count.y > kMaxImages)
        bad("basis count must be at least 1x1 and at most " + std::to_string(kMaxImages) +
            " images");
    if (!(spacing.x > 0.0 && spacing.y > 0.0) || !std::isfinite(spacing.x) ||
        !std::isfinite(spacing.y))
        bad("basis spacing must be positive, got [" + fmt(spacing.x) + ", " + fmt(spacing.y) + "]");
    if (!std::isfinite(origin.x) || !std::isfinite(origin.y)) bad("basis origin must be finite");
    if (!(imageMax.x > imageMin.x && imageMax.y > imageMin.y) || !std::isfinite(imageMin.x) ||
        !std::isfinite(imageMin.y) || !std::isfinite(imageMax.x) || !std::isfinite(imageMax.y))
        bad("image extent must have max > min on both axes");
    if (int(images.size()) != imageCount())
        bad("basis count " + std::to_string(count.x) + "x" + std::to_string(count.y) + " needs " +
            std::to_string(imageCount()) + " images, found " + std::to_string(images.size()));
    if (width < 1 || height < 1) bad("images must have at least one pixel");
    size_t pixels = size_t(width) * size_t(height);
    for (size_t m = 0; m < images.size(); ++m) {
        const LightFieldImage& img = images[m];
        if (img.luminance.size() != pixels || (rgb && img.colour.size() != pixels))
            bad("image " + std::to_string(m) + " has the wrong number of pixels");
        for (size_t k = 0; k < pixels; ++k)
            if (!(img.luminance[k] >= 0.f) || !std::isfinite(img.luminance[k]))
                bad("image " + std::to_string(m) + " pixel (" + std::to_string(k % size_t(width)) +
                    ", " + std::to_string(k / size_t(width)) + ") is negative, NaN or infinite");
    }
}

namespace {

/// The light-field file's JSON document; InputError when it cannot be read or is not JSON.
nlohmann::json readJsonFile(const fs::path& file) {
    std::string text = readInputFile(file.string(), "light-field", kMaxTextBytes);
    nlohmann::json doc;
    try {
        doc = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        throw InputError(file.string() + ": invalid JSON (" + e.what() + ")");
    }
    return doc;
}

/// The top-level keys, format and version, then the model and delta.
void readHeader(const nlohmann::json& doc, const json::Where& where, LightFieldData& lf) {
    using Model = LightFieldData::Model;
    json::checkKeys(
        doc, {"format", "version", "model", "delta", "basis", "image", "images", "unit"}, where);
    if (json::optional(doc, "format", where, std::string(), json::string) != "candela-lightfield")
        json::fail(where / "format", "\"candela-lightfield\"");
    if (!doc.contains("version") || !doc["version"].is_number_integer() || doc["version"] != 1)
        json::fail(where / "version", "1");
    std::string model = json::optional(doc, "model", where, std::string("canned"), json::string);
    if (model == "canned")
        lf.model = Model::Canned;
    else if (model == "goesele")
        lf.model = Model::Goesele;
    else
        json::fail(where / "model", "\"canned\" or \"goesele\"");
    if (!doc.contains("delta")) json::fail(where / "delta", "a positive distance in metres");
    lf.delta = json::positive(doc["delta"], where / "delta");
}

/// "basis": the B-spline nodes' count, spacing and origin on U.
void readBasis(const nlohmann::json& doc, const json::Where& where, LightFieldData& lf) {
    if (!doc.contains("basis")) json::fail(where / "basis", "an object");
    const auto& basis = doc["basis"];
    json::Where wb = where / "basis";
    json::checkKeys(basis, {"kind", "count", "spacing", "origin"}, wb);
    if (json::optional(basis, "kind", wb, std::string("bspline2"), json::string) != "bspline2")
        json::fail(wb / "kind", "\"bspline2\"");
    auto readCount = [](const nlohmann::json& v, const json::Where& w) {
        if (!v.is_array() || v.size() != 2 || !v[0].is_number_integer() ||
            !v[1].is_number_integer() || v[0].get<long>() < 1 || v[1].get<long>() < 1 ||
            v[0].get<long>() > 64 || v[1].get<long>() > 64)
            json::fail(w, "two integers between 1 and 64");
        return glm::ivec2(v[0].get<int>(), v[1].get<int>());
    };
    if (!basis.contains("count")) json::fail(wb / "count", "[W, H]");
    lf.count = readCount(basis["count"], wb / "count");
    if (!basis.contains("spacing")) json::fail(wb / "spacing", "[hx, hy] in metres");
    lf.spacing = json::vec2(basis["spacing"], wb / "spacing");
    if (!(lf.spacing.x > 0.0 && lf.spacing.y > 0.0))
        json::fail(wb / "spacing", "positive spacings");
    lf.origin = json::optional(basis, "origin", wb, glm::dvec2(0.0), json::vec2);
}

/// "image": the images' extent on S; then "unit".
void readExtentAndUnit(const nlohmann::json& doc, const json::Where& where, LightFieldData& lf) {
    if (!doc.contains("image")) json::fail(where / "image", "an object with min and max");
    json::Where wi = where / "image";
    json::checkKeys(doc["image"], {"min", "max"}, wi);
    if (!doc["image"].contains("min") || !doc["image"].contains("max"))
        json::fail(wi, "min and max");
    lf.imageMin = json::vec2(doc["image"]["min"], wi / "min");
    lf.imageMax = json::vec2(doc["image"]["max"], wi / "max");
    if (!(lf.imageMax.x > lf.imageMin.x && lf.imageMax.y > lf.imageMin.y))
        json::fail(wi, "max greater than min on both axes");

    std::string unit = json::optional(doc, "unit", where, std::string("W/(m2 sr)"), json::string);
    if (unit != "W/(m2 sr)" && unit != "cd/m2")
        json::fail(where / "unit", "\"W/(m2 sr)\" or \"cd/m2\"");
    lf.unit = unit;
}

/// One image's decoded pixels (`channels` per pixel) as luminance and, when `rgb`, colour
/// ratios; InputError naming `file` and `imgPath` on a negative, NaN or infinite value.
void convertPixels(const std::vector<float>& px, int w, int h, int channels, bool rgb,
                   LightFieldImage& img, const fs::path& file, const fs::path& imgPath) {
    size_t n = size_t(w) * size_t(h);
    img.luminance.resize(n);
    if (rgb) img.colour.resize(n);
    for (size_t k = 0; k < n; ++k) {
        const float* v = &px[k * size_t(channels)];
        for (int c = 0; c < std::min(channels, 3); ++c)
            if (!(v[c] >= 0.f) || !std::isfinite(v[c]))
                throw InputError(file.string() + ": " + imgPath.string() + ": pixel (" +
                                 std::to_string(k % size_t(w)) + ", " +
                                 std::to_string(k / size_t(w)) + ") is negative, NaN or infinite");
        if (!rgb) {
            img.luminance[k] = v[0];
            continue;
        }
        double y = kLumR * v[0] + kLumG * v[1] + kLumB * v[2];
        img.luminance[k] = float(y);
        img.colour[k] =
            y > 0.0 ? glm::vec3(float(v[0] / y), float(v[1] / y), float(v[2] / y)) : glm::vec3(1.f);
    }
}

/// "images": one file per basis function (relative to `file`'s folder), all of one size and
/// kind (luminance or RGB).
void readImages(const nlohmann::json& doc, const json::Where& where, const fs::path& file,
                LightFieldData& lf) {
    if (!doc.contains("images") || !doc["images"].is_array())
        json::fail(where / "images", "an array of image file names");
    const auto& names = doc["images"];
    if (int(names.size()) != lf.imageCount())
        json::fail(where / "images", std::to_string(lf.imageCount()) + " file names (count " +
                                         std::to_string(lf.count.x) + "x" +
                                         std::to_string(lf.count.y) + "), found " +
                                         std::to_string(names.size()));
    fs::path dir = file.parent_path();
    lf.images.resize(names.size());
    for (size_t m = 0; m < names.size(); ++m) {
        std::string name = json::string(names[m], (where / "images")[m]);
        fs::path imgPath = fs::path(name).is_relative() ? dir / name : fs::path(name);
        lf.imageFiles.push_back(imgPath);
        int w = 0, h = 0, channels = 0;
        std::vector<float> px;
        readImage(imgPath, file.string(), w, h, channels, px);
        if (m == 0) {
            lf.width = w;
            lf.height = h;
            lf.rgb = channels >= 3;
        } else if (w != lf.width || h != lf.height) {
            throw InputError(file.string() + ": " + imgPath.string() + ": image is " +
                             std::to_string(w) + "x" + std::to_string(h) +
                             " but the first image is " + std::to_string(lf.width) + "x" +
                             std::to_string(lf.height) + " (all images must match)");
        } else if ((channels >= 3) != lf.rgb) {
            throw InputError(file.string() + ": " + imgPath.string() +
                             ": mixes luminance and RGB images");
        }
        convertPixels(px, w, h, channels, lf.rgb, lf.images[m], file, imgPath);
    }
}

}  // namespace

std::shared_ptr<LightFieldData> LightFieldData::load(const fs::path& file) {
    nlohmann::json doc = readJsonFile(file);
    json::Where where{file.string(), ""};
    auto lf = std::make_shared<LightFieldData>();
    lf->path = file;
    readHeader(doc, where, *lf);
    readBasis(doc, where, *lf);
    readExtentAndUnit(doc, where, *lf);
    readImages(doc, where, file, *lf);
    lf->validate(file.string());
    lf->precompute();
    return lf;
}

void LightFieldData::save(const fs::path& file) const {
    validate(file.string());
    fs::path dir = file.parent_path().empty() ? fs::path(".") : file.parent_path();
    std::string stem = file.filename().string();
    const std::string suffix = ".lf.json";
    if (stem.size() > suffix.size() &&
        stem.compare(stem.size() - suffix.size(), suffix.size(), suffix) == 0)
        stem = stem.substr(0, stem.size() - suffix.size());
    else
        throw InputError(file.string() + ": light-field files must be named NAME.lf.json");
    nlohmann::json names = nlohmann::json::array();
    for (int j = 0; j < count.y; ++j)
        for (int i = 0; i < count.x; ++i)
            names.push_back(stem + "_" + std::to_string(i) + "_" + std::to_string(j) + ".exr");
    // Every file is checked before the first is written, so a refusal leaves nothing behind;
    // all are written to temporary files before any is renamed, so a failed write (a full
    // disk) replaces none of them.
    checkNotAnInput(file.string());
    for (const auto& name : names) checkNotAnInput((dir / name.get<std::string>()).string());
    AtomicFileSet files;
    int channels = rgb ? 3 : 1;
    for (int j = 0; j < count.y; ++j)
        for (int i = 0; i < count.x; ++i) {
            int m = j * count.x + i;
            fs::path target = dir / names[size_t(m)].get<std::string>();
            std::vector<float> px(size_t(width) * size_t(height) * size_t(channels));
            const LightFieldImage& img = images[size_t(m)];
            for (size_t k = 0; k < img.luminance.size(); ++k) {
                if (!rgb) {
                    px[k] = img.luminance[k];
                    continue;
                }
                glm::vec3 c = img.colour[k] * img.luminance[k];
                px[3 * k] = c.x;
                px[3 * k + 1] = c.y;
                px[3 * k + 2] = c.z;
            }
            files.add(target.string(),
                      encodeImage(target.string(), width, height, channels, px.data(), "zip"),
                      "cannot write the image");
        }
    nlohmann::json doc = {
        {"format", "candela-lightfield"},
        {"version", 1},
        {"model", modelName(model)},
        {"delta", delta},
        {"basis",
         {{"kind", "bspline2"},
          {"count", {count.x, count.y}},
          {"spacing", {spacing.x, spacing.y}},
          {"origin", {origin.x, origin.y}}}},
        {"image", {{"min", {imageMin.x, imageMin.y}}, {"max", {imageMax.x, imageMax.y}}}},
        {"images", names},
        {"unit", unit}};
    files.add(file.string(), doc.dump(2) + "\n");
    files.commit();
}

}  // namespace candela
