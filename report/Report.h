#pragma once
// The lighting report a designer hands to a client, as a PDF drawn by cairo: the project and its
// scene, the luminaire schedule (manufacturer, product, flux, power, count, efficacy, maintenance
// factor) with each photometry's polar diagram, every EN 12464-1 calculation surface (summary
// against its requirement, false-colour picture with its legend and isolux lines, value table),
// the calculation points, the UGR at each observer, a rendered view, and how it was all computed.
// `candela report` and the editor's File > Export report make one; the numbers are those of
// `candela surfaces` and `candela glare` (the same computations, passed in).

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "calculation/CalculationSurfaces.h"
#include "calculation/Glare.h"

namespace candela {

struct Scene;
struct FalseColourLegend;

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
    std::string kind;          ///< "photometric", "GLDF", "light field", ...
    std::string manufacturer;  ///< From the file (IES [MANUFAC], EULUMDAT company, GLDF, TM-33).
    std::string product;       ///< The file's luminaire name or the GLDF product and variant.
    std::string file;          ///< The photometry or container, as the scene names it.
    double flux = 0.0;         ///< Each luminaire's, lm (W for a radiometric source).
    double power = 0.0;        ///< Each luminaire's input power, W; 0: not stated.
    double maintenanceFactor = 1.0;
};
std::vector<ScheduleRow> luminaireSchedule(const Scene& scene);

}  // namespace candela
