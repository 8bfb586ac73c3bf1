// The flux audit: every photometric file in tests/data and resources (IES, EULUMDAT, TM-33 and
// the GLDF containers' photometry), lit by every photometric technique, in a closed black box
// whose walls lie 0.1 m from the opening (or the technique's stated distance, if farther). The
// flux the six walls absorb is the file's flux (every ray leaving the opening lands on one) and
// must come out so within the technique's stated flux limit (TechniqueInfo::limits).
//
// The walls are integrated by Gauss-Legendre on panels graded to the scale the near light varies
// on (at most half the distance to the opening wide, with breaks at the opening's edges and the
// centre's foot). The `point` technique conserves flux exactly, so its audit in the same box is
// the quadrature's own error (a narrow beam inside a panel is what it misses); each technique
// is allowed its stated tolerance plus twice that. Every file runs on its own worker thread.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "luminaires/Registry.h"
#include "luminaires/photometric/PhotometricLuminaire.h"
#include "scene/SceneIo.h"
#include "shaders/shared/Constants.h"

namespace candela {
namespace {

namespace fs = std::filesystem;

/// The audit allows a technique its stated flux tolerance, plus twice the quadrature's error on
/// the point law in the same box (its flux is exactly the file's: what the rule misses of a
/// narrow beam), plus this.
constexpr double kQuadratureTolerance = 2e-3;
/// The quadrature must integrate the point law this well (narrow beams cost it most: 1.2 % on
/// defined.ies), or the audit measures nothing.
constexpr double kQuadratureLimit = 2e-2;
/// The walls' distance from the opening, metres, unless a technique states a farther one.
constexpr double kWallDistance = 0.1;
/// Gauss-Legendre points per panel and direction; each wall is cut into 2 x 2 panels at the
/// foot of the centre (where the irradiance peaks).
constexpr int kOrder = 4;
/// Panels are at most this times the distance to the opening wide (the wall's distance over the
/// opening's footprint), so the near light's variation spans a few of them.
constexpr double kPanelScale = 0.5;
/// Samples per point of the progressive techniques.
constexpr int kSpp = 32;

/// Photometric files that are meant to be refused, or whose container holds no photometry to read
/// (their tests are elsewhere).
bool refusedOnPurpose(const fs::path& p) {
    std::string name = p.filename().string();
    for (const char* bad :
         {"huge_candela.ies", "GldfWithMissingProduct.gldf", "GldfWithFiles.gldf",
          "GldfWithInvalidRoot.gldf", "Invalid Profile - 01.ies", "Truncated Profile - 01.IES",
          // Photometry only as a URL, under a name the container does not hold, empty, or a
          // variant whose geometry places no emitter.
          "GldfWithHeaderMandatory.gldf", "GldfWithLargeFiles.gldf", "GldfWithCodepage850.gldf",
          "GldfWithEncodingUtf8.gldf", "GldfWithNoFiles.gldf", "GldfWithMissingFiles.gldf",
          "GldfWithOrphanedFiles.gldf", "GldfWithMetaInfo.gldf"})
        if (name == bad) return true;
    return false;
}

/// Every photometric file the repository ships or tests with (not the fuzzing corpora, not the
/// L3D geometry's structure.xml).
std::vector<fs::path> photometricFiles() {
    std::vector<fs::path> out;
    for (const fs::path& root :
         {fs::path(CANDELA_TEST_DATA), fs::path(CANDELA_SOURCE_DIR) / "resources"})
        for (const auto& entry : fs::recursive_directory_iterator(root)) {
            if (!entry.is_regular_file()) continue;
            std::string ext = entry.path().extension().string();
            std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
            bool photometry = ext == ".ies" || ext == ".ldt" || ext == ".gldf" ||
                              (ext == ".xml" && entry.path().filename() != "structure.xml");
            if (photometry && !refusedOnPurpose(entry.path())) out.push_back(entry.path());
        }
    std::sort(out.begin(), out.end());
    return out;
}

/// The file as a luminaire at the origin aiming down.
std::unique_ptr<Luminaire> luminaireOf(const fs::path& file) {
    std::string ext = file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
    nlohmann::json entry = {{"type", ext == ".gldf" ? "gldf" : "photometric"},
                            {"file", file.string()},
                            {"position", {0, 0, 0}},
                            {"aim", {0, -1, 0}},
                            {"c0", {1, 0, 0}}};
    return parseLuminaire(entry, json::Where{file.string(), "luminaire"});
}

/// Gauss-Legendre nodes and weights on [-1, 1] (Newton on the Legendre polynomial).
void gaussLegendre(int n, std::vector<double>& x, std::vector<double>& w) {
    x.assign(size_t(n), 0.0);
    w.assign(size_t(n), 0.0);
    for (int i = 0; i < n; ++i) {
        double z = std::cos(gpu::kPi * (i + 0.75) / (n + 0.5)), dp = 0.0;
        for (int iter = 0; iter < 100; ++iter) {
            double p0 = 1.0, p1 = z;
            for (int k = 2; k <= n; ++k) {
                double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = n * (z * p1 - p0) / (z * z - 1.0);
            double dz = p1 / dp;
            z -= dz;
            if (std::abs(dz) < 1e-15) break;
        }
        x[size_t(i)] = z;
        w[size_t(i)] = 2.0 / ((1.0 - z * z) * dp * dp);
    }
}

struct Audit {
    double flux = 0.0;      ///< lm through the six walls.
    double stdError = 0.0;  ///< Of the progressive techniques' estimate, lm.
};

/// The flux absorbed by the walls of the box [lo, hi] (the luminaire's local frame: opening in
/// z = 0 about the centre, aim +z) under technique t.
Audit auditBox(const Luminaire& light, const TechniqueInfo& t, const glm::dvec3& lo,
               const glm::dvec3& hi, const glm::dvec3& openingLo, const glm::dvec3& openingHi) {
    std::vector<double> gx, gw;
    gaussLegendre(kOrder, gx, gw);
    glm::dvec3 ex, ey, ez;
    photometricModel(light)->photometricFrame(light.pose, ex, ey, ez);
    glm::dvec3 centre = light.emitterPose().position;
    Audit out;
    double variance = 0.0;
    EstimateOptions options;
    options.spp = kSpp;
    // Wall `axis` at coordinate `at` (inward normal along `inward`), spanning [lo, hi] in the two
    // other axes u, v.
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            double at = side == 0 ? lo[axis] : hi[axis];
            double h = std::abs(at);
            int u = (axis + 1) % 3, v = (axis + 2) % 3;
            glm::dvec3 inward(0.0);
            inward[axis] = side == 0 ? 1.0 : -1.0;
            // Panels along each of the wall's axes, graded to the scale the near light varies
            // on: breaks at the wall's ends, the opening's edges and the centre's foot, then
            // widths of at most half the distance to the opening (h over its footprint).
            auto panels = [&](int a) {
                std::vector<double> breaks = {lo[a], hi[a], 0.0, openingLo[a], openingHi[a]};
                std::sort(breaks.begin(), breaks.end());
                breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
                std::vector<std::pair<double, double>> out;
                for (size_t b = 0; b + 1 < breaks.size(); ++b) {
                    double x = breaks[b], end = breaks[b + 1];
                    if (x < lo[a] || end > hi[a]) continue;
                    while (x < end) {
                        double away = std::max({openingLo[a] - x, x - openingHi[a], 0.0});
                        double width = std::min(end - x, kPanelScale * std::max(h, away));
                        if (end - (x + width) < 1e-3 * width) width = end - x;
                        out.push_back({x, x + width});
                        x += width;
                    }
                }
                return out;
            };
            for (auto [u0, u1] : panels(u))
                for (auto [v0, v1] : panels(v))
                    for (int i = 0; i < kOrder; ++i)
                        for (int j = 0; j < kOrder; ++j) {
                            glm::dvec3 local(0.0);
                            local[axis] = at;
                            local[u] = 0.5 * (u0 + u1) + 0.5 * (u1 - u0) * gx[size_t(i)];
                            local[v] = 0.5 * (v0 + v1) + 0.5 * (v1 - v0) * gx[size_t(j)];
                            double weight =
                                0.25 * (u1 - u0) * (v1 - v0) * gw[size_t(i)] * gw[size_t(j)];
                            glm::dvec3 p = centre + local.x * ex + local.y * ey + local.z * ez;
                            glm::dvec3 n = inward.x * ex + inward.y * ey + inward.z * ez;
                            options.seed = uint64_t(axis * 7919 + side * 104729 + i * 131 + j) +
                                           uint64_t(1e6 * (u0 + 2.0 * v0));
                            Estimate e = t.irradiance(light, p, n, options);
                            out.flux += weight * e.irradiance.y;
                            variance += weight * weight * e.stdError.y * e.stdError.y;
                        }
        }
    out.stdError = std::sqrt(variance);
    return out;
}

/// One file's audit: every photometric technique in its box. Failures are collected as text
/// (the audit runs on several threads; gtest's assertions are for the main one).
std::string auditFile(const fs::path& file, int& checked) {
    std::string failures;
    std::unique_ptr<Luminaire> light;
    try {
        light = luminaireOf(file);
    } catch (const std::exception& e) {
        return file.string() + " does not load: " + e.what() + "\n";
    }
    const PhotometricLuminaire* photometric = photometricModel(*light);
    if (!photometric) return file.string() + " is not a photometric luminaire\n";
    double flux = light->power().y;
    if (!(flux > 0.0)) return {};  // a table of zeros: nothing to conserve
    glm::dvec2 lo(0.0), hi(0.0);
    for (const glm::dvec2& c : photometric->polygon()) {
        lo = glm::min(lo, c);
        hi = glm::max(hi, c);
    }
    const TechniqueInfo* point = findTechnique(LuminaireKind::Photometric, "point");
    for (const TechniqueInfo& t : techniques()) {
        if (t.kind != LuminaireKind::Photometric) continue;
        const StatedLimits& limits = t.limits;
        double margin = std::max(kWallDistance, limits.fromOpeningSizes * photometric->size());
        glm::dvec3 boxLo(lo - margin, -margin), boxHi(hi + margin, margin);
        glm::dvec3 openingLo(lo, 0.0), openingHi(hi, 0.0);
        Audit a = auditBox(*light, t, boxLo, boxHi, openingLo, openingHi);
        // The quadrature's own error in this box: the point law's, whose flux is exactly the
        // file's.
        double quadrature = std::abs(
            auditBox(*light, *point, boxLo, boxHi, openingLo, openingHi).flux / flux - 1.0);
        char line[512];
        if (quadrature > kQuadratureLimit) {
            std::snprintf(line, sizeof line, "%s: the quadrature of the point law is %.2f %% off\n",
                          file.filename().c_str(), 100.0 * quadrature);
            failures += line;
        }
        double allowed = (limits.fluxTolerance + 2.0 * quadrature + kQuadratureTolerance) * flux +
                         (t.progressive ? 4.0 * a.stdError : 0.0);
        if (!(std::abs(a.flux - flux) <= allowed)) {
            std::snprintf(line, sizeof line,
                          "%s, %s: the walls %.3g m from the opening absorb %.6g lm of its %.6g lm "
                          "(%+.2f %%; stated %.2f %%, quadrature %.2f %%, +- %.2f %%)\n",
                          file.filename().c_str(), std::string(t.name).c_str(), margin, a.flux,
                          flux, 100.0 * (a.flux / flux - 1.0), 100.0 * limits.fluxTolerance,
                          100.0 * quadrature, 100.0 * a.stdError / flux);
            failures += line;
        }
        if (std::getenv("CANDELA_FLUX_AUDIT_PRINT"))
            std::printf("audit|%s|%s|%+.3f|%.3f|%.3f\n", file.filename().c_str(),
                        std::string(t.name).c_str(), 100.0 * (a.flux / flux - 1.0),
                        100.0 * a.stdError / flux, 100.0 * quadrature);
        ++checked;
    }
    return failures;
}

TEST(FluxAudit, EveryTechniqueConservesEveryFilesFluxInAClosedBox) {
    std::vector<fs::path> files = photometricFiles();
    ASSERT_GE(files.size(), 70u) << "the audit should see every shipped and test photometric file";
    // The files on every core, each worker taking the next file.
    std::atomic<size_t> next{0};
    std::atomic<int> checked{0};
    std::mutex mutex;
    std::string failures;
    auto worker = [&] {
        for (size_t i = next++; i < files.size(); i = next++) {
            int n = 0;
            std::string f = auditFile(files[i], n);
            checked += n;
            std::lock_guard lock(mutex);
            failures += f;
        }
    };
    std::vector<std::thread> threads;
    for (unsigned k = 0; k < std::max(1u, std::thread::hardware_concurrency()); ++k)
        threads.emplace_back(worker);
    for (std::thread& t : threads) t.join();
    EXPECT_EQ(failures, "");
    EXPECT_GT(checked.load(), 700);  // 10 techniques on each of the 76 files
}

}  // namespace
}  // namespace candela
