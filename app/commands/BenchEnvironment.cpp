// `candela bench --environment sky|MAP.hdr|MAP.exr --out DIR`: what accuracy costs in time for
// the environment techniques (Lu et al. 2013), on a fixed scene (a ground, a matte box and a
// glossy box, so shadow rays and the Phong lobe both run) and view. Three parts, one run:
//  1. Error against samples and GPU time for each technique (relative RMSE of linear luminance
//     and mean CIE76 Delta E of the tone-mapped images against a converged reference), and the
//     samples uniform-faces needs to match balanced (the paper: 60 against 180);
//  2. Per-frame cost of a changing map at 128^2 and 256^2 faces: the table rebuild (Algorithm 1)
//     and the sample pools against the shading pass, with the sun moving every frame;
//  3. Temporal stability while the sun moves slowly (the metric is defined in part 3 below).
// Writes bench.csv, rebuild.csv, temporal.csv, summary.txt, the images and plots.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "app/commands/BenchUtil.h"
#include "app/commands/Commands.h"
#include "luminaires/Environment.h"
#include "renderer/ImageFile.h"
#include "renderer/Renderer.h"
#include "renderer/context/GlContext.h"
#include "scene/SceneIo.h"
#include "util/Error.h"
#include "util/FileOutput.h"

namespace candela {

namespace fs = std::filesystem;

namespace {

struct Shot {
    std::vector<float> linear;          ///< RGB radiance (cd/m2 for the sky)
    std::vector<unsigned char> display; ///< tone-mapped sRGB8
    double shadeMs = 0.0;               ///< GPU time of the environment shading pass
    double cdfMs = 0.0;                 ///< GPU time of the table rebuild (env:cdf)
    double samplesMs = 0.0;             ///< GPU time of the sample pools (env:samples)
};

/// The bench scene around `environment` (a scene-file "environment" object): a 20 m ground, a
/// matte 1 m box and a glossy one (Phong exponent from roughness 0.3), seen from 5 m.
Scene benchScene(const nlohmann::json& environment, const fs::path& outDir) {
    nlohmann::json doc = nlohmann::json::parse(R"({"geometry": [
        {"plane": {"center": [0, 0, 0], "normal": [0, 1, 0], "size": [20, 20]}, "albedo": [0.5, 0.5, 0.5]},
        {"box": {"center": [-0.7, 0.5, 0], "size": [1, 1, 1], "rotate_y_deg": 20}, "albedo": [0.7, 0.6, 0.5]},
        {"box": {"center": [0.9, 0.4, 0.6], "size": [0.8, 0.8, 0.8], "rotate_y_deg": -15},
         "albedo": [0.1, 0.2, 0.4], "specular": [0.5, 0.5, 0.5], "roughness": 0.3}],
      "camera": {"position": [3.2, 2.4, 4.2], "target": [0, 0.4, 0], "fov_deg": 50}})");
    doc["environment"] = environment;
    // Kept beside the results, so `candela render` can reproduce any image.
    writeFileAtomically((outDir / "bench_scene.json").string(), doc.dump(2) + "\n");
    return parseScene(doc, (outDir / "bench_scene.json").string());
}

Shot render(Renderer& renderer, const Scene& scene, RenderSettings settings, const std::string& technique,
            int spp, uint32_t seed, bool read = true) {
    settings.environmentTechnique = technique;
    settings.samplesPerFrame = std::min(spp, 64);
    settings.maxSamples = spp;
    settings.seed = seed;
    renderer.setSettings(settings);
    renderer.update(scene, kChangeAll);
    Shot shot;
    do {
        renderer.renderFrame();
        for (const auto& p : renderer.stats().passes) {
            if (p.name.rfind("shade:environment", 0) == 0) shot.shadeMs += p.gpuMs;
            else if (p.name == "env:cdf") shot.cdfMs += p.gpuMs;
            else if (p.name == "env:samples") shot.samplesMs += p.gpuMs;
        }
    } while (!renderer.converged());
    if (read) {
        shot.linear = renderer.readLinear();
        shot.display = renderer.readDisplay();
    }
    return shot;
}

double median(std::vector<double> v) {
    if (v.empty()) return std::nan("");
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

/// The sky of the bench with the sun at `azimuthDeg`.
std::shared_ptr<const EnvironmentMap> skyAt(SkyParams sky, double azimuthDeg) {
    sky.sunAzimuthDeg = azimuthDeg;
    return makeSkyMap(sky);
}

}  // namespace

int benchEnvironment(const Args& args) {
    std::string source, outDir = "bench-environment";
    std::vector<int> sppList = {4, 8, 16, 32, 64, 128, 256, 512};
    int refSpp = 16384, width = 480, height = 270, temporalFrames = 24, temporalSpp = 16, repeats = 4;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "--environment") source = flagValue(args, i);
        else if (a == "--out") outDir = flagValue(args, i);
        else if (a == "--spp") sppList = parseList(flagValue(args, i));
        else if (a == "--reference-spp") refSpp = parseInt(a, flagValue(args, i), 16, 1 << 22);
        else if (a == "--size") parseSize(flagValue(args, i), width, height);
        else if (a == "--frames") temporalFrames = parseInt(a, flagValue(args, i), 3, 10000);
        else if (a == "--repeats") repeats = parseInt(a, flagValue(args, i), 1, 64);
        else throw InputError("bench: unknown option " + a);
    }
    if (source.empty())
        throw InputError("usage: candela bench --environment sky|MAP.hdr|MAP.exr [--out DIR] [--spp 4,8,...] "
                         "[--reference-spp N] [--size WxH] [--frames N] [--repeats K]");
    fs::create_directories(outDir);
    const fs::path out(outDir);

    // The bench's sky: a clear noon-ish sun 35 degrees up (its disc a few texels of a 1024-wide
    // map, some 1e4 times the sky's luminance), the moving map of parts 2 and 3 in any case.
    SkyParams sky;
    sky.sunElevationDeg = 35.0;
    sky.sunAzimuthDeg = 120.0;
    sky.width = 1024;
    nlohmann::json environment =
        source == "sky" ? nlohmann::json{{"sky", {{"sun_elevation_deg", sky.sunElevationDeg},
                                                  {"sun_azimuth_deg", sky.sunAzimuthDeg},
                                                  {"resolution", sky.width}}}}
                        : nlohmann::json{{"file", fs::absolute(source).generic_string()}};
    ProtectedInputs inputs;  // the map (MAP.hdr|MAP.exr): bench_scene.json and every image must miss it
    if (source != "sky") inputs.add(source);
    Scene scene = benchScene(environment, out);
    auto context = createOffscreenContext();
    ShaderLibrary shaders;
    Renderer renderer(shaders);
    RenderSettings settings;
    settings.width = width;
    settings.height = height;

    std::ostringstream summary;
    char line[512];
    std::snprintf(line, sizeof line, "environment: %s (%dx%d lat-long), scene %s, %dx%d pixels\ncontext: %s\n",
                  source == "sky" ? "procedural sky, sun 35 deg up" : source.c_str(), scene.environmentMap->width(),
                  scene.environmentMap->height(), (out / "bench_scene.json").c_str(), width, height,
                  context->description().c_str());
    summary << line;

    // ---- 1. Error against samples and time -------------------------------------------------
    // The reference: balanced-mis converged (unbiased, and the most robust on the glossy box),
    // as two independent halves whose difference measures its own noise.
    std::fprintf(stderr, "bench: reference, 2 x %d spp at %dx%d\n", refSpp / 2, width, height);
    Shot half1 = render(renderer, scene, settings, "balanced-mis", refSpp / 2, 1000001);
    Shot half2 = render(renderer, scene, settings, "balanced-mis", refSpp / 2, 2000003);
    std::vector<float> ref(half1.linear.size());
    for (size_t i = 0; i < ref.size(); ++i) ref[i] = 0.5f * (half1.linear[i] + half2.linear[i]);
    double refNoise = 0.5 * relRmse(half1.linear, half2.linear);
    double avg = meanLuminance(ref);
    settings.fixedAverage = float(avg);  // every image tone-mapped against the reference's mean
    std::vector<unsigned char> refDisplay = render(renderer, scene, settings, "balanced-mis", refSpp / 2, 1000001).display;
    writeImage8((out / "reference.png").string(), width, height, refDisplay);
    writeImageFloat((out / "reference.exr").string(), width, height, ref);

    const char* techniques[] = {"balanced", "uniform-faces", "balanced-mis", "global-cdf"};
    for (const char* t : techniques) render(renderer, scene, settings, t, 1, 1);  // compile first
    std::vector<BenchRow> rows;
    uint32_t seed = 7;
    auto addRow = [&](const std::string& t, int spp, const Shot& s) {
        BenchRow r = benchRow(t, spp, s.shadeMs, s.linear, s.display, ref, refDisplay, refNoise);
        rows.push_back(r);
        std::fprintf(stderr, "bench: %-14s %6d spp  %9.2f ms  rel. RMSE %.4f (raw %.4f)  Delta E %.3f\n",
                     t.c_str(), spp, r.shadeMs, r.rmse, r.rawRmse, r.deltaE);
    };
    // Each point is the mean squared error of `repeats` images with independent seeds: the
    // balanced techniques share one pool of light samples per face among all pixels of a frame,
    // so part of a frame's error is common to every pixel and one image's rmse varies much
    // from seed to seed (their spread goes in the CSV).
    for (const char* t : techniques)
        for (int spp : sppList) {
            std::vector<BenchRow> images;
            for (int k = 0; k < repeats; ++k) {
                Shot s = render(renderer, scene, settings, t, spp, seed++);
                images.push_back(benchRow(t, spp, s.shadeMs, s.linear, s.display, ref, refDisplay, refNoise));
                if (k == 0 && (spp == sppList.front() || spp == 64 || spp == sppList.back()))
                    writeImage8((out / (std::string(t) + "_" + std::to_string(spp) + ".png")).string(), width,
                                height, s.display);
            }
            BenchRow r = meanRow(images);
            rows.push_back(r);
            std::fprintf(stderr, "bench: %-14s %6d spp  %9.2f ms  rel. RMSE %.4f +- %.4f over %d images  Delta E %.3f\n",
                         t, spp, r.shadeMs, r.rmse, r.rmseSpread, r.repeats, r.deltaE);
        }
    {
        render(renderer, scene, settings, "havran2005", 1, 1);  // compile; builds the lights
        Shot s = render(renderer, scene, settings, "havran2005", 1, seed++);
        addRow("havran2005", 1, s);
        writeImage8((out / "havran2005.png").string(), width, height, s.display);
    }
    writeBenchCsv((out / "bench.csv").string(), rows);
    std::snprintf(line, sizeof line,
                  "\n1. error against samples (reference: balanced-mis, %d spp, own noise %.5f removed in "
                  "quadrature; each error the root mean square over %d images of independent seeds)\n",
                  refSpp, refNoise, repeats);
    summary << line;
    for (int spp : sppList) {
        double eb = 0, eu = 0, em = 0, eg = 0, tb = 0;
        for (const BenchRow& r : rows) {
            if (r.spp != spp) continue;
            if (r.technique == "balanced") eb = r.rmse, tb = r.shadeMs;
            else if (r.technique == "uniform-faces") eu = r.rmse;
            else if (r.technique == "balanced-mis") em = r.rmse;
            else if (r.technique == "global-cdf") eg = r.rmse;
        }
        double needU = atError(rows, "uniform-faces", eb, false);
        double needUm = atError(rows, "uniform-faces", em, false);
        double timeU = atError(rows, "uniform-faces", eb, true);
        std::snprintf(line, sizeof line,
                      "%5d spp: rel. RMSE balanced %.4f, uniform-faces %.4f, balanced-mis %.4f, global-cdf "
                      "%.4f; uniform-faces needs %s the samples of balanced (%s of balanced-mis) and %s its "
                      "time\n",
                      spp, eb, eu, em, eg, formatRatio(needU / spp).c_str(), formatRatio(needUm / spp).c_str(),
                      formatRatio(timeU / tb).c_str());
        summary << line;
    }
    for (const BenchRow& r : rows)
        if (r.technique == "havran2005") {
            std::snprintf(line, sizeof line,
                          "havran2005 (256 lights, deterministic): rel. RMSE %.4f, Delta E %.3f in %.2f ms\n",
                          r.rmse, r.deltaE, r.shadeMs);
            summary << line;
        }

    // ---- 2. Per-frame cost of a changing map -----------------------------------------------
    // The sun moves every frame, so every frame gets a new map: Algorithm 1 runs each time.
    summary << "\n2. per frame with the sun moving (a new map every frame), medians of 8 frames\n";
    {
        std::ostringstream csv;  // rebuild.csv
        csv << "face_size,spp,cdf_ms,samples_ms,shade_ms,upload_and_sky_ms\n";
        for (int faceSize : {128, 256}) {
            for (int spp : {16, 64}) {
                RenderSettings s = settings;
                s.environmentFaceSize = faceSize;
                s.environmentTechnique = "balanced";
                s.samplesPerFrame = spp;
                s.maxSamples = 0;
                renderer.setSettings(s);
                std::vector<double> cdf, samples, shade, cpu;
                for (int frame = -1; frame < 8; ++frame) {  // frame -1 compiles and warms up
                    auto start = std::chrono::steady_clock::now();
                    scene.environmentMap = skyAt(sky, sky.sunAzimuthDeg + 0.5 * (frame + 2));  // rebuilt
                    renderer.update(scene, kChangeEnvironment);
                    renderer.renderFrame();
                    double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
                    double c = 0, smp = 0, sh = 0;
                    for (const auto& p : renderer.stats().passes) {
                        if (p.name == "env:cdf") c += p.gpuMs;
                        else if (p.name == "env:samples") smp += p.gpuMs;
                        else if (p.name.rfind("shade:environment", 0) == 0) sh += p.gpuMs;
                    }
                    if (frame < 0) continue;
                    cdf.push_back(c), samples.push_back(smp), shade.push_back(sh), cpu.push_back(wall);
                    csv << faceSize << "," << spp << "," << c << "," << smp << "," << sh << "," << wall << "\n";
                }
                std::snprintf(line, sizeof line,
                              "  %3d^2 faces, %2d spp/frame: tables %.2f ms + sample pools %.2f ms against "
                              "shading %.2f ms (tables %.0f %% of shading); whole frame incl. sky on the CPU "
                              "and upload %.0f ms wall\n",
                              faceSize, spp, median(cdf), median(samples), median(shade),
                              100.0 * median(cdf) / median(shade), median(cpu));
                summary << line;
                std::fprintf(stderr, "bench: %s", line);
            }
        }
        writeFileAtomically((out / "rebuild.csv").string(), csv.str());
    }

    // ---- 3. Temporal stability -------------------------------------------------------------
    // The sun moves by a fixed step a frame (0.01 degrees is the real sun's motion in about 2 s)
    // for `temporalFrames` frames of temporalSpp samples, every frame a new map and a new
    // accumulation. Metric: the flicker of static pixels, sqrt(sum_t,p (I_t+1(p) - I_t(p))^2 /
    // sum_t,p I_t(p)^2) over luminance, and its tail, the 99.9th percentile of
    // |I_t+1(p) - I_t(p)| / mean_p I over all pixel steps. The true change per step is measured
    // the same way between converged images of the first and last frame (the same seed for both),
    // divided by the number of steps.
    summary << "\n3. temporal stability: the sun moving a fixed step per frame, " << temporalFrames
            << " frames of " << temporalSpp << " spp, 128^2 faces\n";
    {
        struct Case {
            const char* name;
            const char* technique;
            bool freshSeed;
        };
        const Case cases[] = {{"balanced (fractional N_f, same seed)", "balanced", false},
                              {"balanced-integer (N_f rounded, same seed)", "balanced-integer", false},
                              {"balanced (fractional N_f, new seed per frame)", "balanced", true},
                              {"uniform-faces (same seed)", "uniform-faces", false},
                              {"havran2005 (filtered lights)", "havran2005", false}};
        std::ostringstream csv;  // temporal.csv
        csv << "sun_step_deg,case,frame,flicker_step\n";
        RenderSettings s = settings;
        s.environmentFaceSize = 128;
        auto luminances = [](const std::vector<float>& rgb) {
            std::vector<double> y(rgb.size() / 3);
            for (size_t i = 0; i < y.size(); ++i) y[i] = luma(&rgb[3 * i]);
            return y;
        };
        for (double step : {0.001, 0.01, 0.05}) {
            std::vector<double> first, last;
            for (int end : {0, 1}) {
                scene.environmentMap = skyAt(sky, sky.sunAzimuthDeg + step * end * (temporalFrames - 1));
                (end ? last : first) = luminances(render(renderer, scene, s, "balanced-mis", refSpp / 4, 77).linear);
            }
            double num = 0, den = 0;
            for (size_t i = 0; i < first.size(); ++i)
                num += (last[i] - first[i]) * (last[i] - first[i]), den += first[i] * first[i];
            std::snprintf(line, sizeof line, "  sun step %.3f deg/frame; change of converged images per step %.5f (an upper bound: their own decorrelation included)\n", step,
                          std::sqrt(num / den) / (temporalFrames - 1));
            summary << line;
            for (const Case& c : cases) {
                std::vector<double> prev, deltas;
                double sumD2 = 0, sumI2 = 0, sumI = 0;
                for (int frame = 0; frame < temporalFrames; ++frame) {
                    scene.environmentMap = skyAt(sky, sky.sunAzimuthDeg + step * frame);
                    auto y = luminances(render(renderer, scene, s, c.technique, temporalSpp,
                                               c.freshSeed ? uint32_t(101 + frame) : 101u).linear);
                    if (!prev.empty()) {
                        double d2 = 0, i2 = 0;
                        for (size_t i = 0; i < y.size(); ++i) {
                            double d = y[i] - prev[i];
                            d2 += d * d, i2 += prev[i] * prev[i], sumI += prev[i];
                            deltas.push_back(std::abs(d));
                        }
                        sumD2 += d2, sumI2 += i2;
                        csv << step << "," << c.technique << (c.freshSeed ? "-fresh-seed" : "") << "," << frame << ","
                            << std::sqrt(d2 / i2) << "\n";
                    }
                    prev = std::move(y);
                }
                double meanI = sumI / double(deltas.size());
                size_t k = size_t(0.999 * double(deltas.size()));
                std::nth_element(deltas.begin(), deltas.begin() + long(k), deltas.end());
                std::snprintf(line, sizeof line, "    %-48s flicker %.5f, 99.9th percentile step %.4f of the mean\n",
                              c.name, std::sqrt(sumD2 / sumI2), deltas[k] / meanI);
                summary << line;
                std::fprintf(stderr, "bench: step %.3f: %s", step, line);
            }
        }
        writeFileAtomically((out / "temporal.csv").string(), csv.str());
    }

    writeFileAtomically((out / "summary.txt").string(), summary.str());
    std::fputs(summary.str().c_str(), stdout);

    std::ostringstream gp;
    gp << "set terminal pngcairo size 1350,420 noenhanced\nset datafile separator ','\nset logscale xy\n"
          "set grid\nset key bottom left\nset multiplot layout 1,3\n"
          "set xlabel 'samples per pixel'\nset ylabel 'rel. RMSE (luminance, ref. noise removed)'\n"
       << sweepPlot("balanced uniform-faces balanced-mis global-cdf", 2, 4)
       << "set xlabel 'GPU time of the shading pass (ms)'\n"
       << sweepPlot("balanced uniform-faces balanced-mis global-cdf havran2005", 3, 4)
       << "unset logscale\nset logscale y\nset xlabel 'frame (sun +0.01 deg each)'\n"
          "set ylabel 'frame-to-frame change (rel. RMS)'\nset key top right\n"
          "plot for [t in 'balanced balanced-integer balanced-fresh-seed uniform-faces havran2005'] 'temporal.csv' "
          "using (strcol(2) eq t && $1 == 0.01 ? $3 : 1/0):4 with linespoints title t.' (0.01 deg/frame)'\n"
          "unset multiplot\n";
    writeFileAtomically((out / "plot.gp").string(), gp.str());
    runGnuplot(outDir, "error_vs_time.png");
    std::printf("wrote %s/bench.csv, rebuild.csv, temporal.csv and images\n", outDir.c_str());
    return 0;
}

}  // namespace candela
