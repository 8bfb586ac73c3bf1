#include "formats/Gldf.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <pugixml.hpp>
#include <set>

#include "util/Error.h"
#include "util/FileInput.h"
#include "util/TextEncoding.h"
#include "util/ZipArchive.h"

namespace candela {

namespace {

namespace fs = std::filesystem;

/// The content types the schema allows (GeneralDefinitions/Files/File/@contentType).
const char* const kContentTypes[] = {
    "ldc/eulumdat",   "ldc/ies",        "ldc/iesxml",    "image/png",    "image/svg",  "image/jpg",
    "geo/l3d",        "geo/r3d",        "geo/m3d",       "document/pdf", "symbol/dxf", "symbol/svg",
    "sensor/sensxml", "sensor/sensldt", "spectrum/text", "other"};

/// How many of a folder's members a "not in the container" message names (one line stays short).
constexpr int kMembersNamed = 5;

/// Throws the message as one line of valid UTF-8 (container paths, member names and values
/// quoted from product.xml may hold anything).
[[noreturn]] void fail(const std::string& message) {
    throw InputError(oneLine(message));
}

std::string inQuotes(const std::string& s) {
    return "\"" + s + "\"";
}

/// Reads product.xml's elements; every message names the container and product.xml.
class ProductReader {
  public:
    explicit ProductReader(GldfProduct& product) : mProduct(product) {}

    [[noreturn]] void defect(const std::string& what) const {
        fail(mProduct.path + ": product.xml: " + what);
    }

    /// Text content, whitespace trimmed, one line of valid UTF-8 (a name wrapped over lines in
    /// the file is shown on one).
    static std::string text(const pugi::xml_node& node) {
        std::string s = oneLine(node.text().get());
        std::string_view v = s;
        size_t begin = v.find_first_not_of(' ');
        if (begin == std::string_view::npos) return "";
        return std::string(v.substr(begin, v.find_last_not_of(' ') - begin + 1));
    }

    /// `s` as a number, or `fallback` when it is not one (a label, not a value that must be).
    static double numberOr(const std::string& s, double fallback) {
        double v = 0.0;
        return photometry_detail::parseNumber(s, v) && std::isfinite(v) ? v : fallback;
    }

    static std::string attribute(const pugi::xml_node& node, const char* name) {
        return oneLine(node.attribute(name).value());
    }

    /// A Locale-typed element: the English text where there is one, else the first.
    static std::string locale(const pugi::xml_node& node) {
        pugi::xml_node first = node.child("Locale");
        for (pugi::xml_node l : node.children("Locale"))
            if (std::string(l.attribute("language").value()) == "en") return text(l);
        return first ? text(first) : "";
    }

    /// An optional number in [lo, hi]; `fallback` when the element is absent.
    double number(const pugi::xml_node& parent, const char* name, const std::string& owner,
                  double lo, double hi, double fallback = -1.0) const {
        pugi::xml_node node = parent.child(name);
        if (!node) return fallback;
        return numberOf(text(node), std::string("<") + name + "> of " + owner, lo, hi);
    }

    double numberOf(const std::string& s, const std::string& what, double lo, double hi) const {
        double v = 0.0;
        if (!photometry_detail::parseNumber(s, v))
            defect(what + ": expected a number, found " + inQuotes(s));
        if (!(v >= lo && v <= hi))
            defect(what + ": " + s + " is outside [" + photometry_detail::formatNumber(lo) + ", " +
                   photometry_detail::formatNumber(hi) + "]");
        return v;
    }

    std::string id(const pugi::xml_node& node, const char* attributeName = "id") const {
        std::string value = attribute(node, attributeName);
        if (value.empty())
            defect(std::string("a <") + node.name() + "> without its " + attributeName +
                   " attribute");
        return value;
    }

    void header(const pugi::xml_node& header) {
        if (!header) defect("no <Header> (the schema requires one)");
        mProduct.manufacturer = text(header.child("Manufacturer"));
        mProduct.author = text(header.child("Author"));
        mProduct.createdWithApplication = text(header.child("CreatedWithApplication"));
        mProduct.creationTime = text(header.child("GldfCreationTimeCode"));
        if (pugi::xml_node v = header.child("FormatVersion")) {
            mProduct.formatVersion = attribute(v, "major") + "." + attribute(v, "minor");
            if (std::string pre = attribute(v, "pre-release"); !pre.empty())
                mProduct.formatVersion += " (pre-release " + pre + ")";
        }
    }

    void files(const pugi::xml_node& files) {
        for (pugi::xml_node f : files.children("File")) {
            GldfFile file;
            file.id = id(f);
            if (mProduct.file(file.id))
                defect("two <File> elements with the id " + inQuotes(file.id));
            file.contentType = attribute(f, "contentType");
            // An unknown content type matters only where the file is used: a photometry must be
            // one read here (gldfVariantPhotometry says so), and other files are not read.
            if (std::find(std::begin(kContentTypes), std::end(kContentTypes), file.contentType) ==
                std::end(kContentTypes))
                mProduct.warnings.push_back(
                    mProduct.path + ": product.xml: file " + inQuotes(file.id) +
                    ": unknown contentType " + inQuotes(toValidUtf8(file.contentType)) +
                    " (the schema's: ldc/eulumdat, ldc/ies, ldc/iesxml, image/*, geo/*, "
                    "document/pdf, symbol/*, sensor/*, spectrum/text, other); not read as any");
            std::string type = attribute(f, "type");
            if (type != "localFileName" && type != "url")
                defect("file " + inQuotes(file.id) + ": type " + inQuotes(type) +
                       ", expected \"localFileName\" or \"url\"");
            file.url = type == "url";
            file.name = text(f);
            if (file.name.empty()) defect("file " + inQuotes(file.id) + ": no file name or URL");
            mProduct.files.push_back(std::move(file));
        }
    }

    void photometries(const pugi::xml_node& photometries) {
        for (pugi::xml_node p : photometries.children("Photometry")) {
            std::string pid = id(p);
            std::string fileId;
            if (pugi::xml_node ref = p.child("PhotometryFileReference")) {
                fileId = id(ref, "fileId");
                if (!mProduct.file(fileId))
                    defect("photometry " + inQuotes(pid) + " refers to file " + inQuotes(fileId) +
                           ", which <Files> does not list");
            }
            mPhotometryFile[pid] = fileId;
        }
    }

    /// LightSourceMaintenance of a light source (CIE lamp factors or LED factors).
    std::vector<GldfMaintenance> lampMaintenance(const pugi::xml_node& m,
                                                 const std::string& owner) const {
        std::vector<GldfMaintenance> out;
        for (pugi::xml_node f :
             m.child("CieLampMaintenanceFactors").children("CieLampMaintenanceFactor")) {
            std::string hours = attribute(f, "burningTime");
            GldfMaintenance llmf;
            llmf.what = "LLMF after " + hours + " h";
            llmf.factor = number(f, "LampLumenMaintenanceFactor", owner, 0.0, 1.0);
            llmf.kind = GldfMaintenance::Kind::Llmf;
            llmf.hours = numberOr(hours, -1.0);
            GldfMaintenance lsf = llmf;
            lsf.what = "LSF after " + hours + " h";
            lsf.factor = number(f, "LampSurvivalFactor", owner, 0.0, 1.0);
            lsf.kind = GldfMaintenance::Kind::Lsf;
            out.push_back(llmf);
            out.push_back(lsf);
        }
        for (pugi::xml_node f : m.children("LedMaintenanceFactor")) {
            std::string hours = attribute(f, "hours");
            GldfMaintenance led;
            led.what = "LED maintenance after " + hours + " h";
            led.factor = numberOf(text(f), "<LedMaintenanceFactor> of " + owner, 0.0, 1.0);
            led.kind = GldfMaintenance::Kind::Led;
            led.hours = numberOr(hours, -1.0);
            out.push_back(led);
        }
        std::erase_if(out, [](const GldfMaintenance& m) { return m.factor < 0.0; });
        return out;
    }

    void lightSources(const pugi::xml_node& sources) {
        for (pugi::xml_node s : sources.children()) {
            std::string name = s.name();
            if (name != "ChangeableLightSource" && name != "FixedLightSource") continue;
            std::string sid = id(s);
            std::string owner = "light source " + inQuotes(sid);
            LightSource& source = mLightSources[sid];
            source.flux = number(s, "RatedLuminousFlux", owner, 0.0, kMaxLumens);
            source.power = number(s, "RatedInputPower", owner, 0.0, 1e9);
            source.maintenance = lampMaintenance(s.child("LightSourceMaintenance"), owner);
        }
    }

    void equipments(const pugi::xml_node& equipments) {
        for (pugi::xml_node e : equipments.children("Equipment")) {
            std::string eid = id(e);
            Equipment& equipment = mEquipments[eid];
            if (pugi::xml_node ref = e.child("LightSourceReference")) {
                equipment.lightSource = id(ref, "changeableLightSourceId");
                if (!mLightSources.count(equipment.lightSource))
                    defect("equipment " + inQuotes(eid) + " refers to light source " +
                           inQuotes(equipment.lightSource) +
                           ", which <LightSources> does not define");
                if (ref.attribute("lightSourceCount"))
                    equipment.count =
                        int(numberOf(attribute(ref, "lightSourceCount"),
                                     "lightSourceCount of equipment " + inQuotes(eid), 1.0, 1e6));
            }
            equipment.power = number(e, "RatedInputPower", "equipment " + inQuotes(eid), 0.0, 1e9);
        }
    }

    GldfLightEmitter lightEmitter(const pugi::xml_node& l, const std::string& emitterId) {
        GldfLightEmitter out;
        out.fixed = std::string(l.name()) == "FixedLightEmitter";
        std::string owner = "emitter " + inQuotes(emitterId);
        pugi::xml_node reference = l.child("PhotometryReference");
        if (!reference) defect(owner + ": a <" + l.name() + "> without <PhotometryReference>");
        out.photometryId = id(reference, "photometryId");
        auto photometry = mPhotometryFile.find(out.photometryId);
        if (photometry == mPhotometryFile.end())
            defect(owner + " refers to photometry " + inQuotes(out.photometryId) +
                   ", which <Photometries> does not define");
        out.fileId = photometry->second;
        const LightSource* source = nullptr;
        double equipmentPower = -1.0;
        if (out.fixed) {
            if (pugi::xml_node ref = l.child("LightSourceReference"))
                out.lightSourceId = id(ref, "fixedLightSourceId");
            out.ratedFlux = number(l, "RatedLuminousFlux", owner, 0.0, kMaxLumens);
        } else if (pugi::xml_node ref = l.child("EquipmentReference")) {
            std::string equipmentId = id(ref, "equipmentId");
            auto equipment = mEquipments.find(equipmentId);
            if (equipment == mEquipments.end())
                defect(owner + " refers to equipment " + inQuotes(equipmentId) +
                       ", which <Equipments> does not define");
            out.lightSourceId = equipment->second.lightSource;
            out.lightSourceCount = equipment->second.count;
            equipmentPower = equipment->second.power;
        }
        if (!out.lightSourceId.empty()) {
            auto it = mLightSources.find(out.lightSourceId);
            if (it == mLightSources.end())
                defect(owner + " refers to light source " + inQuotes(out.lightSourceId) +
                       ", which <LightSources> does not define");
            source = &it->second;
            out.maintenance = source->maintenance;
        }
        if (pugi::xml_node r = l.child("Rotation")) {
            std::string what = owner + "'s <Rotation>";
            // The schema's range: whole degrees in [0, 360] (non-integers are read too).
            out.rotationXyz = {number(r, "X", what, 0.0, 360.0, 0.0),
                               number(r, "Y", what, 0.0, 360.0, 0.0),
                               number(r, "Z", what, 0.0, 360.0, 0.0)};
            out.rotationG0 = number(r, "G0", what, 0.0, 360.0, 0.0);
        }
        if (!out.fixed && source && source->flux >= 0.0)
            out.ratedFlux = source->flux * out.lightSourceCount;
        out.ratedPower = equipmentPower;
        if (out.ratedPower < 0.0 && source && source->power >= 0.0)
            out.ratedPower = source->power * out.lightSourceCount;
        return out;
    }

    void emitters(const pugi::xml_node& emitters) {
        for (pugi::xml_node e : emitters.children("Emitter")) {
            GldfEmitter emitter;
            emitter.id = id(e);
            if (mProduct.emitter(emitter.id))
                defect("two <Emitter> elements with the id " + inQuotes(emitter.id));
            for (pugi::xml_node l : e.children()) {
                std::string name = l.name();
                if (name == "ChangeableLightEmitter" || name == "FixedLightEmitter")
                    emitter.lights.push_back(lightEmitter(l, emitter.id));
                else if (name == "SensorEmitter")
                    ++emitter.sensors;
            }
            mProduct.emitters.push_back(std::move(emitter));
        }
    }

    std::string emitterReference(const pugi::xml_node& ref, const std::string& variantId) const {
        std::string emitterId = id(ref, "emitterId");
        if (!mProduct.emitter(emitterId))
            defect("variant " + inQuotes(variantId) + " refers to emitter " + inQuotes(emitterId) +
                   ", which <Emitters> does not define");
        return emitterId;
    }

    /// Appends the placements of a ModelGeometryReference (one per EmitterReference).
    void modelGeometry(const pugi::xml_node& model, GldfVariant& variant) const {
        std::string gid = id(model, "geometryId");
        variant.geometryIds.push_back(gid);
        if (!mProduct.modelGeometry(gid))
            defect("variant " + inQuotes(variant.id) + " refers to model geometry " +
                   inQuotes(gid) + ", which <Geometries> does not define");
        if (variant.modelGeometryId.empty()) variant.modelGeometryId = gid;
        for (pugi::xml_node ref : model.children("EmitterReference")) {
            variant.emitters.push_back(emitterReference(ref, variant.id));
            variant.emitterObjects.push_back(text(ref.child("EmitterObjectExternalName")));
        }
    }

    void geometries(const pugi::xml_node& geometries) {
        for (pugi::xml_node g : geometries.children("ModelGeometry")) {
            GldfModelGeometry model;
            model.id = id(g);
            if (mProduct.modelGeometry(model.id))
                defect("two <ModelGeometry> elements with the id " + inQuotes(model.id));
            for (pugi::xml_node ref : g.children("GeometryFileReference")) {
                std::string fileId = id(ref, "fileId");
                if (!mProduct.file(fileId))
                    defect("model geometry " + inQuotes(model.id) + " refers to file " +
                           inQuotes(fileId) + ", which <Files> does not list");
                model.fileIds.push_back(fileId);
            }
            mProduct.modelGeometries.push_back(std::move(model));
        }
    }

    void variantGeometry(const pugi::xml_node& geometry, GldfVariant& variant) const {
        if (pugi::xml_node ref = geometry.child("EmitterReference")) {
            variant.emitters.push_back(emitterReference(ref, variant.id));
            variant.emitterObjects.emplace_back();
        } else if (pugi::xml_node simple = geometry.child("SimpleGeometryReference")) {
            variant.geometryIds.push_back(id(simple, "geometryId"));
            variant.emitters.push_back(emitterReference(simple, variant.id));
            variant.emitterObjects.emplace_back();
        } else if (pugi::xml_node model = geometry.child("ModelGeometryReference")) {
            modelGeometry(model, variant);
        } else if (pugi::xml_node both = geometry.child("GeometryReferences")) {
            // Levels of detail of one luminaire: the model's placements, else the simple one's.
            pugi::xml_node simple = both.child("SimpleGeometryReference");
            pugi::xml_node model = both.child("ModelGeometryReference");
            if (model) modelGeometry(model, variant);
            if (simple) {
                variant.geometryIds.push_back(id(simple, "geometryId"));
                std::string emitterId = emitterReference(simple, variant.id);
                if (!model) {
                    variant.emitters.push_back(emitterId);
                    variant.emitterObjects.emplace_back();
                }
            }
        }
    }

    /// Leaves a variant's sensor-only emitters out of its placements, and places the product's
    /// only light emitter where the variant's <Geometry> names none.
    void placeableEmitters(GldfVariant& variant) const {
        for (size_t i = variant.emitters.size(); i-- > 0;) {
            const GldfEmitter* e = mProduct.emitter(variant.emitters[i]);
            if (!e || !e->lights.empty() || e->sensors == 0) continue;
            if (std::find(variant.sensorEmitters.begin(), variant.sensorEmitters.end(), e->id) ==
                variant.sensorEmitters.end())
                variant.sensorEmitters.insert(variant.sensorEmitters.begin(), e->id);
            variant.emitters.erase(variant.emitters.begin() + std::ptrdiff_t(i));
            variant.emitterObjects.erase(variant.emitterObjects.begin() + std::ptrdiff_t(i));
        }
        if (!variant.emitters.empty() || !variant.sensorEmitters.empty()) return;
        const GldfEmitter* only = nullptr;
        int lights = 0;
        for (const GldfEmitter& e : mProduct.emitters)
            if (!e.lights.empty()) {
                only = &e;
                ++lights;
            }
        if (lights != 1) return;
        variant.emitters.push_back(only->id);
        variant.emitterObjects.emplace_back();
        variant.assumedEmitter = only->id;
    }

    /// A Pictures element's images; one naming no file is left out with a warning (the picture
    /// is an illustration: the product is read without it).
    std::vector<GldfPicture> pictures(const pugi::xml_node& node) {
        std::vector<GldfPicture> out;
        for (pugi::xml_node image : node.children("Image")) {
            GldfPicture picture{attribute(image, "fileId"), attribute(image, "imageType")};
            if (!mProduct.file(picture.fileId)) {
                mProduct.warnings.push_back(mProduct.path + ": product.xml: picture file " +
                                            inQuotes(picture.fileId) +
                                            " is not among the files; left out");
                continue;
            }
            out.push_back(std::move(picture));
        }
        return out;
    }

    void productDefinitions(const pugi::xml_node& definitions) {
        if (!definitions) defect("no <ProductDefinitions> (the schema requires one)");
        pugi::xml_node meta = definitions.child("ProductMetaData");
        if (!meta) defect("no <ProductMetaData> in <ProductDefinitions>");
        mProduct.uniqueProductId = text(meta.child("UniqueProductId"));
        mProduct.productNumber = locale(meta.child("ProductNumber"));
        mProduct.productName = locale(meta.child("Name"));
        mProduct.description = locale(meta.child("Description"));
        mProduct.pictures = pictures(meta.child("Pictures"));
        pugi::xml_node maintenance = meta.child("LuminaireMaintenance");
        for (const char* group : {"CieLuminaireMaintenanceFactors", "IesLuminaireLightLossFactors",
                                  "JiegMaintenanceFactors"})
            for (pugi::xml_node f : maintenance.child(group).children()) {
                std::string name = f.name();
                std::string years = attribute(f, "years"), room = attribute(f, "roomCondition");
                std::string what = name + " after " + years + " years (" + room + ")";
                GldfMaintenance m;
                m.what = what;
                m.factor = numberOf(text(f), name + " of the product", 0.0, 1.0);
                if (std::string(group) == "CieLuminaireMaintenanceFactors") {
                    m.kind = GldfMaintenance::Kind::Lmf;
                    m.years = numberOr(years, -1.0);
                    m.room = room;
                }
                mProduct.luminaireMaintenance.push_back(m);
            }
        for (pugi::xml_node v : definitions.child("Variants").children("Variant")) {
            GldfVariant variant;
            variant.id = id(v);
            if (mProduct.variant(variant.id))
                defect("two <Variant> elements with the id " + inQuotes(variant.id));
            variant.name = locale(v.child("Name"));
            variant.description = locale(v.child("Description"));
            variant.productNumber = locale(v.child("ProductNumber"));
            variant.pictures = pictures(v.child("Pictures"));
            variantGeometry(v.child("Geometry"), variant);
            placeableEmitters(variant);
            mProduct.variants.push_back(std::move(variant));
        }
        if (mProduct.variants.empty()) defect("no <Variant> in <ProductDefinitions>/<Variants>");
    }

    void read(const pugi::xml_node& root) {
        if (std::string(root.name()) != "Root")
            defect("the root element is <" + toValidUtf8(root.name()) + ">, expected <Root>");
        header(root.child("Header"));
        pugi::xml_node general = root.child("GeneralDefinitions");
        files(general.child("Files"));
        photometries(general.child("Photometries"));
        lightSources(general.child("LightSources"));
        equipments(general.child("Equipments"));
        emitters(general.child("Emitters"));
        geometries(general.child("Geometries"));
        productDefinitions(root.child("ProductDefinitions"));
    }

  private:
    struct LightSource {
        double flux = -1.0, power = -1.0;
        std::vector<GldfMaintenance> maintenance;
    };
    struct Equipment {
        std::string lightSource;
        int count = 1;
        double power = -1.0;
    };
    GldfProduct& mProduct;
    std::map<std::string, std::string> mPhotometryFile;  ///< photometry id -> file id
    std::map<std::string, LightSource> mLightSources;
    std::map<std::string, Equipment> mEquipments;
};

/// "a, b, c" for messages.
/// A member's bytes; refuses a missing one naming what its folder does hold (a name written in
/// another encoding shows up there).
std::string readMember(const ZipArchive& archive, const std::string& path,
                       const std::string& member, const std::string& label) {
    int64_t index = archive.find(member);
    if (index < 0) {
        std::string folder = member.substr(0, member.find('/') + 1), held;
        int count = 0;
        for (const std::string& name : archive.names())
            if (name.size() > folder.size() && name.compare(0, folder.size(), folder) == 0 &&
                ++count <= kMembersNamed)
                held += (held.empty() ? "" : ", ") + name;
        if (count > kMembersNamed)
            held += " and " + std::to_string(count - kMembersNamed) + " more";
        fail(path + ": " + label + ": not in the container" +
             (held.empty() ? "" : " (it holds " + held + ")") +
             "; the container is incomplete: ask the manufacturer for a corrected one");
    }
    return archive.read(index, label);
}

std::string emitterList(const std::vector<std::string>& ids) {
    std::string out;
    for (const std::string& id : ids) out += (out.empty() ? "" : ", ") + id;
    return out;
}

/// gldfVariantGeometry on an archive already open.
std::shared_ptr<const L3dLuminaire> readVariantGeometry(const ZipArchive& archive,
                                                        const GldfProduct& product,
                                                        const GldfVariant& variant) {
    const std::string& path = product.path;
    if (variant.modelGeometryId.empty()) return nullptr;
    const GldfModelGeometry* model = product.modelGeometry(variant.modelGeometryId);
    if (!model)
        fail(path + ": variant " + inQuotes(variant.id) + " refers to model geometry " +
             inQuotes(variant.modelGeometryId) + ", which the product does not define");
    const GldfFile* file = nullptr;
    for (const std::string& id : model->fileIds)
        if (const GldfFile* f = product.file(id); f && f->contentType == "geo/l3d") {
            file = f;
            break;
        }
    if (!file)
        fail(path + ": model geometry " + inQuotes(model->id) +
             " has no geo/l3d file (its r3d and m3d formats are not read)");
    if (file->url)
        fail(path + ": geometry file " + inQuotes(file->id) + " is only a URL (" + file->name +
             "), not in the container");
    std::string member = file->member();
    std::string label =
        member + " (file " + inQuotes(file->id) + ", model geometry " + inQuotes(model->id) + ")";
    std::string l3d = readMember(archive, path, member, label);
    return std::make_shared<const L3dLuminaire>(parseL3d(l3d, path + ":" + member));
}

}  // namespace

std::string GldfFile::member() const {
    if (url) return "";
    return contentType.substr(0, contentType.find('/')) + "/" + name;
}

const GldfFile* GldfProduct::file(const std::string& id) const {
    for (const GldfFile& f : files)
        if (f.id == id) return &f;
    return nullptr;
}

const GldfEmitter* GldfProduct::emitter(const std::string& id) const {
    for (const GldfEmitter& e : emitters)
        if (e.id == id) return &e;
    return nullptr;
}

const GldfModelGeometry* GldfProduct::modelGeometry(const std::string& id) const {
    for (const GldfModelGeometry& g : modelGeometries)
        if (g.id == id) return &g;
    return nullptr;
}

const GldfVariant* GldfProduct::variant(const std::string& id) const {
    for (const GldfVariant& v : variants)
        if (v.id == id) return &v;
    return nullptr;
}

std::string readGldfBytes(const std::string& path) {
    return readInputFile(path, "GLDF", kMaxGldfContainer);
}

GldfProduct parseGldf(const std::string& bytes, const std::string& path) {
    ZipArchive archive(bytes, path, "a GLDF container");
    GldfProduct product;
    product.path = path;
    for (const std::string& name : archive.names())
        if (!name.empty() && name.back() != '/') product.members.push_back(name);
    int64_t index = archive.find("product.xml");
    if (index < 0) fail(path + ": product.xml: missing");
    gldf_detail::readProductXml(archive.read(index, "product.xml"), product);
    return product;
}

void gldf_detail::readProductXml(const std::string& xml, GldfProduct& product) {
    pugi::xml_document doc;
    // encoding_auto: UTF-8 or UTF-16 by byte-order mark or declaration, as writers produce.
    pugi::xml_parse_result parsed =
        doc.load_buffer(xml.data(), xml.size(), pugi::parse_default, pugi::encoding_auto);
    if (!parsed)
        fail(product.path + ": product.xml: not well-formed XML (" + parsed.description() +
             " at byte " + std::to_string(parsed.offset) + ")");
    ProductReader(product).read(doc.document_element());
}

GldfPhotometry gldfVariantPhotometry(const std::string& bytes, const GldfProduct& product,
                                     const GldfVariant& variant, const PhotometryOptions& options,
                                     size_t placement,
                                     std::shared_ptr<const L3dLuminaire> geometry) {
    const std::string& path = product.path;
    std::string variantName = "variant " + inQuotes(variant.id);
    size_t count = variant.emitters.size();
    if (count == 0 && !variant.sensorEmitters.empty())
        fail(path + ": " + variantName + " has only sensor emitters (" +
             emitterList(variant.sensorEmitters) +
             "), which give no light: choose another variant of the product");
    if (count == 0) {
        int lights = 0;
        for (const GldfEmitter& e : product.emitters) lights += e.lights.empty() ? 0 : 1;
        fail(path + ": " + variantName + " places no emitter (its <Geometry> names none) and " +
             (lights == 0 ? "the product defines no light emitter: the container holds no "
                            "photometry to place; ask the manufacturer for one that does"
                          : "the product has " + std::to_string(lights) +
                                " light emitters, so which one it places is unknown: choose "
                                "another variant, or place one of its photometry files itself"));
    }
    if (placement >= count)
        fail(path + ": " + variantName + " places " + std::to_string(count) +
             " emitter(s); there is no emitter " + std::to_string(placement) + " (from 0)");
    // Several emitters need the geometry's objects to say where each one is.
    const std::string& object =
        placement < variant.emitterObjects.size() ? variant.emitterObjects[placement] : "";
    if (count > 1 && object.empty())
        fail(path + ": " + variantName + " places " + std::to_string(count) + " emitters (" +
             emitterList(variant.emitters) + ") but does not say where emitter " +
             std::to_string(placement) +
             " is (no <EmitterObjectExternalName> in a model geometry): it cannot be placed");
    GldfPhotometry out;
    out.emitter = product.emitter(variant.emitters[placement]);
    // parseGldf resolves every reference; a product assembled otherwise is checked here too.
    if (!out.emitter)
        fail(path + ": " + variantName + " refers to emitter " +
             inQuotes(variant.emitters[placement]) + ", which the product does not define");
    std::string emitterName = "emitter " + inQuotes(out.emitter->id);
    if (out.emitter->lights.empty())
        fail(path + ": " + emitterName + " (" + variantName +
             ") has no light emitter (ChangeableLightEmitter or FixedLightEmitter)");
    const GldfLightEmitter& light = out.emitter->lights.front();
    if (light.fileId.empty())
        fail(path + ": photometry " + inQuotes(light.photometryId) + " (" + emitterName +
             ") has no <PhotometryFileReference>");
    out.file = product.file(light.fileId);
    if (!out.file)
        fail(path + ": photometry " + inQuotes(light.photometryId) + " refers to file " +
             inQuotes(light.fileId) + ", which the product does not list");
    const GldfFile& file = *out.file;
    if (file.url)
        fail(path + ": photometry file " + inQuotes(file.id) + " is only a URL (" + file.name +
             "), not in the container: download it and place it as a photometric luminaire, or "
             "ask the manufacturer for a container that holds it");
    std::string member = file.member();
    std::string label =
        member + " (file " + inQuotes(file.id) + ", referenced by " + emitterName + ")";
    const std::string& type = file.contentType;
    if (type != "ldc/eulumdat" && type != "ldc/ies" && type != "ldc/iesxml")
        fail(path + ": " + label + ": content type " + inQuotes(type) +
             " is not a photometry read here (ldc/eulumdat, ldc/ies or ldc/iesxml)");
    ZipArchive archive(bytes, path, "a GLDF container");
    std::string text = readMember(archive, path, member, label);
    try {
        std::string name = path + ":" + member;
        out.data = type == "ldc/eulumdat" ? parseEulumdat(text, name, options)
                   : type == "ldc/ies"    ? parseIes(text, name, options)
                                          : parseTm33(text, name, options);
    } catch (const std::exception& e) {
        fail(path + ": " + label + ": " + std::to_string(text.size()) + " bytes, not " +
             (type == "ldc/eulumdat" ? "a EULUMDAT"
              : type == "ldc/ies"    ? "an IES"
                                     : "an IES TM-33") +
             " file: " + e.what() + "; ask the manufacturer for a corrected container");
    }
    // What was read leniently, once per variant (its first placement).
    if (placement == 0) {
        for (const std::string& w : product.warnings) out.data.warnings.push_back(w);
        if (!variant.assumedEmitter.empty())
            out.data.warnings.push_back(path + ": " + variantName +
                                        ": its <Geometry> names no emitter; placing the "
                                        "product's only light emitter, " +
                                        inQuotes(variant.assumedEmitter));
        for (const std::string& sensor : variant.sensorEmitters)
            out.data.warnings.push_back(path + ": " + variantName + ": sensor emitter " +
                                        inQuotes(sensor) + " skipped (a sensor gives no light)");
    }
    out.geometry = geometry ? std::move(geometry) : readVariantGeometry(archive, product, variant);
    if (out.geometry && !object.empty()) {
        out.opening = out.geometry->emitter(object);
        if (!out.opening) {
            std::string names;
            for (const L3dEmitter& e : out.geometry->emitters)
                names += (names.empty() ? "" : ", ") + e.name;
            fail(path + ": " + variantName + " places " + emitterName + " at object " +
                 inQuotes(object) + ", which its geometry " + out.geometry->path +
                 " does not hold (it has " + (names.empty() ? "none" : names) + ")");
        }
    }
    return out;
}

std::string GldfMaintenanceFactors::text(double hours) const {
    char buf[192];
    std::snprintf(buf, sizeof buf, "%.4g = %s %.4g x LSF %.4g (%g h) x LMF %.4g x RSMF %.4g",
                  factor(), led ? "LED factor" : "LLMF", llmf, lsf, hours, lmf, rsmf);
    return buf;
}

GldfMaintenanceFactors gldfMaintenanceFactors(const GldfProduct& product,
                                              const GldfLightEmitter& light,
                                              const GldfMaintenanceChoice& choice) {
    const std::string& path = product.path;
    GldfMaintenanceFactors out;
    // Lamp factors at the burning time asked.
    bool llmf = false, lsf = false;
    std::string stated;
    for (const GldfMaintenance& m : light.maintenance) {
        if (m.kind != GldfMaintenance::Kind::Llmf && m.kind != GldfMaintenance::Kind::Lsf &&
            m.kind != GldfMaintenance::Kind::Led)
            continue;
        char h[32];
        std::snprintf(h, sizeof h, "%g", m.hours);
        if (stated.find(std::string(h) + " h") == std::string::npos)
            stated += (stated.empty() ? "" : ", ") + std::string(h) + " h";
        if (m.hours != choice.hours) continue;
        if (m.kind == GldfMaintenance::Kind::Lsf) {
            out.lsf = m.factor;
            lsf = true;
        } else {
            out.llmf = m.factor;
            out.led = m.kind == GldfMaintenance::Kind::Led;
            llmf = true;
        }
    }
    char hours[32];
    std::snprintf(hours, sizeof hours, "%g h", choice.hours);
    std::string source =
        "the light source of photometry " + inQuotes(light.photometryId) +
        (light.lightSourceId.empty() ? ""
                                     : " (light source " + inQuotes(light.lightSourceId) + ")");
    if (!llmf)
        fail(path + ": " + source + " states no lumen maintenance factor at " + hours +
             (stated.empty() ? " (it states none)" : " (it states them at " + stated + ")"));
    if (!lsf && !out.led)
        fail(path + ": " + source + " states no lamp survival factor at " + hours);
    // The luminaire maintenance factor: given, or the product's for the years and room.
    if (choice.lmf >= 0.0) {
        out.lmf = choice.lmf;
    } else {
        std::string listed;
        bool found = false;
        for (const GldfMaintenance& m : product.luminaireMaintenance) {
            if (m.kind != GldfMaintenance::Kind::Lmf) continue;
            char y[32];
            std::snprintf(y, sizeof y, "%g years (%s)", m.years, m.room.c_str());
            listed += (listed.empty() ? "" : ", ") + std::string(y);
            if (m.years == choice.years && m.room == choice.room) {
                out.lmf = m.factor;
                found = true;
            }
        }
        if (!found) {
            char y[96];
            std::snprintf(y, sizeof y, "%g years in a \"%s\" room", choice.years,
                          choice.room.c_str());
            fail(path + ": the product states no CIE luminaire maintenance factor for " + y +
                 (listed.empty() ? " (it states none: give \"lmf\")"
                                 : " (it states " + listed + "; or give \"lmf\")"));
        }
    }
    out.rsmf = choice.rsmf;
    return out;
}

std::shared_ptr<const L3dLuminaire> gldfVariantGeometry(const std::string& bytes,
                                                        const GldfProduct& product,
                                                        const GldfVariant& variant) {
    if (variant.modelGeometryId.empty()) return nullptr;
    ZipArchive archive(bytes, product.path, "a GLDF container");
    return readVariantGeometry(archive, product, variant);
}

void gldfRotateEmitter(const GldfLightEmitter& light, glm::dvec3& c0, glm::dvec3& aim) {
    constexpr double kDegree = 3.14159265358979323846 / 180.0;
    double g = light.rotationG0 * kDegree;
    glm::dvec3 c90 = glm::cross(c0, aim);
    c0 = std::cos(g) * c0 + std::sin(g) * c90;
    // Right-handed rotation of v about the unit axis a by t radians (Rodrigues).
    auto turn = [](const glm::dvec3& v, const glm::dvec3& a, double t) {
        return std::cos(t) * v + std::sin(t) * glm::cross(a, v) +
               (1.0 - std::cos(t)) * glm::dot(a, v) * a;
    };
    glm::dvec3 r = light.rotationXyz * kDegree;
    for (glm::dvec3* v : {&c0, &aim}) {  // R = Rz Rx Ry: Ry first
        *v = turn(*v, {0, 1, 0}, r.y);
        *v = turn(*v, {1, 0, 0}, r.x);
        *v = turn(*v, {0, 0, 1}, r.z);
        *v = glm::normalize(*v);
    }
}

}  // namespace candela
