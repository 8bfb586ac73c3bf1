#pragma once
// GLDF (Global Lighting Data Format, DIAL and Relux): a ZIP container holding product.xml (the
// product, its variants, emitters, light sources and a list of files) and members such as
// ldc/*.ldt or ldc/*.ies photometry and geo/*.l3d geometry. The container is read with libzip and
// product.xml with pugixml; element names follow the format's schema (gldf.xsd, 1.0.0-rc.3).
//
// What is read: the header, the product's metadata (name, article number, description,
// pictures) and maintenance, the Files list, the photometries, light sources, equipments and
// emitters, and the variants (their own article numbers, descriptions and pictures) with the
// emitters their geometry places. gldfProductInfo and gldfPicture give what a designer reads
// about a variant: manufacturer, article number, description and its picture decoded. A variant is
// placed as one photometric luminaire: its emitter's photometry (the first of interchangeable light
// emitters) read from the container by the IES or EULUMDAT parser. A variant whose model geometry
// (an L3D member, formats/L3d.h) names the emitter's light-emitting object takes its opening and
// its position and rotation in the luminaire from it; a variant that places several emitters at
// such objects is several photometric luminaires, one per placement. Not yet: the emitter's own
// <Rotation>, sensors, spectra.
//
// Every defect is an InputError of one line in valid UTF-8 that names the container, the member
// and what is wrong ("lamp.gldf: product.xml: missing"); member names in code page 850 or UTF-8.

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "formats/L3d.h"
#include "formats/Photometry.h"
#include "util/ZipArchive.h"

namespace candela {

/// Largest container read, bytes: the container is read into memory whole.
constexpr uint64_t kMaxGldfContainer = uint64_t(256) << 20;
/// Largest member read from a container (uncompressed), bytes (util/ZipArchive.h).
constexpr uint64_t kMaxGldfMember = kMaxZipMember;

/// One entry of GeneralDefinitions/Files.
struct GldfFile {
    std::string id;
    std::string contentType;  ///< "ldc/eulumdat", "ldc/ies", "geo/l3d", "image/png", "other", ...
    bool url = false;         ///< type="url": `name` is a web address, not a member.
    std::string name;         ///< The local file name (type="localFileName") or the URL.
    /// The member it is stored as: the content type's folder and the name ("ldc/lamp.ldt");
    /// empty for a URL.
    std::string member() const;
};

/// One maintenance figure, as the file states it.
struct GldfMaintenance {
    std::string what;  ///< "LLMF after 125 h", "LSF after 125 h", "LMF after 3 years (clean)", ...
    double factor = 0.0;  ///< Dimensionless, 0..1.
    /// What it is: a lamp lumen maintenance or survival factor, an LED maintenance factor (at a
    /// burning time), a CIE luminaire maintenance factor (after years in a room condition), or
    /// another system's (IES, JIEG: shown, not used).
    enum class Kind { Llmf, Lsf, Led, Lmf, Other } kind = Kind::Other;
    double hours = -1.0;  ///< Burning time, h (Llmf, Lsf, Led); < 0 when not a number.
    double years = -1.0;  ///< Years (Lmf); < 0 when not a number.
    std::string room;     ///< roomCondition (Lmf): "Very Clean", "Clean", "Normal", "Dirty".
};

/// What a designer chooses to derive a GLDF luminaire's maintenance factor from its data
/// (EN 12464-1, CIE 97: MF = LLMF x LSF x LMF x RSMF): the burning time whose lamp factors
/// (LLMF and LSF, or an LED factor as LLMF with LSF 1) apply, the luminaire maintenance factor
/// (given, or the product's CIE factor for `years` in `room`) and the room surface maintenance
/// factor (given, or 1: no interreflection loss).
struct GldfMaintenanceChoice {
    double hours = -1.0;  ///< Burning time, h (required).
    double lmf = -1.0;    ///< < 0: from the product's data for years and room.
    double years = -1.0;
    std::string room;
    double rsmf = 1.0;
};

/// The four factors and where they came from.
struct GldfMaintenanceFactors {
    double llmf = 1.0, lsf = 1.0, lmf = 1.0, rsmf = 1.0;
    bool led = false;  ///< LLMF is an LED maintenance factor (LSF 1).
    double factor() const { return llmf * lsf * lmf * rsmf; }
    /// "0.5609 = LLMF 0.8 x LSF 0.82 (150 h) x LMF 0.9 x RSMF 0.95".
    std::string text(double hours) const;
};

/// One light emitter of an Emitter (ChangeableLightEmitter or FixedLightEmitter) with what its
/// photometry, equipment and light source say.
struct GldfLightEmitter {
    bool fixed = false;  ///< FixedLightEmitter (flux stated on the emitter) or Changeable.
    std::string photometryId;
    std::string fileId;         ///< The photometry's file; empty when it gives none.
    std::string lightSourceId;  ///< Empty when none is referenced.
    int lightSourceCount = 1;
    /// Rated luminous flux, lm (the light source's times its count, or the fixed emitter's);
    /// < 0 when not stated.
    double ratedFlux = -1.0;
    /// Rated input power, W (the equipment's, else the light source's times its count); < 0 when
    /// not stated.
    double ratedPower = -1.0;
    std::vector<GldfMaintenance> maintenance;  ///< The light source's LightSourceMaintenance.
    /// <Rotation>, degrees ("for wall or floor luminaires, if not measured in position of use";
    /// the guide's example turns a street luminaire's IES data 90 degrees about G0): about the
    /// luminaire's x, y and z axes, and about the photometric solid's own gamma = 0 axis. All 0
    /// when not given. gldfRotateEmitter applies it.
    glm::dvec3 rotationXyz{0.0};
    double rotationG0 = 0.0;
    bool rotated() const { return rotationXyz != glm::dvec3(0.0) || rotationG0 != 0.0; }
};

/// Turns an emitter's photometric frame (its C0 direction and aim, unit vectors in the L3D
/// luminaire frame) by its <Rotation>. The schema names the axes but not the senses and order;
/// Candela reads them as L3D reads its own rotations, right-handed (counter-clockwise seen from
/// the axis' tip): first G0 about the photometric solid's vertical axis, in the sense of
/// increasing C (C0 goes where C = G0 was: C0 + G0 x C90), then R = Rz Rx Ry about the luminaire's
/// axes. The opening stays where it is and turns with the aim.
void gldfRotateEmitter(const GldfLightEmitter& light, glm::dvec3& c0, glm::dvec3& aim);

/// GeneralDefinitions/Emitters/Emitter.
struct GldfEmitter {
    std::string id;
    /// Interchangeable light emitters (the schema's reading of several); the first is placed.
    std::vector<GldfLightEmitter> lights;
    int sensors = 0;  ///< SensorEmitter children (not placed).
};

/// One Image of a Pictures element (the product's ProductMetaData/Pictures or a variant's):
/// a file of GeneralDefinitions/Files and what it shows.
struct GldfPicture {
    std::string fileId;
    std::string
        imageType;  ///< "Product Picture", "Application Picture", "Technical Sketch", "Other".
};

/// ProductDefinitions/Variants/Variant.
struct GldfVariant {
    std::string id;
    std::string name;           ///< First Locale of Name (may be empty).
    std::string description;    ///< First Locale of Description (may be empty).
    std::string productNumber;  ///< Its own ProductNumber (overrides the product's; may be empty).
    std::vector<GldfPicture> pictures;  ///< Its Pictures, in the file's order.
    /// Emitter ids as the variant's geometry places them, one per placement (a model geometry can
    /// place an emitter at several named objects); the simple and model levels of detail of a
    /// GeometryReferences element are the same placements, so the model's are taken.
    std::vector<std::string> emitters;
    /// Parallel to emitters: the L3D light-emitting object each placement names
    /// (EmitterObjectExternalName; "" when it names none).
    std::vector<std::string> emitterObjects;
    std::vector<std::string> geometryIds;  ///< Simple and model geometries referenced.
    std::string modelGeometryId;  ///< The ModelGeometry that places the emitters ("" for none).
    /// Emitters the geometry places that are sensors only (a presence sensor gives no light):
    /// listed, and left out of `emitters`.
    std::vector<std::string> sensorEmitters;
    /// The product's only light emitter, placed because the variant's <Geometry> names none (an
    /// empty <Geometry>, as some manufacturers write); "" when the variant names its own.
    std::string assumedEmitter;
};

/// GeneralDefinitions/Geometries/ModelGeometry: a 3D model (its files: levels of detail and
/// formats).
struct GldfModelGeometry {
    std::string id;
    std::vector<std::string> fileIds;
};

struct GldfProduct {
    std::string path;  ///< The container, for messages (may not be valid UTF-8).
    // Header.
    std::string manufacturer, author, formatVersion, createdWithApplication, creationTime;
    // ProductMetaData: first Locale of each translatable field.
    std::string uniqueProductId, productName, productNumber, description;
    std::vector<GldfPicture> pictures;  ///< ProductMetaData/Pictures, in the file's order.
    std::vector<GldfMaintenance> luminaireMaintenance;  ///< LuminaireMaintenance factors.
    std::vector<GldfFile> files;
    std::vector<GldfEmitter> emitters;
    std::vector<GldfVariant> variants;
    std::vector<GldfModelGeometry> modelGeometries;
    std::vector<std::string> members;  ///< Every member of the container, UTF-8.
    /// What was read leniently, one line each ("PATH: product.xml: file "x": unknown contentType
    /// "invalid"; kept"); every placement repeats them among its photometry's warnings.
    std::vector<std::string> warnings;

    const GldfFile* file(const std::string& id) const;
    const GldfEmitter* emitter(const std::string& id) const;
    const GldfVariant* variant(const std::string& id) const;
    const GldfModelGeometry* modelGeometry(const std::string& id) const;
};

/// A variant's photometry as a placed luminaire needs it.
struct GldfPhotometry {
    const GldfEmitter* emitter = nullptr;  ///< Points into the product it was read from.
    const GldfFile* file = nullptr;
    PhotometricData data;  ///< data.path is "CONTAINER:MEMBER" for messages.
    /// The variant's L3D geometry (null when it references no model geometry) and the luminous
    /// opening the placement names in it (null when it names none).
    std::shared_ptr<const L3dLuminaire> geometry;
    const L3dEmitter* opening = nullptr;  ///< Points into *geometry.
};

/// The container's bytes; refuses a missing or unreadable file and one above kMaxGldfContainer.
std::string readGldfBytes(const std::string& path);
/// Reads the container (its bytes) and its product.xml; `path` names it in messages.
GldfProduct parseGldf(const std::string& bytes, const std::string& path);
inline GldfProduct loadGldf(const std::string& path) {
    return parseGldf(readGldfBytes(path), path);
}
/// The photometry of one placement (0 for the first) of a variant of `product` (read from
/// `bytes`, the same container), with the variant's geometry and the object the placement names:
/// refuses a variant with no emitter, a placement it does not have, one of several placements
/// that names no object of a model geometry (where it is is then unknown), an emitter without
/// photometry, a URL, a missing, oversized or unparsable member, naming it.
/// `geometry`, when given, is the variant's geometry as gldfVariantGeometry read it before (for
/// a variant's other placements: the L3D is read once).
GldfPhotometry gldfVariantPhotometry(const std::string& bytes, const GldfProduct& product,
                                     const GldfVariant& variant,
                                     const PhotometryOptions& options = defaultPhotometryOptions(),
                                     size_t placement = 0,
                                     std::shared_ptr<const L3dLuminaire> geometry = nullptr);

/// The L3D geometry of a variant's model geometry (its first geo/l3d file, read from `bytes`);
/// null when the variant references no model geometry. Refuses a missing, URL-only or broken
/// geometry file, naming the container and the member.
std::shared_ptr<const L3dLuminaire> gldfVariantGeometry(const std::string& bytes,
                                                        const GldfProduct& product,
                                                        const GldfVariant& variant);

/// The maintenance factors of a placed light emitter of `product` for `choice`: refuses a burning
/// time the emitter's light source states no factors for, and a luminaire maintenance factor
/// neither given nor stated for the years and room asked, naming the container and listing what
/// it does state.
GldfMaintenanceFactors gldfMaintenanceFactors(const GldfProduct& product,
                                              const GldfLightEmitter& light,
                                              const GldfMaintenanceChoice& choice);

/// What a designer and a client read about one variant of a product, from product.xml alone
/// (no member is read): for the editor's inspector and the report's luminaire schedule and
/// datasheets.
struct GldfProductInfo {
    std::string manufacturer;   ///< The header's Manufacturer (may be empty).
    std::string product;        ///< The product's name (may be empty).
    std::string variant;        ///< The variant's name (may be empty).
    std::string articleNumber;  ///< The variant's ProductNumber, else the product's; may be empty.
    std::string description;    ///< The variant's Description, else the product's; may be empty.
    /// The picture to show: the variant's first "Product Picture", else the product's; failing
    /// those, the variant's first image of another type, else the product's. Only PNG and JPEG
    /// files in the container are taken (an SVG or a URL is not decoded); null when there is none.
    const GldfFile* picture = nullptr;  ///< Points into the product.
};

/// The product data of variant `variantId` of `product` ("" or an unknown id: the product's own,
/// with no variant name). For a placed GLDF luminaire (luminaires/photometric, `gldf` and
/// `gldfVariant` of its model), as the report's schedule does it:
///     GldfProductInfo info = gldfProductInfo(*model.gldf, model.gldfVariant);
///     std::vector<std::string> warnings;  // shown, never fatal
///     std::optional<GldfImage> picture =
///         gldfPicture(readGldfBytes(model.gldf->path), *model.gldf, info, warnings);
/// (readGldfBytes throws InputError when the container is gone since it was loaded.)
GldfProductInfo gldfProductInfo(const GldfProduct& product, const std::string& variantId);

/// A picture decoded to 8-bit RGB, rows top to bottom (transparent pixels over white).
struct GldfImage {
    int width = 0, height = 0;
    std::vector<unsigned char> rgb;  ///< width x height x 3 bytes.
};

/// The largest picture side decoded, pixels: product pictures are a few hundred pixels; beyond
/// this a picture is refused with a warning rather than decoded.
constexpr int kMaxGldfPictureSide = 8192;

/// Decodes `info.picture` from `bytes` (the same container's bytes, readGldfBytes(product.path)).
/// Never throws for the picture itself: a missing, empty, oversized or undecodable member is a
/// warning ("lamp.gldf: image/lamp.png: cannot read image: ...") appended to `warnings`, and the
/// result is empty; so is the result when `info` has no picture.
std::optional<GldfImage> gldfPicture(const std::string& bytes, const GldfProduct& product,
                                     const GldfProductInfo& info,
                                     std::vector<std::string>& warnings);

namespace gldf_detail {
/// Reads product.xml's text into `product` (product.path names the container in messages); for
/// parseGldf and the fuzz target, which feeds it XML without a container around it.
void readProductXml(const std::string& xml, GldfProduct& product);
}  // namespace gldf_detail

}  // namespace candela
