#pragma once
// The lighting report a designer hands to a client, as a PDF drawn by cairo: a cover (project,
// client, designer, date, a rendered view), the contents, the project data, per room its data
// (size, area, height, reflectances, maintenance factor) and its plan seen from above
// (dimensions, openings, furniture, luminaires with their mounting heights, task areas), the
// luminaire schedule (manufacturer, product, article number, picture, count, flux, power,
// efficacy, maintenance factor), a datasheet per luminaire type (figures, light output ratio,
// polar diagram in cd/klm, UGR table), every EN 12464-1 calculation surface (summary against its
// requirement, false-colour picture with its legend and isolux lines, value table), the
// calculation points, the power density, the UGR at each observer, and how it was all computed.
// `candela report` and the editor's File > Export report make one; the numbers are those of
// `candela surfaces` and `candela glare` (the same computations, passed in).

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "calculation/CalculationSurfaces.h"
#include "calculation/Glare.h"
#include "formats/Gldf.h"
#include "scene/RoomIo.h"

namespace candela {

struct Scene;
struct FalseColourLegend;
class Luminaire;
struct PhotometricData;

struct ReportInput {
    const Scene* scene = nullptr;
    std::string title;       ///< The project's name (the scene file's stem unless given).
    std::string date;        ///< YYYY-MM-DD.
    std::string evaluation;  ///< How the illuminance was computed (estimators, samples, light).
    SurfaceReport surfaces;  ///< computeSurfaces' result (may hold no surface).
    std::optional<GlareReport> glare;  ///< computeGlare's; empty when the scene has no observer.
    std::string glareNote;             ///< Why there is no UGR, when glare is empty.
    /// The rendered view: 8-bit RGB rows top to bottom (empty: none, viewNote says why).
    std::vector<unsigned char> view;
    int viewWidth = 0, viewHeight = 0;
    std::string viewNote;
};

/// What `how` computed on `scene` with `patches` interreflection patches (0: none), in the
/// report's words ("direct light with shadows, and interreflected light; each luminaire's
/// light from its own measured photometry; ...").
std::string reportEvaluationText(const Scene& scene, const GridSpec& how, size_t patches);

/// Today's date, YYYY-MM-DD in UTC (thread-safe): a report's date and a converted file's.
std::string todayUtc();

/// Fills what the report computes: scene, title, today's date, the evaluation text, the surfaces
/// (computeSurfaces, when the scene has any) and the UGR (computeGlare, when it has observers),
/// or the notes saying there are none. The view is the caller's. `status` hears progress.
void computeReportContents(ReportInput& in, const Scene& scene, const std::string& title,
                           const GridSpec& how,
                           const std::function<void(const std::string&)>& status = {});

/// The report's PDF bytes (A4 pages). Throws InputError when cairo cannot draw it.
std::string reportPdf(const ReportInput& input);

/// A false-colour picture (8-bit RGB rows top to bottom, `width` x `height`) with its legend in a
/// strip on its right: the colour scale, its ticks labelled in `unit`, the isolux levels marked.
/// Returns the wider picture and sets `width` to its width.
std::vector<unsigned char> withFalseColourLegend(const std::vector<unsigned char>& rgb, int& width,
                                                 int height, const FalseColourLegend& legend,
                                                 const std::string& unit);

/// One row of the luminaire schedule: identical luminaires (same file, variant, emitter, dimming
/// and maintenance factor) counted together.
struct ScheduleRow {
    std::string names;  ///< "Downlight 1 .. Downlight 6" or the one name.
    int count = 0;
    std::vector<size_t> members;  ///< Its luminaires, indices into Scene::luminaires.
    std::string kind;             ///< "photometric", "GLDF", "light field", ...
    std::string manufacturer;     ///< From the file (IES [MANUFAC], EULUMDAT company, GLDF, TM-33).
    std::string product;          ///< The file's luminaire name or the GLDF product and variant.
    std::string file;             ///< The photometry or container, as the scene names it.
    /// The article number: a GLDF variant's or product's ProductNumber, else the file's own
    /// (IES [LUMCAT], EULUMDAT luminaire number, TM-33 CatalogNumber); may be empty.
    std::string articleNumber;
    std::string description;  ///< A GLDF product's or variant's description; may be empty.
    /// A GLDF product's picture (gldfPicture); empty when it has none or it does not decode.
    std::optional<GldfImage> picture;
    /// Why a picture the product names is not shown (gldfPicture's warnings).
    std::vector<std::string> pictureNotes;
    double flux = 0.0;   ///< Each luminaire's, lm (W for a radiometric source).
    double power = 0.0;  ///< Each luminaire's input power, W; 0: not stated.
    double maintenanceFactor = 1.0;
};
/// The schedule of `scene`'s luminaires. `pictures`: decode GLDF products' pictures (reads each
/// container again).
std::vector<ScheduleRow> luminaireSchedule(const Scene& scene, bool pictures = false);

/// A luminaire's rated input power as its file states it (a photometric file's input watts, a
/// GLDF emitter's equipment or light source), W; 0 when it states none.
double luminaireInputPower(const Luminaire& luminaire);

/// What a datasheet states of a photometry (the file's own figures, undimmed).
struct DatasheetFigures {
    double flux = 0.0;      ///< The luminaire's flux from its intensity table, lm.
    double lampFlux = 0.0;  ///< The lamps' rated flux, lm; 0 for absolute photometry.
    /// Light output ratio, luminaire over lamp flux (the table's flux over the lamps'); < 0 for
    /// absolute photometry, where the luminaire is measured as a whole and no lamp flux exists.
    double lightOutputRatio = -1.0;
    /// The ratio the file itself states (EULUMDAT's LORL), < 0 when it states none.
    double statedLightOutputRatio = -1.0;
};
DatasheetFigures datasheetFigures(const PhotometricData& data);

/// One room of the design as the report describes it: a scene-file room, or the scene's bounds
/// when the scene has no room entry.
struct RoomSummary {
    std::string name;
    std::optional<RoomSpec> room;       ///< Empty: the scene's bounds stand in for a room.
    glm::dvec2 lo{0.0}, hi{0.0};        ///< The floor's bounding box (x, z), m.
    double floorY = 0.0, height = 0.0;  ///< The floor's y and the height to the ceiling, m.
    double area = 0.0;                  ///< Floor area, m2 (a room's by the shoelace formula).
    std::vector<size_t> luminaires;     ///< Indices into Scene::luminaires within the room.
    std::vector<size_t> furniture;      ///< Indices into Scene::geometry of its furniture.
    std::vector<size_t> taskAreas;      ///< Indices into Scene::taskAreas over its floor.
    double power = 0.0;                 ///< Its luminaires' input power in all, W (as stated).
    int powerUnstated = 0;              ///< How many of its luminaires state no input power.
    /// The task area whose Em the density per 100 lx refers to: the room's largest horizontal
    /// task area ("" when it has none or it was not computed), and its Em, lx.
    std::string reference;
    double em = 0.0;
    /// Input power per floor area, W/m2; < 0 when a luminaire states no input power or the
    /// floor has no area.
    double powerDensity() const;
    /// That per 100 lx of the reference's Em, W/m2 per 100 lx; < 0 when either is not known.
    double powerDensityPer100Lux() const;
};
/// The rooms of `scene` (each "room" geometry entry, in order; else one for the scene's bounds)
/// with what stands in each, and the Em of each room's reference task area from `surfaces`
/// (computeSurfaces' result; may hold no surface).
std::vector<RoomSummary> roomSummaries(const Scene& scene, const SurfaceReport& surfaces);

}  // namespace candela
