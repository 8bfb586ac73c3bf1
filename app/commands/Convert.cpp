// candela convert: a TM-25 ray file or a procedural luminaire to a light-field file, or an IES
// or EULUMDAT file to IES TM-33.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>

#include "app/commands/Commands.h"
#include "formats/Photometry.h"
#include "formats/Tm25RayFile.h"
#include "luminaires/lightfield/LightFieldRays.h"
#include "luminaires/lightfield/ProceduralLuminaire.h"
#include "report/Report.h"
#include "util/Error.h"
#include "util/FileOutput.h"

namespace candela {

namespace {

using Clock = std::chrono::steady_clock;

constexpr double kMmPerM = 1000.0;

struct ConvertOptions {
    std::string input, procedural, out;
    LayoutOptions layout;
    uint64_t rays = 0;
    bool rawFlux = false;
    bool layoutFlagGiven = false;  ///< --grid, --res, --delta, --axis or --coverage
};

double seconds(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
}

/// Percentages on stderr, at most one line a second, so short conversions stay quiet.
class Progress {
  public:
    explicit Progress(std::string what) : mWhat(std::move(what)), mLast(Clock::now()) {}
    void operator()(double fraction) {
        auto now = Clock::now();
        if (seconds(mLast, now) < 1.0) return;
        mLast = now;
        std::fprintf(stderr, "candela convert: %s %.0f %%\n", mWhat.c_str(), 100.0 * fraction);
    }

  private:
    std::string mWhat;
    Clock::time_point mLast;
};

glm::ivec2 parseGrid(const std::string& v) {
    int w = 0, h = 0;
    char x = 0, extra = 0;
    if (std::sscanf(v.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x' || w < 3 || h < 3 ||
        w > 64 || h > 64)
        throw InputError("--grid: expected WxH basis functions with each in 3..64, got \"" + v +
                         "\"");
    return {w, h};
}

SourceAxis parseAxis(const std::string& v) {
    if (v == "z") return SourceAxis::AsGiven;
    if (v == "main") return SourceAxis::MainAxis;
    throw InputError(
        "--axis: expected z (rays given with +z forward) or main (rotate the mean emission "
        "direction onto +z), got \"" +
        v + "\"");
}

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

/// An IES or EULUMDAT file's conversion to TM-33.
bool isPhotometryInput(const ConvertOptions& o) {
    std::string ext = lowerExtension(o.input);
    return ext == ".ies" || ext == ".ldt";
}

/// The options that belong to one form of the command: bad usage when they are mixed.
void checkForm(const ConvertOptions& o, const CommandLine& cli) {
    if (o.input.empty() && o.procedural.empty())
        throw CommandUsageError(
            "missing the file to convert (RAYS.TM25RAY, FILE.ies or FILE.ldt) or --procedural "
            "NAME",
            cli.shortHelp());
    if (!o.input.empty() && !o.procedural.empty())
        throw CommandUsageError("give a file to convert or --procedural NAME, not both (" +
                                    o.input + " and --procedural " + o.procedural + ")",
                                cli.shortHelp());
    if (o.out.empty())
        throw CommandUsageError(
            "missing --out (the file to write: NAME.lf.json, or NAME.xml for photometry)",
            cli.shortHelp());
    if (isPhotometryInput(o) && (o.layoutFlagGiven || o.rawFlux || o.rays > 0))
        throw CommandUsageError(
            "--grid, --res, --delta, --axis, --coverage, --raw-flux and --rays apply to ray "
            "files and procedural luminaires, not to photometry",
            cli.shortHelp());
    if (!o.procedural.empty() && (o.layoutFlagGiven || o.rawFlux))
        throw CommandUsageError(
            "--grid, --res, --delta, --axis, --coverage and --raw-flux apply to ray files; a "
            "procedural preset fixes its own layout",
            cli.shortHelp());
    if (o.procedural.empty() && !isPhotometryInput(o) && o.rays > 0)
        throw CommandUsageError("--rays applies to --procedural only", cli.shortHelp());
}

/// The output's folder and name, once the form is known.
void checkOutput(const ConvertOptions& o) {
    std::filesystem::path dir = std::filesystem::path(o.out).parent_path();
    if (!dir.empty() && !std::filesystem::is_directory(dir))
        throw InputError(o.out + ": the output folder " + dir.string() + " does not exist");
    if (isPhotometryInput(o)) {
        std::string ext = lowerExtension(o.out);
        if (ext != ".xml" && ext != ".iesxml")
            throw InputError(o.out +
                             ": the output of a photometry conversion is IES TM-33, named "
                             "NAME.xml or NAME.iesxml");
        return;
    }
    const std::string suffix = ".lf.json";
    if (o.out.size() <= suffix.size() ||
        o.out.compare(o.out.size() - suffix.size(), suffix.size(), suffix) != 0)
        throw InputError(o.out + ": the output must be named NAME.lf.json");
}

/// The command line into `o`; false when --help was asked for (printed).
bool parseArgs(const Args& args, ConvertOptions& o) {
    o.layout.resolution = {128, 128};
    CommandLine cli("convert");
    cli.argument("INPUT", o.input,
                 "the file to convert: a TM-25 ray file (RAYS.TM25RAY) or photometry (FILE.ies, "
                 "FILE.ldt); none with --procedural",
                 false);
    cli.output("--out", o.out, "FILE",
               "the file to write (required): NAME.lf.json for a light field (its images "
               "NAME_I_J.exr beside it), NAME.xml or NAME.iesxml for photometry");

    cli.group("ray-file options (RAYS.TM25RAY to a light field)");
    LayoutOptions& layout = o.layout;
    cli.option("--grid", "WxH", "basis functions on U, each 3..64 (5x5)",
               [&layout](const std::string& v) { layout.count = parseGrid(v); });
    cli.option("--res", "N", "pixels of each image on S, N x N, 4..4096 (128)",
               [&layout](const std::string& v) {
                   int n = parseInt("--res", v, 4, 4096);
                   layout.resolution = {n, n};
               });
    cli.number("--delta", layout.delta, 1e-6, 100.0, "METRES",
               "the distance from U to S, 1e-6..100 (default: the larger half-width of the box on "
               "U that keeps --coverage of the flux)");
    cli.option("--axis", "z|main",
               "z: the rays' +z is the emission axis (the default); main: rotate the "
               "flux-weighted mean emission direction onto +z",
               [&layout](const std::string& v) { layout.axis = parseAxis(v); });
    cli.number("--coverage", layout.coverage, 0.9, 0.99999, "C",
               "share of the forward flux that the box on U and the image on S each keep, "
               "0.9..0.99999 (0.995)");
    cli.flag("--raw-flux", o.rawFlux,
             "the rays' flux as the file stores it (default: per-ray values are relative weights, "
             "scaled to the header's total flux when it gives one)");

    cli.group("procedural headlight options");
    cli.option("--procedural", "bike-headlight|car-headlight",
               "a simulated headlight (dies, reflector and cover, traced) instead of a file; it "
               "fixes its own layout",
               [&o](const std::string& v) {
                   const std::vector<std::string>& presets = proceduralPresets();
                   if (std::find(presets.begin(), presets.end(), v) == presets.end())
                       throw InputError("--procedural: unknown procedural luminaire \"" + v +
                                        "\" (expected bike-headlight or car-headlight)");
                   o.procedural = v;
               });
    cli.option(
        "--rays", "N",
        "rays the dies emit, 1000..1e9 (32000000 for bike-headlight, 40000000 for "
        "car-headlight)",
        [&o](const std::string& v) { o.rays = uint64_t(parseDouble("--rays", v, 1000, 1e9)); });
    if (!cli.parse(args)) return false;
    for (const char* flag : {"--grid", "--res", "--delta", "--axis", "--coverage"})
        o.layoutFlagGiven = o.layoutFlagGiven || cli.given(flag);
    checkForm(o, cli);
    checkOutput(o);
    return true;
}

void printFlux(const char* label, double v, double total, const char* unit) {
    std::printf("%s %.6g %s (%.2f %%)", label, v, unit, total > 0.0 ? 100.0 * v / total : 0.0);
}

void printProjection(const ProjectionReport& r, const LightFieldLayout& l, const char* unit) {
    double dropped = r.backwardFlux + r.outsideImageFlux + r.outsideBasisFlux;
    printFlux("flux kept:", r.keptFlux, r.totalFlux, unit);
    std::printf("\n");
    printFlux("flux dropped:", dropped, r.totalFlux, unit);
    std::printf(
        ": backward %.4g %s (%llu rays), outside the image on S %.4g %s (%llu rays), "
        "outside the basis on U %.4g %s (%llu rays wholly)\n",
        r.backwardFlux, unit, (unsigned long long)r.backwardRays, r.outsideImageFlux, unit,
        (unsigned long long)r.outsideImageRays, r.outsideBasisFlux, unit,
        (unsigned long long)r.outsideBasisRays);
    std::printf("model flux (sum of C_m G_m): %.6g %s\n", r.modelFlux, unit);
    std::printf("delta: %.4g mm\n", l.delta * kMmPerM);
    glm::dvec2 last = l.origin + glm::dvec2(l.count - 1) * l.spacing;
    std::printf(
        "U: %dx%d basis functions, spacing %.4g x %.4g mm, nodes [%.4g, %.4g] x [%.4g, %.4g] mm\n",
        l.count.x, l.count.y, l.spacing.x * kMmPerM, l.spacing.y * kMmPerM, l.origin.x * kMmPerM,
        last.x * kMmPerM, l.origin.y * kMmPerM, last.y * kMmPerM);
    std::printf("S: %dx%d pixels over [%.4g, %.4g] x [%.4g, %.4g] mm\n", l.resolution.x,
                l.resolution.y, l.imageMin.x * kMmPerM, l.imageMax.x * kMmPerM,
                l.imageMin.y * kMmPerM, l.imageMax.y * kMmPerM);
}

int convertRayFile(const ConvertOptions& o) {
    // Checked before the rays are read; LightFieldData::save checks its images' names too.
    ProtectedInputs inputs({o.input});
    checkNotAnInput(o.out, "--out");
    auto t0 = Clock::now();
    Progress reading("reading rays");
    Tm25RayFile file = readTm25(
        o.input, [&](uint64_t done, uint64_t total) { reading(double(done) / double(total)); });
    const Tm25Header& h = file.header;
    std::fprintf(stderr, "candela convert: read %llu rays from %s\n",
                 (unsigned long long)file.rays.size(), o.input.c_str());
    for (const std::string& w : file.warnings)
        std::fprintf(stderr, "candela convert: warning: %s: %s\n", o.input.c_str(), w.c_str());
    auto t1 = Clock::now();

    Tm25FluxInfo flux;
    std::vector<EmittedRay> rays = raysFromTm25(file, !o.rawFlux, flux);
    LayoutOptions lo = o.layout;
    lo.what = o.input;
    LayoutChoice choice = chooseLayout(rays, lo);
    ProjectionReport report;
    Progress projecting("projecting rays");
    auto lf = projectRays(rays, choice, flux.unit, report, Estimator::FluxConserving,
                          [&](double f) { projecting(f); });
    auto t2 = Clock::now();
    lf->save(o.out);
    auto t3 = Clock::now();

    const char* unit = flux.photometric ? "lm" : "W";
    std::printf("converted: %s -> %s\n", o.input.c_str(), o.out.c_str());
    std::printf("source: TM-25 ray file, %s, %llu rays, date \"%s\"\n",
                h.creationMethod == 1   ? "measured"
                : h.creationMethod == 0 ? "simulated"
                                        : "unknown creation method",
                (unsigned long long)h.rayCount, h.dateTime.c_str());
    std::printf("flux in file header: %.6g lm (luminous), %.6g W (radiant)\n", h.luminousFlux,
                h.radiantFlux);
    std::printf("flux of the rays: %.6g %s (%s)", flux.raySum, unit,
                flux.photometric ? "luminous" : "radiant");
    if (flux.scale != 1.0)
        std::printf(", disagrees with the header: scaled by %.6g to the header's %.6g %s\n",
                    flux.scale, flux.headerTotal, unit);
    else if (std::isfinite(flux.headerTotal) && flux.headerTotal > 0.0)
        std::printf(", header / rays = %.6f\n", flux.headerTotal / flux.raySum);
    else
        std::printf("\n");
    printProjection(report, choice.layout, unit);
    glm::dvec3 axis = choice.meanDirection;
    std::printf(
        "frame: %s; mean direction (%.3f, %.3f, %.3f); U at z = %.4g mm of the %ssource frame\n",
        lo.axis == SourceAxis::AsGiven ? "+z as given"
        : choice.axisFallback          ? "+z kept (the source has no main axis)"
                                       : "main axis rotated onto +z",
        axis.x, axis.y, axis.z, choice.frame.uPlaneZ * kMmPerM,
        lo.axis == SourceAxis::AsGiven ? "" : "rotated ");
    std::printf("time: read %.2f s, project %.2f s, save %.2f s, total %.2f s\n", seconds(t0, t1),
                report.seconds, seconds(t2, t3), seconds(t0, t3));
    return 0;
}

int convertProcedural(const ConvertOptions& o) {
    auto t0 = Clock::now();
    ProceduralOptions po;
    po.rays = o.rays;
    Progress tracing("tracing " + o.procedural);
    po.progress = [&](double f) { tracing(f); };
    ProceduralResult r = buildProceduralLuminaire(o.procedural, po);
    auto t1 = Clock::now();
    r.data->save(o.out);
    auto t2 = Clock::now();
    std::printf("converted: procedural %s -> %s\n", o.procedural.c_str(), o.out.c_str());
    std::printf("source: %s; %llu rays traced, %llu leave through the cover\n",
                proceduralDescription(o.procedural).c_str(), (unsigned long long)r.emittedRays,
                (unsigned long long)r.exitRays);
    std::printf(
        "flux of the dies: %.6g lm; leaving through the cover: %.6g lm (the rest is absorbed)\n",
        r.emittedFlux, r.exitFlux);
    printProjection(r.report, r.layout, "lm");
    std::printf("time: trace %.2f s, project %.2f s, save %.2f s, total %.2f s\n", r.traceSeconds,
                r.report.seconds, seconds(t1, t2), seconds(t0, t2));
    return 0;
}

int convertPhotometry(const ConvertOptions& o) {
    ProtectedInputs inputs({o.input});
    checkNotAnInput(o.out, "--out");
    PhotometricData d = loadPhotometry(o.input);
    inputs.add(d.tiltPath);
    for (const std::string& w : d.warnings)
        std::fprintf(stderr, "candela convert: warning: %s\n", w.c_str());
    std::vector<std::string> notes;
    std::string xml = writeTm33(d, todayUtc(), notes);
    // Read back before anything is written: what lands on disk is a file Candela loads, with the
    // same table.
    PhotometricData back = parseTm33(xml, o.out);
    double flux = d.fluxFromTable(), backFlux = back.fluxFromTable();
    if (back.candela.size() != d.candela.size() || !(std::abs(backFlux - flux) <= 1e-9 * flux))
        throw InputError(o.out + ": the TM-33 document does not read back as " + o.input +
                         "'s table (an internal error; nothing was written)");
    writeFileAtomically(o.out, xml);
    std::printf("converted: %s (%s) -> %s (IES TM-33-18)\n", o.input.c_str(), d.format.c_str(),
                o.out.c_str());
    std::printf(
        "table: %zu vertical x %zu horizontal angles (unfolded), luminaire flux %.6g lm "
        "(exact quadrature; the TM-33 document's: %.6g lm)\n",
        d.vertical.size(), d.horizontal.size(), flux, backFlux);
    for (const std::string& n : notes) std::printf("note: %s\n", n.c_str());
    return 0;
}

}  // namespace

int cmdConvert(const Args& args) {
    ConvertOptions o;
    if (!parseArgs(args, o)) return 0;
    if (!o.input.empty() && isPhotometryInput(o)) return convertPhotometry(o);
    return o.procedural.empty() ? convertRayFile(o) : convertProcedural(o);
}

}  // namespace candela
