// `candela bench --prost FILE... --out DIR`: the evaluation of Prost (2019), Sec. 6.2, for every
// photometric technique and every file given.
//
// The normalised setup: every file's intensity table on the same 1 x 1 m opening, at heights 0.1,
// 1.1, 3.1 and 5.1 m over a ground plane (of its lower edge while it stands vertical), its normal
// turned from horizontal (pi/2 from the ground's normal) to straight down (pi) in five steps. The ground is imaged from
// above (an orthographic grid of receivers through the production shading passes, the GPU probe).
// Per technique, file, height and rotation: NMSE (Eq. 6.7) against the `reference` technique,
// upper and lower error bounds (the extreme signed differences of the tone-mapped images, Eq. 6.8,
// which also saturate the error images: orange too bright, blue too dark), the NMSE of the near
// field (receivers within 1.5 m of the opening's centre, where the thesis sees light bumps), the
// light bumps (local maxima there that the smoothed reference does not have) and the GPU time of
// the shading pass.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <numbers>
#include <sstream>

#include "app/commands/BenchUtil.h"
#include "luminaires/PhotometricLuminaire.h"
#include "luminaires/Registry.h"
#include "renderer/ImageFile.h"
#include "renderer/Renderer.h"
#include "renderer/context/GlContext.h"
#include "util/Error.h"
#include "util/FileOutput.h"

namespace candela {

namespace fs = std::filesystem;

namespace {

constexpr double kHeights[] = {0.1, 1.1, 3.1, 5.1};
constexpr int kRotations = 5;  // angle to the ground's normal: pi/2, 5pi/8, 3pi/4, 7pi/8, pi

/// The ground region imaged at height H: a square of side 2 (2 + H) m, shifted 0.5 (2 + H) m
/// towards where the light faces when horizontal (+x), so every rotation's footprint is in view.
struct Region {
    double x0, x1, z0, z1;
};

Region regionFor(double height) {
    double s = 2.0 + height;
    return {-0.5 * s, 1.5 * s, -s, s};
}

struct Metrics {
    double nmse = 0.0, ueb = 0.0, leb = 0.0, nearNmse = 0.0, bumpiness = 0.0, gpuMs = 0.0;
};

/// Eq. (6.8) with a fixed scale: Ld = L / (1 + L), L = a E.
double toneMap(double e, double a) { return a * e / (1.0 + a * e); }

/// Eq. (6.7): mean over pixels of (R - A)^2 / (mean R * mean A).
double nmse(const std::vector<double>& r, const std::vector<double>& a, const std::vector<char>* mask = nullptr) {
    double sr = 0.0, sa = 0.0, se = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < r.size(); ++i) {
        if (mask && !(*mask)[i]) continue;
        sr += r[i];
        sa += a[i];
        se += (r[i] - a[i]) * (r[i] - a[i]);
        ++n;
    }
    if (n == 0) return 0.0;
    double mr = sr / double(n), ma = sa / double(n);
    return mr > 0.0 && ma > 0.0 ? se / double(n) / (mr * ma) : (se > 0.0 ? INFINITY : 0.0);
}

/// Pixels of the near field brighter than all 8 neighbours by more than 1 % of their mean: the
/// "light bumps" a fixed sample set leaves near the light (Prost Fig. 6.11).
int localMaxima(const std::vector<double>& img, const std::vector<char>& mask, int size) {
    int count = 0;
    for (int y = 1; y + 1 < size; ++y)
        for (int x = 1; x + 1 < size; ++x) {
            size_t k = size_t(y * size + x);
            if (!mask[k]) continue;
            double sum = 0.0;
            bool peak = true;
            for (int dy = -1; dy <= 1 && peak; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    if (!dx && !dy) continue;
                    double v = img[size_t((y + dy) * size + x + dx)];
                    peak = peak && img[k] > v;
                    sum += v;
                }
            if (peak && img[k] > 1.01 * sum / 8.0) ++count;
        }
    return count;
}

/// Orange where the approximation is too bright, blue where too dark, white where right; full
/// saturation at the bound (Prost Fig. 6.5).
void errorColour(double d, double ueb, double leb, unsigned char* out) {
    double t = d >= 0.0 ? (ueb > 0.0 ? std::min(1.0, d / ueb) : 0.0) : (leb < 0.0 ? std::min(1.0, d / leb) : 0.0);
    const double orange[3] = {255, 140, 0}, blue[3] = {30, 90, 255};
    const double* c = d >= 0.0 ? orange : blue;
    for (int k = 0; k < 3; ++k) out[k] = (unsigned char)std::lround(255.0 + t * (c[k] - 255.0));
}

/// A contact sheet: rows of cells, each cell an N x N RGB8 image.
struct Sheet {
    int cell, cols, rows;
    std::vector<unsigned char> rgb;
    Sheet(int cell_, int cols_, int rows_)
        : cell(cell_), cols(cols_), rows(rows_), rgb(size_t(cell_ * cols_) * size_t(cell_ * rows_) * 3, 40) {}
    unsigned char* at(int col, int row, int x, int y) {
        size_t w = size_t(cell * cols);
        return &rgb[((size_t(row * cell + y)) * w + size_t(col * cell + x)) * 3];
    }
};

/// Flux over pi I(0): 1 for a Lambertian (cosine) distribution, smaller for a spot, larger for
/// wide or side-emitting ones. A rough "how diffuse" figure for the summary.
double diffuseness(const PhotometricData& d) {
    double i0 = d.intensity({0.0, 0.0, 1.0});
    return i0 > 0.0 ? d.fluxFromTable() / (std::numbers::pi * i0) : INFINITY;
}

}  // namespace

int benchProst(const Args& args) {
    std::vector<std::string> files;
    std::string outDir = "bench-prost";
    int size = 128, refSpp = 2048;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "--prost") continue;
        if (a == "--out") outDir = flagValue(args, i);
        else if (a == "--size") size = parseInt(a, flagValue(args, i), 8, 2048);
        else if (a == "--reference-spp") refSpp = parseInt(a, flagValue(args, i), 16, 1 << 22);
        else if (a.rfind("--", 0) == 0) throw InputError("bench --prost: unknown option " + a);
        else if (fs::is_directory(a)) {
            for (const auto& e : fs::recursive_directory_iterator(a)) {
                std::string ext = e.path().extension().string();
                std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
                if (e.is_regular_file() && (ext == ".ies" || ext == ".ldt")) files.push_back(e.path().string());
            }
        } else files.push_back(a);
    }
    if (files.empty())
        throw InputError("usage: candela bench --prost FILE.ies|FILE.ldt|DIR... [--out DIR] [--size N] "
                         "[--reference-spp N]");
    std::sort(files.begin(), files.end());
    ProtectedInputs inputs(files);  // no result file may replace a photometric file
    fs::create_directories(outDir);

    std::vector<std::string> techniques;
    for (const auto& t : candela::techniques())
        if (t.kind == "photometric" && t.name != "reference") techniques.emplace_back(t.name);

    auto context = createOffscreenContext();
    ShaderLibrary shaders;
    Renderer renderer(shaders);

    std::ostringstream csv;  // results.csv, written when complete
    csv << "file,technique,height_m,rotation_deg,nmse,ueb,leb,near_nmse,bumps,gpu_ms\n";
    std::ostringstream perHeight;  // nmse_by_height.csv
    perHeight << "file,technique,height_m,nmse,near_nmse,bumps,gpu_ms\n";
    std::ostringstream summary;
    char line[512];
    std::snprintf(line, sizeof line,
                  "bench --prost: %zu files, %dx%d receivers per image, reference %d spp, context %s\n",
                  files.size(), size, size, refSpp, context->description().c_str());
    summary << line;

    // Per technique: sums over every (file, height) for the means in the summary.
    struct Totals {
        double logNmse = 0.0, nearNmse = 0.0, bump = 0.0, ms = 0.0;
        int count = 0, lowestFast = 0;
    };
    std::map<std::string, Totals> totals;
    int configurations = 0, hybridBeatsBoth = 0;

    const size_t N = size_t(size) * size_t(size);
    for (const std::string& file : files) {
        auto light = std::make_unique<PhotometricLuminaire>();
        try {
            light->data = PhotometricLuminaire::load(file);
            inputs.add(light->sourceFiles());  // its TILT file too
        } catch (const std::exception& e) {
            std::fprintf(stderr, "bench --prost: skipping %s\n", e.what());
            summary << "skipped: " << e.what() << "\n";
            continue;
        }
        light->file = file;
        light->openingOverride = {1.0, 1.0};  // the normalised light-emitting object
        light->updateOpening();
        Scene scene;
        scene.luminaires.push_back(std::move(light));
        auto& lum = static_cast<PhotometricLuminaire&>(*scene.luminaires[0]);
        std::string stem = fs::path(file).stem().string();
        for (char& c : stem)
            if (!std::isalnum((unsigned char)c) && c != '-' && c != '_') c = '_';
        std::snprintf(line, sizeof line, "\n%s: flux %.5g lm, diffuseness (flux / pi I(0)) %.3g\n", file.c_str(),
                      lum.data->fluxFromTable(), diffuseness(*lum.data));
        summary << line;

        for (double height : kHeights) {
            Region reg = regionFor(height);
            std::vector<glm::vec3> points(N), normals(N, glm::vec3(0, 1, 0));
            for (int j = 0; j < size; ++j)
                for (int i = 0; i < size; ++i)
                    points[size_t(j) * size_t(size) + size_t(i)] =
                        glm::vec3(float(reg.x0 + (i + 0.5) / size * (reg.x1 - reg.x0)), 0.f,
                                  float(reg.z0 + (j + 0.5) / size * (reg.z1 - reg.z0)));
            Sheet images(size, int(techniques.size()) + 1, kRotations);
            Sheet errors(size, int(techniques.size()), kRotations);
            std::map<std::string, std::vector<double>> allA;  // concatenated over rotations
            std::vector<double> allR;
            std::vector<char> allNear;
            std::map<std::string, Metrics> sums;
            for (int rot = 0; rot < kRotations; ++rot) {
                double angle = std::numbers::pi * (0.5 + 0.125 * rot);
                // The height is that of the opening's lowest edge when it stands vertical (Prost:
                // height 0.1 leaves 0.246 at 3 pi / 4 and 0.6 at pi), so its centre is 0.5 higher.
                lum.pose.position = {0.0, height + 0.5, 0.0};
                lum.pose.aim = {std::sin(angle), std::cos(angle), 0.0};
                lum.pose.c0 = {0.0, 0.0, 1.0};
                RenderSettings settings;
                settings.techniqueOverride = "reference";
                settings.seed = uint32_t(1 + rot);
                renderer.setSettings(settings);
                std::vector<glm::vec3> ref = renderer.probe(scene, points, normals, refSpp, size);
                std::vector<double> r(N);
                double mean = 0.0;
                for (size_t k = 0; k < N; ++k) mean += (r[k] = ref[k].y);
                mean /= double(N);
                double a = mean > 0.0 ? 1.0 / mean : 1.0;  // one tone-mapping scale for every technique
                std::vector<char> nearMask(N);
                for (size_t k = 0; k < N; ++k) {
                    glm::dvec3 d = glm::dvec3(points[k]) - lum.pose.position;
                    nearMask[k] = glm::length(d) < 1.5;
                }
                for (int y = 0; y < size; ++y)
                    for (int x = 0; x < size; ++x) {
                        unsigned char v = (unsigned char)std::lround(255.0 * std::pow(toneMap(r[size_t(y * size + x)], a), 1.0 / 2.2));
                        unsigned char* px = images.at(0, rot, x, y);
                        px[0] = px[1] = px[2] = v;
                    }
                std::vector<double> smooth(N, 0.0);  // the reference, 5 x 5 box (edges: what is inside)
                for (int y = 0; y < size; ++y)
                    for (int x = 0; x < size; ++x) {
                        double sum = 0.0;
                        int count = 0;
                        for (int dy = -2; dy <= 2; ++dy)
                            for (int dx = -2; dx <= 2; ++dx) {
                                int xx = x + dx, yy = y + dy;
                                if (xx < 0 || yy < 0 || xx >= size || yy >= size) continue;
                                sum += r[size_t(yy * size + xx)];
                                ++count;
                            }
                        smooth[size_t(y * size + x)] = sum / count;
                    }
                int smoothMaxima = localMaxima(smooth, nearMask, size);
                allR.insert(allR.end(), r.begin(), r.end());
                allNear.insert(allNear.end(), nearMask.begin(), nearMask.end());
                for (size_t t = 0; t < techniques.size(); ++t) {
                    settings.techniqueOverride = techniques[t];
                    renderer.setSettings(settings);
                    renderer.probe(scene, points, normals, 1, size);  // compile and warm up
                    std::vector<glm::vec3> img = renderer.probe(scene, points, normals, 1, size);
                    Metrics m;
                    for (const auto& p : renderer.stats().passes) m.gpuMs += p.gpuMs;
                    std::vector<double> A(N);
                    for (size_t k = 0; k < N; ++k) A[k] = img[k].y;
                    m.nmse = nmse(r, A);
                    m.nearNmse = nmse(r, A, &nearMask);
                    std::vector<double> diff(N);
                    m.ueb = 0.0;
                    m.leb = 0.0;
                    for (size_t k = 0; k < N; ++k) {
                        diff[k] = toneMap(A[k], a) - toneMap(r[k], a);
                        m.ueb = std::max(m.ueb, diff[k]);
                        m.leb = std::min(m.leb, diff[k]);
                    }
                    // Light bumps: local maxima near the light that the reference (smoothed by
                    // a 5 x 5 box, which removes its own noise) does not have.
                    m.bumpiness = std::max(0, localMaxima(A, nearMask, size) - smoothMaxima);
                    for (int y = 0; y < size; ++y)
                        for (int x = 0; x < size; ++x) {
                            size_t k = size_t(y * size + x);
                            unsigned char v = (unsigned char)std::lround(255.0 * std::pow(toneMap(A[k], a), 1.0 / 2.2));
                            unsigned char* px = images.at(int(t) + 1, rot, x, y);
                            px[0] = px[1] = px[2] = v;
                            errorColour(diff[k], m.ueb, m.leb, errors.at(int(t), rot, x, y));
                        }
                    csv << file << "," << techniques[t] << "," << height << "," << angle * 180.0 / std::numbers::pi << ","
                        << m.nmse << "," << m.ueb << "," << m.leb << "," << m.nearNmse << "," << m.bumpiness << ","
                        << m.gpuMs << "\n";
                    auto& acc = allA[techniques[t]];
                    acc.insert(acc.end(), A.begin(), A.end());
                    Metrics& s = sums[techniques[t]];
                    s.gpuMs += m.gpuMs / kRotations;
                    s.bumpiness += m.bumpiness / kRotations;
                }
            }
            std::string base = stem + "_h" + std::to_string(int(std::lround(height * 10)));
            writeImage8((fs::path(outDir) / (base + "_images.png")).string(), images.cell * images.cols,
                        images.cell * images.rows, images.rgb);
            writeImage8((fs::path(outDir) / (base + "_errors.png")).string(), errors.cell * errors.cols,
                        errors.cell * errors.rows, errors.rgb);
            // The height's NMSE over all its rotations (the thesis' Fig. 6.7-6.10 entries).
            ++configurations;
            std::string best;
            double bestNmse = INFINITY, hybrid = 0, scattered = 0, poisson = 0;
            std::snprintf(line, sizeof line, "  height %.1f m:", height);
            summary << line;
            for (const std::string& t : techniques) {
                Metrics& s = sums[t];
                s.nmse = nmse(allR, allA[t]);
                s.nearNmse = nmse(allR, allA[t], &allNear);
                perHeight << file << "," << t << "," << height << "," << s.nmse << "," << s.nearNmse << ","
                          << s.bumpiness << "," << s.gpuMs << "\n";
                Totals& tt = totals[t];
                tt.logNmse += std::log(std::max(s.nmse, 1e-12));
                tt.nearNmse += s.nearNmse;
                tt.bump += s.bumpiness;
                tt.ms += s.gpuMs;
                ++tt.count;
                if (t != "hybrid" && s.nmse < bestNmse) bestNmse = s.nmse, best = t;
                if (t == "hybrid") hybrid = s.nmse;
                if (t == "scattered") scattered = s.nmse;
                if (t == "mc-poisson-24") poisson = s.nmse;
                std::snprintf(line, sizeof line, " %s %.3g", t.c_str(), s.nmse);
                summary << line;
            }
            ++totals[best].lowestFast;
            if (hybrid <= scattered && hybrid <= poisson) ++hybridBeatsBoth;
            summary << "  (lowest: " << best << ")\n";
            std::fprintf(stderr, "bench --prost: %s height %.1f done\n", file.c_str(), height);
        }
    }
    writeFileAtomically((fs::path(outDir) / "nmse_by_height.csv").string(), perHeight.str());
    writeFileAtomically((fs::path(outDir) / "results.csv").string(), csv.str());

    summary << "\nover " << configurations << " (file, height) configurations: technique, geometric-mean NMSE, "
               "mean near-field NMSE, mean light bumps per image, mean GPU ms per image, times lowest NMSE\n";
    for (const std::string& t : techniques) {
        const Totals& tt = totals[t];
        if (tt.count == 0) continue;
        std::snprintf(line, sizeof line, "  %-14s %10.4g %10.4g %10.4g %9.2f %4d\n", t.c_str(),
                      std::exp(tt.logNmse / tt.count), tt.nearNmse / tt.count, tt.bump / tt.count, tt.ms / tt.count,
                      tt.lowestFast);
        summary << line;
    }
    std::snprintf(line, sizeof line, "hybrid has an NMSE no larger than both scattered and mc-poisson-24 in %d of %d\n",
                  hybridBeatsBoth, configurations);
    summary << line;
    writeFileAtomically((fs::path(outDir) / "summary.txt").string(), summary.str());
    std::fputs(summary.str().c_str(), stdout);

    // NMSE against GPU time per (file, height, technique), and NMSE by height.
    std::ostringstream gp;
    std::string list;
    for (const std::string& t : techniques) list += (list.empty() ? "" : " ") + t;
    gp << "set terminal pngcairo size 1000,420 noenhanced\nset datafile separator ','\nset logscale y\nset format y '%g'\n"
          "set grid\nset key outside right\nset multiplot layout 1,2\n"
          "set logscale x\nset xlabel 'GPU time of the shading pass per image (ms)'\nset ylabel 'NMSE (Eq. 6.7)'\n"
          "plot for [t in '" << list << "'] 'nmse_by_height.csv' using (strcol(2) eq t ? $7 : 1/0):4 "
          "with points pointsize 1 title t\n"
          "unset logscale x\nset xlabel 'height of the light (m)'\nset xrange [0:5.6]\n"
          "plot for [t in '" << list << "'] 'nmse_by_height.csv' using (strcol(2) eq t ? $3 + 0.05 * (strstrt('"
       << list << "', t) % 7) : 1/0):4 with points pointsize 1 notitle\nunset multiplot\n";
    writeFileAtomically((fs::path(outDir) / "plot.gp").string(), gp.str());
    runGnuplot(outDir, "nmse.png");
    std::printf("wrote %s/results.csv, nmse_by_height.csv, summary.txt and image sheets\n", outDir.c_str());
    return 0;
}

}  // namespace candela
