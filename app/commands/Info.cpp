#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/commands/Commands.h"
#include "calculation/Plausibility.h"
#include "calculation/UgrTable.h"
#include "formats/Gldf.h"
#include "formats/L3d.h"
#include "luminaires/Registry.h"
#include "luminaires/lightfield/LightField.h"
#include "luminaires/photometric/PhotometricLuminaire.h"
#include "scene/GltfLoader.h"
#include "scene/SceneIo.h"
#include "util/Error.h"
#include "util/TextEncoding.h"

namespace candela {

static const char* symmetryName(PhotometricSymmetry s) {
    switch (s) {
        case PhotometricSymmetry::None:
            return "none";
        case PhotometricSymmetry::Axial:
            return "rotational (one C plane)";
        case PhotometricSymmetry::Quadrant:
            return "quadrants (C0-C90 mirrored)";
        case PhotometricSymmetry::PlaneC0C180:
            return "mirror about the C0-C180 plane";
        case PhotometricSymmetry::PlaneC90C270:
            return "mirror about the C90-C270 plane";
    }
    return "?";
}

/// `candela info FILE.ies|FILE.ldt|FILE.xml`: what the file holds, its flux two ways and what was
/// assumed to read it (one "warning:" line each; --strict refuses the file instead), and where its
/// own figures disagree (calculation/Plausibility.h, one "warning:" line each).

/// The light output ratio as designers read it: the luminaire's flux (the table's) over the
/// lamps' rated flux.
static void printLightOutputRatio(const PhotometricData& d, double flux) {
    if (!(d.lampFlux > 0.0)) return;  // absolute photometry: no lamp flux, no ratio
    char said[64] = "";
    if (d.declaresLightOutputRatio)
        std::snprintf(said, sizeof said, "; the file declares %.4g %%", 100.0 * d.lightOutputRatio);
    std::printf("light output ratio (luminaire flux / lamp flux): %.1f %% (%.6g lm / %.6g lm%s)\n",
                100.0 * flux / d.lampFlux, flux, d.lampFlux, said);
}

/// EULUMDAT's declared luminaire flux (lamp flux x LORL) against the table's.
static void printDeclaredFlux(const PhotometricData& d, double flux) {
    double declared = d.declaredFlux();
    if (declared > 0.0)
        std::printf(
            "lamp flux %.6g lm x light output ratio %.4g = %.6g lm (table / declared %.4f)\n",
            d.lampFlux, d.lightOutputRatio, declared, flux / declared);
    else if (d.lampFlux > 0.0)
        std::printf(
            "lamp flux %.6g lm, light output ratio 0: no declared luminaire flux to compare\n",
            d.lampFlux);
    else
        std::printf("absolute photometry: no lamp flux declared\n");
}

/// The UGR reference values a datasheet gives: the CIE 190 table's 4H x 8H room at reflectances
/// 70/50/20 (calculation/UgrTable.h; `candela glare --table` prints the whole table), or why there
/// are none.
static void printUgrReference(const PhotometricData& d) {
    try {
        UgrTable t = computeUgrTable(d);
        auto shown = [](double ugr) {
            char s[16] = "-";  // no light towards the eye: no glare to rate
            if (std::isfinite(ugr)) std::snprintf(s, sizeof s, "%.1f", ugr);
            return std::string(s);
        };
        for (const UgrRoomResult& r : t.rooms)
            if (r.size.x == 4 && r.size.y == 8)
                std::printf(
                    "UGR reference (CIE 190 table, room 4H x 8H, reflectances 70/50/20 %%, "
                    "luminaires every %.4g H): %s crosswise, %s endwise at %.6g lm\n",
                    t.options.spacing, shown(r.crosswise[0]).c_str(), shown(r.endwise[0]).c_str(),
                    t.flux);
    } catch (const InputError& e) {
        std::printf("UGR reference: none (%s)\n", e.what());
    }
}

/// The photometry's description; `path` names it ("lamp.ldt", "lamp.gldf:ldc/lamp.ldt").
/// `rated`: the GLDF light emitter whose photometry it is, or null.
static void printPhotometry(const std::string& path, std::shared_ptr<const PhotometricData> data,
                            const GldfLightEmitter* rated = nullptr) {
    auto light = std::make_unique<PhotometricLuminaire>();
    light->file = path;
    light->data = std::move(data);
    light->updateOpening();
    const PhotometricData& d = *light->data;
    std::printf("photometry: %s\n", toValidUtf8(path).c_str());
    std::printf("format: %s, type %s goniometry, symmetry: %s\n", d.format.c_str(),
                d.goniometer == Goniometer::B ? "B" : "C", symmetryName(d.symmetry));
    if (!d.name.empty()) std::printf("luminaire: %s\n", d.name.c_str());
    std::printf(
        "angles: %zu vertical (%.4g..%.4g deg) x %zu horizontal (%.4g..%.4g deg, unfolded)\n",
        d.vertical.size(), d.vertical.front(), d.vertical.back(), d.horizontal.size(),
        d.horizontal.front(), d.horizontal.back());
    std::printf("max intensity: %.6g cd\n", d.maxIntensity());
    std::printf(
        "opening: %.4g m along C0-C180 x %.4g m along C90-C270 x %.4g m high, emitting "
        "polygon %.4g m2%s\n",
        d.opening.length, d.opening.width, d.opening.height, light->area(),
        light->polygon().empty() ? " (a point source)" : "");
    double flux = d.fluxFromTable();
    std::printf("luminaire flux (exact quadrature of the table): %.6g lm\n", flux);
    printLightOutputRatio(d, flux);
    // IES declares no LOR to multiply by: the ratio above is all there is to say.
    if (d.declaresLightOutputRatio) printDeclaredFlux(d, flux);
    if (d.statedFlux > 0.0)
        std::printf("luminous flux the file states: %.6g lm (table / stated %.4f)\n", d.statedFlux,
                    flux / d.statedFlux);
    if (d.inputWatts > 0.0 && std::isfinite(flux / d.inputWatts))
        std::printf("input power: %.4g W (%.1f lm/W)\n", d.inputWatts, flux / d.inputWatts);
    printUgrReference(d);
    for (const std::string& w : d.warnings) std::printf("warning: %s\n", w.c_str());
    for (const std::string& w : plausibilityNotes(path, d, rated))
        std::printf("warning: %s\n", w.c_str());
}

static void printMaintenance(const char* indent, const std::vector<GldfMaintenance>& factors) {
    for (const GldfMaintenance& m : factors)
        std::printf("%s%s: %.4g (%.1f %%)\n", indent, m.what.c_str(), m.factor, 100.0 * m.factor);
}

/// One emitter of a variant: each interchangeable light emitter's photometry and ratings.
static void printGldfEmitter(const GldfProduct& product, const GldfEmitter& emitter) {
    std::printf("  emitter \"%s\": %zu light emitter(s)%s%s\n", emitter.id.c_str(),
                emitter.lights.size(),
                emitter.lights.size() > 1 ? " (interchangeable; the first is placed)" : "",
                emitter.sensors > 0 ? ", and sensors (skipped: a sensor gives no light)" : "");
    for (const GldfLightEmitter& light : emitter.lights) {
        const GldfFile* file = product.file(light.fileId);
        std::string where = !file ? "no file" : file->url ? "URL " + file->name : file->member();
        std::printf("    %s light emitter, photometry \"%s\": %s\n",
                    light.fixed ? "fixed" : "changeable", light.photometryId.c_str(),
                    where.c_str());
        if (light.rotated())
            std::printf("      rotation: X %g deg, Y %g deg, Z %g deg, G0 %g deg %s\n",
                        light.rotationXyz.x, light.rotationXyz.y, light.rotationXyz.z,
                        light.rotationG0,
                        &light != &emitter.lights.front()
                            ? "(not placed)"
                            : "(applied: G0 about the photometric axis, C0 towards C90, then "
                              "Rz Rx Ry about the luminaire's axes, right-handed; the schema "
                              "does not state the senses)");
        if (light.ratedFlux >= 0.0)
            std::printf("      rated luminous flux: %.6g lm%s\n", light.ratedFlux,
                        light.lightSourceCount > 1 ? " (all its light sources)" : "");
        if (light.ratedPower >= 0.0)
            std::printf("      rated input power: %.6g W\n", light.ratedPower);
        if (light.ratedFlux >= 0.0 && light.ratedPower > 0.0)
            std::printf("      luminous efficacy (rated flux / rated power): %.4g lm/W\n",
                        light.ratedFlux / light.ratedPower);
        if (!light.maintenance.empty())
            std::printf("      light source maintenance (light source \"%s\"):\n",
                        light.lightSourceId.c_str());
        printMaintenance("        ", light.maintenance);
    }
}

/// `v` rounded to 6 decimals without a sign on zero (so a direction prints as (0.000, 0.000,
/// -1.000)).
static double tidy(double v) {
    return std::round(v * 1e6) / 1e6 + 0.0;
}

/// An L3D geometry: its parts, size and luminous openings (luminaire frame: +z up, metres).
static void printL3d(const L3dLuminaire& l, const char* indent) {
    glm::dvec3 lo, hi;
    l.bounds(lo, hi);
    std::printf("%sgeometry: %s%s%s\n", indent, toValidUtf8(l.path).c_str(),
                l.name.empty() ? "" : ", ", l.name.c_str());
    std::printf("%s  %zu part(s), %d joint(s) (shown at their default rotation), %zu triangles\n",
                indent, l.parts.size(), l.joints, l.triangleCount());
    std::printf(
        "%s  size %.4g x %.4g x %.4g m (x, y, z up), from (%.4g, %.4g, %.4g) m to "
        "(%.4g, %.4g, %.4g) m of the insertion point\n",
        indent, hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, lo.x, lo.y, lo.z, hi.x, hi.y, hi.z);
    for (const L3dEmitter& e : l.emitters) {
        char shape[96];
        if (e.shape == L3dEmitter::Shape::Circle)
            std::snprintf(shape, sizeof shape, "circle %.4g m across", e.sizeX);
        else
            std::snprintf(shape, sizeof shape, "rectangle %.4g x %.4g m", e.sizeX, e.sizeY);
        std::printf(
            "%s  light-emitting object \"%s\" (part \"%s\"): %s, %.4g m2, centre "
            "(%.4g, %.4g, %.4g) m, emitting towards (%.3f, %.3f, %.3f), %zu triangles "
            "assigned\n",
            indent, e.name.c_str(), e.part.c_str(), shape, e.area(), e.centre.x, e.centre.y,
            e.centre.z, tidy(e.normal.x), tidy(e.normal.y), tidy(e.normal.z), e.triangles.size());
    }
}

/// `candela info LAMP.gldf`: the product, each variant with its emitters, and the photometry of
/// each variant that can be placed (or why it cannot).
static void printGldf(const std::string& path) {
    std::string bytes = readGldfBytes(path);
    GldfProduct product = parseGldf(bytes, path);
    std::printf("GLDF container: %s\n", toValidUtf8(path).c_str());
    std::printf("manufacturer: %s\n", product.manufacturer.c_str());
    if (!product.author.empty()) std::printf("author: %s\n", product.author.c_str());
    std::printf("format version: %s, created %s with %s\n", product.formatVersion.c_str(),
                product.creationTime.c_str(), product.createdWithApplication.c_str());
    std::printf("product: %s (product number %s, unique id %s)\n", product.productName.c_str(),
                product.productNumber.c_str(), product.uniqueProductId.c_str());
    if (!product.description.empty()) std::printf("description: %s\n", product.description.c_str());
    if (!product.luminaireMaintenance.empty()) std::printf("luminaire maintenance:\n");
    printMaintenance("  ", product.luminaireMaintenance);
    std::printf("files: %zu listed, %zu members in the container\n", product.files.size(),
                product.members.size());
    for (const std::string& w : product.warnings) std::printf("warning: %s\n", w.c_str());
    std::printf("variants: %zu\n", product.variants.size());
    for (const GldfVariant& variant : product.variants) {
        std::printf("variant \"%s\": %s\n", variant.id.c_str(), variant.name.c_str());
        if (!variant.assumedEmitter.empty())
            std::printf(
                "  its <Geometry> names no emitter: the product's only light emitter, "
                "\"%s\", is placed\n",
                variant.assumedEmitter.c_str());
        for (const std::string& id : variant.sensorEmitters)
            std::printf("  sensor emitter \"%s\": skipped (a sensor gives no light)\n", id.c_str());
        std::vector<std::string> shown;
        for (const std::string& id : variant.emitters) {
            if (std::find(shown.begin(), shown.end(), id) != shown.end()) continue;
            shown.push_back(id);
            printGldfEmitter(product, *product.emitter(id));
        }
        std::vector<std::string> printed;  // photometry members already described
        for (size_t k = 0; k < std::max<size_t>(variant.emitters.size(), 1); ++k) {
            try {
                GldfPhotometry photometry =
                    gldfVariantPhotometry(bytes, product, variant, defaultPhotometryOptions(), k);
                if (photometry.geometry && k == 0) printL3d(*photometry.geometry, "  ");
                if (variant.emitters.size() > 1)
                    std::printf("  placement %zu of %zu: emitter \"%s\"\n", k,
                                variant.emitters.size(), photometry.emitter->id.c_str());
                if (photometry.opening)
                    std::printf(
                        "  the emitter is placed at light-emitting object \"%s\": its "
                        "opening replaces the photometry's\n",
                        photometry.opening->name.c_str());
                std::string name = photometry.data.path;
                if (std::find(printed.begin(), printed.end(), name) != printed.end()) {
                    std::printf("  photometry: %s, as above\n", toValidUtf8(name).c_str());
                    continue;
                }
                printed.push_back(name);
                const GldfLightEmitter* rated =
                    photometry.emitter && !photometry.emitter->lights.empty()
                        ? &photometry.emitter->lights.front()
                        : nullptr;
                printPhotometry(name,
                                std::make_shared<const PhotometricData>(std::move(photometry.data)),
                                rated);
            } catch (const InputError& e) {
                std::printf("  cannot be placed: %s\n", e.what());
                break;
            }
        }
    }
}

/// `candela info NAME.lf.json`: the light field's model, basis, images, flux and table cost.
static void printLightField(const std::string& path) {
    auto start = std::chrono::steady_clock::now();
    std::shared_ptr<LightFieldData> lf = LightFieldData::load(path);
    double loadMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const LightFieldData& d = *lf;
    std::printf("light field: %s\n", path.c_str());
    std::printf("model: %s, delta %.4g mm (U at local z = 0, S at z = delta)\n",
                d.model == LightFieldData::Model::Canned ? "canned" : "goesele", d.delta * 1e3);
    glm::dvec2 last = d.node(d.imageCount() - 1);
    std::printf(
        "basis: quadratic B-splines, %dx%d, spacing %.4g x %.4g mm, nodes [%.4g, %.4g] x [%.4g, "
        "%.4g] mm\n",
        d.count.x, d.count.y, d.spacing.x * 1e3, d.spacing.y * 1e3, d.origin.x * 1e3, last.x * 1e3,
        d.origin.y * 1e3, last.y * 1e3);
    std::printf(
        "images: %d of %dx%d pixels, %s, over [%.4g, %.4g] x [%.4g, %.4g] mm on S, unit %s\n",
        d.imageCount(), d.width, d.height, d.rgb ? "RGB" : "luminance", d.imageMin.x * 1e3,
        d.imageMax.x * 1e3, d.imageMin.y * 1e3, d.imageMax.y * 1e3, d.unit.c_str());
    glm::dvec3 power = d.power();
    bool photometric = d.unit == "cd/m2";
    const char* unit = photometric ? "lm" : "W";
    if (d.rgb)
        std::printf("flux (quadrature of L cos cos / r^2 over U x S): R %.6g, G %.6g, B %.6g %s\n",
                    power.x, power.y, power.z, unit);
    else
        std::printf("flux (quadrature of L cos cos / r^2 over U x S): %.6g %s\n", power.y, unit);
    std::printf(
        "load %.0f ms, of which precomputation (summed-area tables, CDFs, medians) %.1f ms\n",
        loadMs, d.precomputeMs);
}

static void printMeshes(const Scene& scene) {
    size_t triangles = 0;
    for (const Mesh& m : scene.meshes) triangles += m.triangleCount();
    std::printf("meshes: %zu (%zu triangles), materials: %zu\n", scene.meshes.size(), triangles,
                scene.materials.size());
    for (const Mesh& m : scene.meshes) {
        const Material& mat = scene.materials.at(m.material);
        std::printf("  mesh \"%s\": %zu triangles, material \"%s\" albedo (%.3g, %.3g, %.3g)%s\n",
                    m.name.c_str(), m.triangleCount(), mat.name.c_str(), mat.albedo.x, mat.albedo.y,
                    mat.albedo.z, mat.isGlossy() ? ", glossy" : "");
    }
    glm::vec3 lo = scene.boundsMin(), hi = scene.boundsMax();
    std::printf("bounds: (%.3f, %.3f, %.3f) .. (%.3f, %.3f, %.3f) m\n", lo.x, lo.y, lo.z, hi.x,
                hi.y, hi.z);
}

int cmdInfo(const Args& args) {
    std::string path;
    CommandLine cli("info");
    cli.argument("FILE", path,
                 "the file to describe: a scene (.json), light field (.lf.json), glTF file (.gltf, "
                 ".glb), photometry "
                 "(.ies, .ldt, TM-33 .xml or .iesxml), GLDF container (.gldf), or L3D geometry "
                 "(.l3d or an unpacked L3D folder)");
    cli.strictPhotometry();
    if (!cli.parse(args)) return 0;
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower((unsigned char)c));
    if (isPhotometryExtension(ext)) {
        printPhotometry(path, PhotometricLuminaire::load(path));
        return 0;
    }
    if (ext == ".gldf") {
        printGldf(path);
        return 0;
    }
    if (ext == ".l3d" || std::filesystem::is_directory(path)) {
        printL3d(loadL3d(path), "");
        return 0;
    }
    std::string name = std::filesystem::path(path).filename().string();
    if (name.size() > 8 && name.compare(name.size() - 8, 8, ".lf.json") == 0) {
        printLightField(path);
        return 0;
    }
    if (ext == ".json") {
        Scene scene = loadScene(path);
        std::printf("scene: %s\n", path.c_str());
        std::printf("geometry entries: %zu\n", scene.geometry.size());
        printMeshes(scene);
        std::printf("luminaires: %zu\n", scene.luminaires.size());
        for (const auto& l : scene.luminaires) {
            const TechniqueInfo* t = findTechnique(l->kind(), l->technique);
            glm::dvec3 p = l->pose.position;
            std::printf("  \"%s\": %s\n    at (%.3f, %.3f, %.3f) m, technique %s (%s)\n",
                        l->name.c_str(), describe(*l).c_str(), p.x, p.y, p.z, l->technique.c_str(),
                        t ? std::string(t->description).c_str() : "?");
            const PhotometricLuminaire* photometric = photometricModel(*l);
            if (photometric && photometric->data && !photometric->data->warnings.empty())
                std::printf("    %zu warning(s) reading %s (candela info lists them)\n",
                            photometric->data->warnings.size(),
                            toValidUtf8(photometric->file).c_str());
        }
        std::printf("environment: %s\n",
                    scene.environment.is_null() ? "none" : scene.environment.dump().c_str());
        UnitSystem units = scene.units();
        std::printf("units: %s (%s)%s%s\n", units.photometric ? "photometric" : "radiometric",
                    units.photometric ? "lm, cd, cd/m2, lx" : "W, W/sr, W/(m2 sr), W/m2",
                    units.converted ? "; " : "", units.note().c_str());
        std::printf("%s\n", scene.maintenanceNote().c_str());
        const Camera& c = scene.camera;
        std::printf(
            "camera: at (%.3f, %.3f, %.3f) m looking at (%.3f, %.3f, %.3f) m, fov %.1f deg\n",
            c.position.x, c.position.y, c.position.z, c.target.x, c.target.y, c.target.z, c.fovDeg);
        return 0;
    }
    if (ext == ".gltf" || ext == ".glb") {
        Scene scene;
        loadGltf(path, glm::dmat4(1.0), scene, json::Where{path, ""});
        std::printf("glTF: %s\n", path.c_str());
        printMeshes(scene);
        return 0;
    }
    throw InputError(
        path + ": unsupported file type \"" + ext +
        "\" (expected .json, .lf.json, .gltf, .glb, .ies, .ldt, .xml, .iesxml, .gldf, .l3d or a "
        "folder "
        "holding structure.xml)");
}

}  // namespace candela
