#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>

#include "app/commands/Commands.h"
#include "calculation/CalculationGrid.h"
#include "calculation/Interreflection.h"
#include "luminaires/Registry.h"
#include "luminaires/environment/EnvironmentSampling.h"
#include "renderer/FramePlan.h"
#include "renderer/ImageFile.h"
#include "renderer/Renderer.h"
#include "renderer/ViewportMath.h"
#include "renderer/context/GlContext.h"
#include "scene/Bvh.h"
#include "scene/EmbreeVisibility.h"
#include "scene/SceneIo.h"
#include "util/Error.h"
#include "util/FileInput.h"
#include "util/FileOutput.h"

namespace candela {

namespace {

struct ProbePoint {
    glm::dvec3 p, n;
};

std::string trim(const std::string& s) {
    size_t a = s.find_first_not_of(" \t\r\n");
    size_t b = s.find_last_not_of(" \t\r\n");
    return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

/// Reads "x,y,z,nx,ny,nz" rows after that exact header; errors name the file and line.
std::vector<ProbePoint> readPoints(const std::string& path) {
    std::istringstream in(readInputFile(path, "points", kMaxTextBytes));
    std::string line;
    int lineNo = 0;
    std::vector<ProbePoint> points;
    bool header = false;
    while (std::getline(in, line)) {
        ++lineNo;
        std::string t = trim(line);
        if (t.empty()) continue;
        std::string where = path + ":" + std::to_string(lineNo) + ": ";
        if (!header) {
            std::string compact;
            for (char c : t)
                if (c != ' ') compact += c;
            if (compact != "x,y,z,nx,ny,nz")
                throw InputError(where + "expected the header x,y,z,nx,ny,nz, got \"" + t + "\"");
            header = true;
            continue;
        }
        std::stringstream ss(t);
        std::string field;
        double v[6];
        int count = 0;
        while (std::getline(ss, field, ',')) {
            if (count == 6) throw InputError(where + "expected 6 values, got more");
            std::string f = trim(field);
            char* end = nullptr;
            v[count] = std::strtod(f.c_str(), &end);
            if (f.empty() || *end != '\0' || !std::isfinite(v[count]))
                throw InputError(where + "expected a finite number in column " +
                                 std::to_string(count + 1) + ", got \"" + f + "\"");
            ++count;
        }
        if (count != 6) throw InputError(where + "expected 6 values, got " + std::to_string(count));
        glm::dvec3 n(v[3], v[4], v[5]);
        if (glm::length(n) < 1e-12) throw InputError(where + "expected a non-zero normal");
        points.push_back({{v[0], v[1], v[2]}, glm::normalize(n)});
    }
    if (!header) throw InputError(path + ": empty file (expected the header x,y,z,nx,ny,nz)");
    return points;
}

double lum(const glm::dvec3& c) {
    return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
}

/// --show-samples: Fig. 1-2 of Lu et al. 2013 for the first point's normal, as an image, and
/// the selected and effective samples per face on stderr (stdout stays the CSV).
void writeSampleChart(const Scene& scene, const glm::dvec3& normal, std::string_view technique,
                      int spp, const std::string& path) {
    if (!scene.environmentMap) throw InputError("--show-samples: the scene has no environment");
    bool balanced = technique != "uniform-faces";
    const EnvironmentMap& map = *scene.environmentMap;
    CubeMapDistribution cube(map, EnvironmentLighting::defaultFaceSize(map));
    SampleChart chart = sampleChart(map, cube, normal, spp, balanced, 1, 96);
    writeImage8(path, chart.width, chart.height, chart.rgb);
    const char* names[6] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};
    int drawn = 0, effective = 0;
    std::fprintf(
        stderr,
        "samples of %s at %d spp for n = (%.3f, %.3f, %.3f):\nface  share  selected  effective\n",
        balanced ? "balanced" : "uniform-faces", spp, normal.x, normal.y, normal.z);
    for (int f = 0; f < 6; ++f) {
        std::fprintf(stderr, "%-4s  %5.3f  %8d  %9d\n", names[f], chart.mu[size_t(f)],
                     chart.drawn[size_t(f)], chart.effective[size_t(f)]);
        drawn += chart.drawn[size_t(f)], effective += chart.effective[size_t(f)];
    }
    std::fprintf(stderr, "all   1.000  %8d  %9d (%.0f %% effective); chart in %s\n", drawn,
                 effective, drawn ? 100.0 * effective / drawn : 0.0, path.c_str());
}

/// --pixel X,Y: the surface point and normal the camera sees through that pixel of a
/// width x height render (x right, y down from the top-left, as in the rendered PNG).
ProbePoint pixelPoint(const Scene& scene, const std::string& text, int width, int height) {
    std::vector<float> xy = parseNumberList("--pixel", text);
    if (xy.size() != 2 || xy[0] < 0 || xy[1] < 0 || xy[0] >= width || xy[1] >= height)
        throw InputError("--pixel: expected X,Y inside the " + std::to_string(width) + "x" +
                         std::to_string(height) + " image (see --size), got \"" + text + "\"");
    int x = int(xy[0]), y = int(xy[1]);
    Bvh bvh = Bvh::build(scene);
    glm::mat4 viewProj = cameraViewProj(scene.camera, double(width) / double(height));
    std::optional<BvhHit> hit = pickSurface(bvh, viewProj, x + 0.5, y + 0.5, width, height);
    if (!hit)
        throw InputError("--pixel: pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                         ") of " + std::to_string(width) + "x" + std::to_string(height) +
                         " sees no surface");
    std::fprintf(stderr,
                 "pixel (%d, %d) of %dx%d sees (%.4f, %.4f, %.4f) m, normal (%.4f, %.4f, %.4f)\n",
                 x, y, width, height, hit->point.x, hit->point.y, hit->point.z, hit->normal.x,
                 hit->normal.y, hit->normal.z);
    return {hit->point, hit->normal};
}

/// What `candela probe` was asked for.
struct ProbeOptions {
    std::string scenePath, pointsPath, technique, envTechnique, device = "cpu";
    EstimateOptions estimate;
    bool withVisibility = false, indirect = false, noIndirect = false;
    bool byPixel = false;  ///< --pixel given (else --points).
    int patches = 4000;    ///< Asked of the interreflection's mesher.
    std::string visibilityBackend = "embree";
    std::string chartPath, pixel;
    int chartSpp = 64, width = 960, height = 540;
};

void declareProbeOptions(CommandLine& cli, ProbeOptions& o) {
    cli.argument("scene.json", o.scenePath, "the scene file");
    cli.option("--points", "pts.csv",
               "the points: CSV with the header x,y,z,nx,ny,nz, a point (metres) and its normal "
               "per line",
               [&o](const std::string& v) {
                   if (v.empty())
                       throw InputError("--points: expected a file name, got an empty one");
                   o.pointsPath = v;
               });
    cli.text("--pixel", o.pixel, "X,Y",
             "instead of --points: the surface the scene's camera sees through this pixel (x "
             "right, y down from the top-left, as in the rendered PNG), its normal towards the "
             "camera");
    cli.option("--size", "WxH", "with --pixel: the size of the render the pixel is in (960x540)",
               [&o](const std::string& v) { parseSize(v, o.width, o.height); });
    cli.text("--technique", o.technique, "T",
             "one technique for every luminaire (default: each luminaire's own); a name only the "
             "environment has applies to the environment alone");
    cli.text("--env-technique", o.envTechnique, "T",
             "the environment's technique (default: --technique's when it names one, else "
             "reference; on the GPU, balanced)");
    cli.integer("--spp", o.estimate.spp, 1, 1 << 26, "N",
                "samples per point of stochastic techniques (4096)");
    cli.option("--seed", "S", "the random numbers' seed, 0..1073741824 (1)",
               [&o](const std::string& v) {
                   o.estimate.seed = uint64_t(parseInt("--seed", v, 0, 1 << 30));
               });
    cli.optionalValue(
        "--visibility", {"embree", "bvh"},
        "shadows: a shadow ray per sample through Embree (embree, the default) or "
        "Candela's own BVH, the one the GPU traverses (bvh); without it, no shadows",
        [&o](const std::string& v) {
            if (!v.empty() && v != "embree" && v != "bvh")
                throw InputError("--visibility: expected embree or bvh, got \"" + v + "\"");
            o.withVisibility = true;
            o.visibilityBackend = v.empty() ? "embree" : v;
        });
    cli.flag("--indirect", o.indirect,
             "add interreflected light, a radiosity solution on the CPU (brings --visibility)");
    cli.flag("--no-indirect", o.noIndirect, "direct light alone (the default)");
    cli.integer("--patches", o.patches, 16, 50000, "N",
                "about this many patches for the interreflection (4000)");
    cli.option("--device", "cpu|gpu",
               "cpu: each technique's double-precision estimator (the default); gpu: the "
               "renderer's shading pass on a G-buffer made of the points",
               [&o](const std::string& v) {
                   if (v != "cpu" && v != "gpu")
                       throw InputError("--device: expected cpu or gpu, got \"" + v + "\"");
                   o.device = v;
               });
    cli.output("--show-samples", o.chartPath, "F.png",
               "with an environment: draw the light samples taken for the first point's normal on "
               "the unfolded cube into this image, the table per face on stderr");
    cli.integer("--chart-spp", o.chartSpp, 1, 4096, "N",
                "samples drawn in the --show-samples chart (64)");
    cli.strictPhotometry();
}

/// Refuses what cannot go together; --indirect brings --visibility (reflected light needs the
/// geometry, so it brings shadows for the direct light too).
void checkProbeOptions(const CommandLine& cli, ProbeOptions& o) {
    o.byPixel = cli.given("--pixel");
    if (!cli.given("--points") && !o.byPixel)
        throw CommandUsageError("missing --points pts.csv or --pixel X,Y (the points to probe)",
                                cli.shortHelp());
    if (cli.given("--points") && o.byPixel)
        throw CommandUsageError(
            "--points and --pixel: give one of them (points from a file, or the surface a pixel "
            "sees)",
            cli.shortHelp());
    if (cli.given("--size") && !o.byPixel)
        throw CommandUsageError("--size: an option of --pixel X,Y (the render the pixel is in)",
                                cli.shortHelp());
    if (o.indirect && o.noIndirect)
        throw CommandUsageError(
            "interreflected light both asked for (--indirect) and left out (--no-indirect): give "
            "one of them",
            cli.shortHelp());
    if (o.device == "gpu" && o.indirect)
        throw InputError(
            "--device gpu: --indirect is computed on the CPU only (the default device)");
    if (o.indirect && !o.withVisibility) {
        o.withVisibility = true;
        o.visibilityBackend = "embree";
    }
    if (o.device == "gpu" && o.withVisibility)
        throw InputError(
            "--device gpu: --visibility is not available on the GPU probe yet; "
            "use the CPU probe (the default)");
}

/// The environment's technique: --env-technique, else --technique when it names one of the
/// environment's, else the exact reference (on the GPU, which has no exact reference, balanced).
const TechniqueInfo* chooseEnvironmentTechnique(const ProbeOptions& o, const Scene& scene) {
    const TechniqueInfo* chosen = nullptr;
    if (!o.envTechnique.empty()) {
        chosen = findTechnique(LuminaireKind::Environment, o.envTechnique);
        if (!chosen)
            throw InputError("--env-technique: \"" + o.envTechnique +
                             "\" is not an environment "
                             "technique (available: " +
                             techniqueNames(LuminaireKind::Environment) + ")");
    } else {
        chosen = findTechnique(LuminaireKind::Environment,
                               o.technique.empty() ? "reference" : o.technique);
        if (!chosen) chosen = findTechnique(LuminaireKind::Environment, "reference");
    }
    if (o.device == "gpu" && scene.environmentMap && o.envTechnique.empty() &&
        chosen->shader.empty())
        chosen = findTechnique(LuminaireKind::Environment,
                               "balanced");  // the GPU has no exact reference
    if (o.device == "gpu" && scene.environmentMap && chosen->shader.empty())
        throw InputError("--env-technique: \"" + std::string(chosen->name) +
                         "\" runs on the CPU only; use the CPU probe (the default) or another "
                         "technique");
    return chosen;
}

/// Each luminaire's technique, resolved up front so a bad name fails before any work.
/// --technique applies to the luminaires, except that a name only the environment has leaves
/// them on their own techniques.
std::vector<const TechniqueInfo*> chooseTechniques(const Scene& scene,
                                                   const std::string& technique) {
    std::vector<const TechniqueInfo*> chosen;
    for (const auto& l : scene.luminaires) {
        std::string name = technique.empty() ? l->technique : technique;
        if (!technique.empty() && !findTechnique(l->kind(), technique) &&
            findTechnique(LuminaireKind::Environment, technique))
            name = l->technique;
        const TechniqueInfo* t = findTechnique(l->kind(), name);
        if (!t)
            throw InputError("--technique: \"" + name + "\" is not a technique of " +
                             std::string(kindName(l->kind())) +
                             " (available: " + techniqueNames(l->kind()) + ")");
        chosen.push_back(t);
    }
    return chosen;
}

/// Irradiance and its variance per point, luminance-weighted later.
struct ProbeSums {
    std::vector<glm::dvec3> E, var;
    explicit ProbeSums(size_t n) : E(n, glm::dvec3(0.0)), var(n, glm::dvec3(0.0)) {}
    void add(size_t i, const Estimate& e, double scale) {
        E[i] += scale * e.irradiance;
        var[i] += scale * scale * e.stdError * e.stdError;
    }
};

/// What the CPU probe needs besides the estimators: the shadow rays' scene and the radiosity.
struct CpuProbeSetup {
    std::unique_ptr<Bvh> bvh;
    std::unique_ptr<Visibility> visibility;
    std::unique_ptr<Interreflection> interreflection;
};

/// --visibility: shadow rays through Embree (the ray-traced reference); --visibility bvh:
/// through Candela's own BVH, the one the GPU traverses. --indirect: the radiosity solution,
/// whose final gather's standard error joins the direct light's (calculation/Interreflection.h).
CpuProbeSetup setUpCpuProbe(const Scene& scene, const ProbeOptions& o) {
    CpuProbeSetup setup;
    if (o.withVisibility && o.visibilityBackend == "bvh") {
        setup.bvh = std::make_unique<Bvh>(Bvh::build(scene));
        setup.visibility = std::make_unique<BvhVisibility>(*setup.bvh);
    } else if (o.withVisibility) {
        setup.visibility = std::make_unique<EmbreeVisibility>(scene);
    }
    if (o.indirect) {
        InterreflectionOptions io;
        io.mesh.targetPatches = o.patches;
        io.technique = o.technique;
        io.environmentTechnique = o.envTechnique;
        setup.interreflection = std::make_unique<Interreflection>(scene, io);
        std::fprintf(stderr, "probe: interreflection over %zu patches\n",
                     setup.interreflection->mesh().patches.size());
        if (std::string w = setup.interreflection->orientationWarning(scene); !w.empty())
            std::fprintf(stderr, "probe: warning: %s\n", w.c_str());
        setup.interreflection->compute();
    }
    return setup;
}

/// Every technique's double-precision C++ estimator at every point.
ProbeSums probeCpu(const Scene& scene, const std::vector<ProbePoint>& points, const ProbeOptions& o,
                   const TechniqueInfo& env, const std::vector<const TechniqueInfo*>& chosen) {
    CpuProbeSetup setup = setUpCpuProbe(scene, o);
    EstimateOptions options = o.estimate;
    options.visibility = setup.visibility.get();
    ProbeSums sums(points.size());
    for (size_t i = 0; i < points.size(); ++i) {
        const glm::dvec3 &p = points[i].p, &n = points[i].n;
        uint64_t pointSeed = options.seed * 1000003ull + i * 7919ull;
        EstimateOptions each = options;
        if (const Luminaire* environment = scene.environmentLight()) {
            each.seed = pointSeed + 999983ull;
            sums.add(i, env.irradiance(*environment, p, n, each), scene.environmentUnitScale());
        }
        if (setup.interreflection) {
            each.seed = pointSeed + 424242ull;
            sums.add(i, setup.interreflection->gather(p, n, each), 1.0);
        }
        for (size_t k = 0; k < scene.luminaires.size(); ++k) {
            each.seed = pointSeed + k;
            sums.add(i, chosen[k]->irradiance(*scene.luminaires[k], p, n, each),
                     scene.lightScale(*scene.luminaires[k]));
        }
    }
    return sums;
}

/// The production shading pass on a G-buffer made of the points.
ProbeSums probeGpu(const Scene& scene, const std::vector<ProbePoint>& points, const ProbeOptions& o,
                   const TechniqueInfo& env) {
    auto context = createOffscreenContext();
    ShaderLibrary shaders;
    Renderer renderer(shaders);
    RenderSettings s;
    s.techniqueOverride = o.technique;
    s.environmentTechnique = std::string(env.name);
    renderer.setSettings(s);
    std::vector<glm::vec3> p, n;
    for (const auto& q : points) {
        p.push_back(glm::vec3(q.p));
        n.push_back(glm::vec3(q.n));
    }
    std::vector<glm::vec3> r = renderer.probe(scene, p, n, o.estimate.spp);
    ProbeSums sums(points.size());
    for (size_t i = 0; i < points.size(); ++i) sums.E[i] = glm::dvec3(r[i]);
    return sums;
}

/// The CSV on stdout (a stable contract); its unit on stderr (and in docs/command-line.md).
void printProbeCsv(const Scene& scene, const std::vector<ProbePoint>& points, const ProbeSums& sums,
                   bool shadows, bool indirect) {
    UnitSystem units = scene.units();
    std::fprintf(stderr, "probe: E, E_r, E_g, E_b and E_stderr in %s%s\n",
                 units.irradianceLabel().c_str(),
                 indirect ? ", direct plus interreflected light" : "");
    std::fprintf(stderr, "probe: %s\nprobe: %s\n", scene.maintenanceNote().c_str(),
                 scene.bodiesNote().c_str());
    // A tool for comparing techniques: direct light without shadows unless asked for.
    GridSpec light;
    light.visibility = shadows;
    light.indirect = indirect;
    std::fprintf(stderr, "probe: light: %s%s\n", lightStatement(scene, light).c_str(),
                 shadows && indirect ? ""
                                     : " (probe's default; --visibility and --indirect "
                                       "add shadows and interreflected light)");
    std::printf("x,y,z,nx,ny,nz,E,E_r,E_g,E_b,E_stderr\n");
    for (size_t i = 0; i < points.size(); ++i) {
        const ProbePoint& q = points[i];
        const glm::dvec3& E = sums.E[i];
        glm::dvec3 se = glm::sqrt(sums.var[i]);
        std::printf("%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.10g,%.10g,%.10g,%.10g,%.4g\n", q.p.x, q.p.y,
                    q.p.z, q.n.x, q.n.y, q.n.z, lum(E), E.x, E.y, E.z, lum(se));
    }
}

}  // namespace

int cmdProbe(const Args& args) {
    ProbeOptions o;
    CommandLine cli("probe");
    declareProbeOptions(cli, o);
    if (!cli.parse(args)) return 0;
    checkProbeOptions(cli, o);
    Scene scene = loadScene(o.scenePath);
    std::vector<ProbePoint> points =
        o.byPixel ? std::vector<ProbePoint>{pixelPoint(scene, o.pixel, o.width, o.height)}
                  : readPoints(o.pointsPath);
    ProtectedInputs inputs(scene.inputFiles());
    inputs.add(o.pointsPath);
    checkNotAnInput(o.chartPath, "--show-samples");
    const TechniqueInfo* env = chooseEnvironmentTechnique(o, scene);
    std::vector<const TechniqueInfo*> chosen = chooseTechniques(scene, o.technique);
    ProbeSums sums = o.device == "cpu" ? probeCpu(scene, points, o, *env, chosen)
                                       : probeGpu(scene, points, o, *env);
    if (!o.chartPath.empty() && points.empty())
        throw InputError("--show-samples: " + o.pointsPath + " has no points");
    if (!o.chartPath.empty())
        writeSampleChart(scene, points.front().n, env->name, o.chartSpp, o.chartPath);
    printProbeCsv(scene, points, sums, o.withVisibility, o.indirect);
    return 0;
}

}  // namespace candela
