// `candela bench --prost FILE... --out DIR`: the evaluation of Prost (2019), Sec. 6.2, for every
// photometric technique and every file given.
//
// The normalised setup: every file's intensity table on the same 1 x 1 m opening, at heights 0.1,
// 1.1, 3.1 and 5.1 m over a ground plane (of its lower edge while it stands vertical), its normal
// turned from horizontal (pi/2 from the ground's normal) to straight down (pi) in five steps. The
// ground is imaged from above (an orthographic grid of receivers through the production shading
// passes, the GPU probe). Per technique, file, height and rotation: NMSE (Eq. 6.7) against the
// `reference` technique, upper and lower error bounds (the extreme signed differences of the
// tone-mapped images, Eq. 6.8, which also saturate the error images: orange too bright, blue too
// dark), the NMSE of the near field (receivers within 1.5 m of the opening's centre, where the
// thesis sees light bumps), the light bumps (local maxima there that the smoothed reference does
// not have) and the GPU time of the shading pass.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>

#include "app/commands/BenchHarness.h"
#include "app/commands/BenchUtil.h"
#include "luminaires/Registry.h"
#include "luminaires/photometric/PhotometricLuminaire.h"
#include "renderer/ImageFile.h"
#include "renderer/Renderer.h"
#include "shaders/shared/Constants.h"
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
double toneMap(double e, double a) {
    return a * e / (1.0 + a * e);
}

/// Eq. (6.7): mean over pixels of (R - A)^2 / (mean R * mean A).
double nmse(const std::vector<double>& r, const std::vector<double>& a,
            const std::vector<char>* mask = nullptr) {
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
    double t = d >= 0.0 ? (ueb > 0.0 ? std::min(1.0, d / ueb) : 0.0)
                        : (leb < 0.0 ? std::min(1.0, d / leb) : 0.0);
    const double orange[3] = {255, 140, 0}, blue[3] = {30, 90, 255};
    const double* c = d >= 0.0 ? orange : blue;
    for (int k = 0; k < 3; ++k) out[k] = (unsigned char)std::lround(255.0 + t * (c[k] - 255.0));
}

/// A contact sheet: rows of cells, each cell an N x N RGB8 image.
struct Sheet {
    int cell, cols, rows;
    std::vector<unsigned char> rgb;
    Sheet(int cell_, int cols_, int rows_)
        : cell(cell_),
          cols(cols_),
          rows(rows_),
          rgb(size_t(cell_ * cols_) * size_t(cell_ * rows_) * 3, 40) {}
    unsigned char* at(int col, int row, int x, int y) {
        size_t w = size_t(cell * cols);
        return &rgb[((size_t(row * cell + y)) * w + size_t(col * cell + x)) * 3];
    }
};

/// Flux over pi I(0): 1 for a Lambertian (cosine) distribution, smaller for a spot, larger for
/// wide or side-emitting ones. A rough "how diffuse" figure for the summary.
double diffuseness(const PhotometricData& d) {
    double i0 = d.intensity({0.0, 0.0, 1.0});
    return i0 > 0.0 ? d.fluxFromTable() / (gpu::kPi * i0) : INFINITY;
}

/// FILE.ies|FILE.ldt|DIR...: a folder stands for every .ies and .ldt file under it. Sorted;
/// InputError naming the arguments when there is no file at all (only empty folders).
std::vector<std::string> photometryFiles(const std::vector<std::string>& arguments) {
    std::vector<std::string> files;
    for (const std::string& argument : arguments) {
        if (!fs::is_directory(argument)) {
            files.push_back(argument);
            continue;
        }
        for (const auto& e : fs::recursive_directory_iterator(argument)) {
            std::string ext = e.path().extension().string();
            std::transform(ext.begin(), ext.end(), ext.begin(),
                           [](unsigned char c) { return char(std::tolower(c)); });
            if (e.is_regular_file() && (ext == ".ies" || ext == ".ldt"))
                files.push_back(e.path().string());
        }
    }
    if (files.empty()) {
        std::string given;
        for (const std::string& a : arguments) given += (given.empty() ? "" : ", ") + a;
        throw InputError(given + ": no .ies or .ldt file in " +
                         (arguments.size() == 1 ? "it" : "them"));
    }
    std::sort(files.begin(), files.end());
    return files;
}

/// The techniques Prost evaluates: the photometric ones that are exact in one frame (a fixed set
/// of samples or a closed form), in registry order, against the Monte Carlo reference.
std::vector<std::string> evaluatedTechniques() {
    std::vector<std::string> names;
    for (const TechniqueInfo& t : techniques())
        if (t.kind == LuminaireKind::Photometric && !t.progressive) names.emplace_back(t.name);
    return names;
}

/// Per technique: sums over every (file, height) for the means in the summary.
struct Totals {
    double logNmse = 0.0, nearNmse = 0.0, bump = 0.0, ms = 0.0;
    int count = 0, lowestFast = 0;
};

/// What the whole run shares.
struct ProstRun {
    const ProstOptions& options;
    std::vector<std::string> techniques;
    Renderer& renderer;
    fs::path out;
    CsvFile results{"file,technique,height_m,rotation_deg,nmse,ueb,leb,near_nmse,bumps,gpu_ms"};
    CsvFile perHeight{"file,technique,height_m,nmse,near_nmse,bumps,gpu_ms"};
    BenchSummary summary{};
    std::map<std::string, Totals> totals{};
    int configurations = 0, hybridBeatsBoth = 0;
};

/// One file at one height: its receivers, sheets and the images of every rotation.
struct HeightRun {
    HeightRun(const std::string& file_, const Scene& scene_, Luminaire& light_, double height_,
              int size, size_t techniques)
        : file(file_),
          scene(scene_),
          light(light_),
          height(height_),
          images(size, int(techniques) + 1, kRotations),
          errors(size, int(techniques), kRotations) {}
    const std::string& file;
    const Scene& scene;  ///< Holds `light` alone.
    Luminaire& light;
    double height;  ///< Of the opening's lowest edge when it stands vertical, m.
    std::vector<glm::vec3> points, normals;
    Sheet images, errors;
    std::map<std::string, std::vector<double>>
        allA;                  ///< Each technique's images, concatenated over rotations.
    std::vector<double> allR;  ///< The reference's.
    std::vector<char> allNear;
    std::map<std::string, Metrics> sums;
};

/// The reference of one rotation and what each technique is measured with.
struct RotationRef {
    int index = 0;
    double angle = 0.0;       ///< Of the opening's normal to the ground's normal, radians.
    RenderSettings settings;  ///< Its seed.
    std::vector<double> r;    ///< Reference illuminance per receiver.
    double a = 1.0;           ///< Tone-mapping scale, the same for every technique.
    std::vector<char> nearMask;
    int smoothMaxima = 0;  ///< Local maxima of the smoothed reference near the light.
};

/// Writes an N x N image of values, tone-mapped with scale a, into a sheet's cell.
void putGrey(Sheet& sheet, int col, int row, const std::vector<double>& values, double a) {
    for (int y = 0; y < sheet.cell; ++y)
        for (int x = 0; x < sheet.cell; ++x) {
            double v = values[size_t(y * sheet.cell + x)];
            unsigned char grey =
                (unsigned char)std::lround(255.0 * std::pow(toneMap(v, a), 1.0 / 2.2));
            unsigned char* px = sheet.at(col, row, x, y);
            px[0] = px[1] = px[2] = grey;
        }
}

/// The reference, 5 x 5 box (edges: what is inside).
std::vector<double> smoothed(const std::vector<double>& r, int size) {
    std::vector<double> smooth(r.size(), 0.0);
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
    return smooth;
}

/// Turns the light to rotation `rot` and renders the reference there.
RotationRef referenceAt(ProstRun& run, HeightRun& h, int rot) {
    RotationRef ref;
    ref.index = rot;
    ref.angle = gpu::kPi * (0.5 + 0.125 * rot);
    // The height is that of the opening's lowest edge when it stands vertical (Prost: height 0.1
    // leaves 0.246 at 3 pi / 4 and 0.6 at pi), so its centre is 0.5 higher.
    Luminaire& lum = h.light;
    lum.pose.position = {0.0, h.height + 0.5, 0.0};
    lum.pose.aim = {std::sin(ref.angle), std::cos(ref.angle), 0.0};
    lum.pose.c0 = {0.0, 0.0, 1.0};
    ref.settings.techniqueOverride = "reference";
    ref.settings.seed = uint32_t(1 + rot);
    run.renderer.setSettings(ref.settings);
    int size = run.options.size;
    std::vector<glm::vec3> img =
        run.renderer.probe(h.scene, h.points, h.normals, run.options.referenceSpp, size);
    size_t n = img.size();
    ref.r.resize(n);
    double mean = 0.0;
    for (size_t k = 0; k < n; ++k) mean += (ref.r[k] = img[k].y);
    mean /= double(n);
    ref.a = mean > 0.0 ? 1.0 / mean : 1.0;
    ref.nearMask.resize(n);
    for (size_t k = 0; k < n; ++k)
        ref.nearMask[k] = glm::length(glm::dvec3(h.points[k]) - lum.pose.position) < 1.5;
    putGrey(h.images, 0, rot, ref.r, ref.a);
    ref.smoothMaxima = localMaxima(smoothed(ref.r, size), ref.nearMask, size);
    h.allR.insert(h.allR.end(), ref.r.begin(), ref.r.end());
    h.allNear.insert(h.allNear.end(), ref.nearMask.begin(), ref.nearMask.end());
    return ref;
}

/// One technique at one rotation: its metrics, a results.csv row, its cells in the sheets.
void measureTechnique(ProstRun& run, HeightRun& h, const RotationRef& ref, size_t t) {
    const std::string& name = run.techniques[t];
    RenderSettings settings = ref.settings;
    settings.techniqueOverride = name;
    run.renderer.setSettings(settings);
    int size = run.options.size;
    run.renderer.probe(h.scene, h.points, h.normals, 1, size);  // compile and warm up
    std::vector<glm::vec3> img = run.renderer.probe(h.scene, h.points, h.normals, 1, size);
    Metrics m;
    for (const auto& p : run.renderer.stats().passes) m.gpuMs += p.gpuMs;
    size_t n = img.size();
    std::vector<double> A(n), diff(n);
    for (size_t k = 0; k < n; ++k) A[k] = img[k].y;
    m.nmse = nmse(ref.r, A);
    m.nearNmse = nmse(ref.r, A, &ref.nearMask);
    for (size_t k = 0; k < n; ++k) {
        diff[k] = toneMap(A[k], ref.a) - toneMap(ref.r[k], ref.a);
        m.ueb = std::max(m.ueb, diff[k]);
        m.leb = std::min(m.leb, diff[k]);
    }
    // Light bumps: local maxima near the light that the reference (smoothed by a 5 x 5 box,
    // which removes its own noise) does not have.
    m.bumpiness = std::max(0, localMaxima(A, ref.nearMask, size) - ref.smoothMaxima);
    putGrey(h.images, int(t) + 1, ref.index, A, ref.a);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x)
            errorColour(diff[size_t(y * size + x)], m.ueb, m.leb,
                        h.errors.at(int(t), ref.index, x, y));
    run.results.row(h.file, name, h.height, ref.angle * 180.0 / gpu::kPi, m.nmse, m.ueb, m.leb,
                    m.nearNmse, m.bumpiness, m.gpuMs);
    std::vector<double>& all = h.allA[name];
    all.insert(all.end(), A.begin(), A.end());
    Metrics& sum = h.sums[name];
    sum.gpuMs += m.gpuMs / kRotations;
    sum.bumpiness += m.bumpiness / kRotations;
}

/// The ground region imaged at the run's height, an orthographic grid of receivers facing up.
void placeReceivers(HeightRun& h, int size) {
    Region reg = regionFor(h.height);
    size_t n = size_t(size) * size_t(size);
    h.points.resize(n);
    h.normals.assign(n, glm::vec3(0, 1, 0));
    for (int j = 0; j < size; ++j)
        for (int i = 0; i < size; ++i)
            h.points[size_t(j) * size_t(size) + size_t(i)] =
                glm::vec3(float(reg.x0 + (i + 0.5) / size * (reg.x1 - reg.x0)), 0.f,
                          float(reg.z0 + (j + 0.5) / size * (reg.z1 - reg.z0)));
}

/// The height's sheets, and its NMSE over all its rotations (the thesis' Fig. 6.7-6.10
/// entries) in nmse_by_height.csv, the totals and the summary.
void summarizeHeight(ProstRun& run, HeightRun& h, const std::string& stem) {
    std::string base = stem + "_h" + std::to_string(int(std::lround(h.height * 10)));
    for (const auto& [sheet, suffix] :
         {std::pair{&h.images, "_images.png"}, std::pair{&h.errors, "_errors.png"}})
        writeImage8((run.out / (base + suffix)).string(), sheet->cell * sheet->cols,
                    sheet->cell * sheet->rows, sheet->rgb);
    ++run.configurations;
    std::string best;
    double bestNmse = INFINITY, hybrid = 0, scattered = 0, poisson = 0;
    run.summary.add("  height %.1f m:", h.height);
    for (const std::string& t : run.techniques) {
        Metrics& s = h.sums[t];
        s.nmse = nmse(h.allR, h.allA[t]);
        s.nearNmse = nmse(h.allR, h.allA[t], &h.allNear);
        run.perHeight.row(h.file, t, h.height, s.nmse, s.nearNmse, s.bumpiness, s.gpuMs);
        Totals& tt = run.totals[t];
        tt.logNmse += std::log(std::max(s.nmse, 1e-12));
        tt.nearNmse += s.nearNmse;
        tt.bump += s.bumpiness;
        tt.ms += s.gpuMs;
        ++tt.count;
        // Prost's comparison (Sec. 6.6): the lowest error among the fixed techniques, and the
        // hybrid against the two it blends.
        if (t != "hybrid" && s.nmse < bestNmse) bestNmse = s.nmse, best = t;
        if (t == "hybrid") hybrid = s.nmse;
        if (t == "scattered") scattered = s.nmse;
        if (t == "mc-poisson-24") poisson = s.nmse;
        run.summary.add(" %s %.3g", t.c_str(), s.nmse);
    }
    ++run.totals[best].lowestFast;
    if (hybrid <= scattered && hybrid <= poisson) ++run.hybridBeatsBoth;
    run.summary.addText("  (lowest: " + best + ")\n");
    std::fprintf(stderr, "bench --prost: %s height %.1f done\n", h.file.c_str(), h.height);
}

/// Every height and rotation of one file; a file that does not load is skipped and named.
void benchFile(ProstRun& run, const std::string& file, ProtectedInputs& inputs) {
    auto light = std::make_shared<PhotometricLuminaire>();
    try {
        light->data = PhotometricLuminaire::load(file);
        inputs.add(sourceFiles(Luminaire(light)));  // its TILT file too
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench --prost: skipping %s\n", e.what());
        run.summary.addText(std::string("skipped: ") + e.what() + "\n");
        return;
    }
    light->file = file;
    light->openingOverride = {1.0, 1.0};  // the normalised light-emitting object
    light->updateOpening();
    Scene scene;
    const PhotometricData& data = *light->data;
    scene.luminaires.push_back(placed(std::move(light)));
    Luminaire& lum = *scene.luminaires[0];
    std::string stem = fs::path(file).stem().string();
    for (char& c : stem)
        if (!std::isalnum((unsigned char)c) && c != '-' && c != '_') c = '_';
    run.summary.add("\n%s: flux %.5g lm, diffuseness (flux / pi I(0)) %.3g\n", file.c_str(),
                    data.fluxFromTable(), diffuseness(data));
    for (double height : kHeights) {
        HeightRun h(file, scene, lum, height, run.options.size, run.techniques.size());
        placeReceivers(h, run.options.size);
        for (int rot = 0; rot < kRotations; ++rot) {
            RotationRef ref = referenceAt(run, h, rot);
            for (size_t t = 0; t < run.techniques.size(); ++t) measureTechnique(run, h, ref, t);
        }
        summarizeHeight(run, h, stem);
    }
}

void addTotals(ProstRun& run) {
    run.summary.add(
        "\nover %d (file, height) configurations: technique, geometric-mean NMSE, mean near-field "
        "NMSE, "
        "mean light bumps per image, mean GPU ms per image, times lowest NMSE\n",
        run.configurations);
    for (const std::string& t : run.techniques) {
        const Totals& tt = run.totals[t];
        if (tt.count == 0) continue;
        run.summary.add("  %-14s %10.4g %10.4g %10.4g %9.2f %4d\n", t.c_str(),
                        std::exp(tt.logNmse / tt.count), tt.nearNmse / tt.count, tt.bump / tt.count,
                        tt.ms / tt.count, tt.lowestFast);
    }
    run.summary.add(
        "hybrid has an NMSE no larger than both scattered and mc-poisson-24 in %d of %d\n",
        run.hybridBeatsBoth, run.configurations);
}

/// NMSE against GPU time per (file, height, technique), and NMSE by height.
void plotNmse(const fs::path& out, const std::vector<std::string>& techniques) {
    std::string list;
    for (const std::string& t : techniques) list += (list.empty() ? "" : " ") + t;
    writePlot(out, 1000, 420,
              "set logscale y\nset format y '%g'\nset grid\nset key outside right\nset multiplot "
              "layout 1,2\n"
              "set logscale x\nset xlabel 'GPU time of the shading pass per image (ms)'\nset "
              "ylabel 'NMSE (Eq. 6.7)'\n"
              "plot for [t in '" +
                  list +
                  "'] 'nmse_by_height.csv' using (strcol(2) eq t ? $7 : 1/0):4 "
                  "with points pointsize 1 title t\n"
                  "unset logscale x\nset xlabel 'height of the light (m)'\nset xrange [0:5.6]\n"
                  "plot for [t in '" +
                  list + "'] 'nmse_by_height.csv' using (strcol(2) eq t ? $3 + 0.05 * (strstrt('" +
                  list + "', t) % 7) : 1/0):4 with points pointsize 1 notitle\nunset multiplot\n",
              "nmse.png");
}

}  // namespace

int benchProst(const ProstOptions& options) {
    ProstOptions o = options;
    o.files = photometryFiles(options.files);
    ProtectedInputs inputs(o.files);  // no result file may replace a photometric file
    BenchFolder folder(o.out);        // whole or not at all: committed at the end
    const fs::path& out = folder.path();
    BenchGpu gpu;
    ProstRun run{o, evaluatedTechniques(), gpu.renderer, out};
    run.summary.light(
        "each technique's direct light on an open ground plane (nothing casts a "
        "shadow); no interreflected light");
    run.summary.add(
        "bench --prost: %zu files, %dx%d receivers per image, reference %d spp, context %s\n",
        o.files.size(), o.size, o.size, o.referenceSpp, gpu.context->description().c_str());
    for (const std::string& file : o.files) benchFile(run, file, inputs);
    run.perHeight.write(out / "nmse_by_height.csv");
    run.results.write(out / "results.csv");
    addTotals(run);
    run.summary.write(out);
    plotNmse(out, run.techniques);
    folder.commit();
    std::printf("wrote %s/results.csv, nmse_by_height.csv, summary.txt and image sheets\n",
                o.out.c_str());
    return 0;
}

}  // namespace candela
