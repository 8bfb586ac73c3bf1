// The environment map on the GPU (renderer/passes/EnvironmentPass, shaders/environment_*.glsl)
// under OSMesa, against the CPU twin of luminaires/EnvironmentSampling (double precision) and the
// exact texel sum: the per-frame tables of Algorithm 1, a chi-square test of the GPU's light
// samples, the production shading pass through the GPU probe, hard cases, and the frame plan
// (which passes run, and that a static map is not rebuilt).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "luminaires/environment/EnvironmentSampling.h"
#include "renderer/Renderer.h"
#include "renderer/ShaderLibrary.h"
#include "renderer/passes/EnvironmentPass.h"
#include "scene/SceneIo.h"
#include "shaders/shared/Constants.h"
#include "tests/TestUtil.h"
#include "util/Error.h"

namespace candela {
namespace {

using gpu::kPi;
double lum(const glm::dvec3& c) {
    return luminanceOf(c);
}

std::shared_ptr<const EnvironmentMap> realMap(const char* file) {
    return EnvironmentMap::load(test::dataDir() + "/hdr/" + file);
}

std::shared_ptr<const EnvironmentMap> constantMap(float value, int w = 64) {
    return std::make_shared<EnvironmentMap>(
        w, w / 2, std::vector<glm::vec3>(size_t(w) * size_t(w / 2), glm::vec3(value)), 1.0, 0.0,
        "constant");
}

/// Irradiance through the production shading pass (Renderer::probe) for normals at the origin.
std::vector<glm::dvec3> gpuProbe(std::shared_ptr<const EnvironmentMap> map,
                                 const std::string& technique,
                                 const std::vector<glm::dvec3>& normals, int spp,
                                 int faceSize = 0) {
    test::glContext();
    static ShaderLibrary shaders;
    Renderer renderer(shaders);
    RenderSettings s;
    s.environmentTechnique = technique;
    s.environmentFaceSize = faceSize;
    renderer.setSettings(s);
    Scene scene;
    scene.environment = {{"file", "test"}};
    scene.environmentMap = std::move(map);
    std::vector<glm::vec3> p(normals.size(), glm::vec3(0.f)), n;
    for (const glm::dvec3& d : normals) n.push_back(glm::vec3(d));
    std::vector<glm::vec3> r = renderer.probe(scene, p, n, spp);
    std::vector<glm::dvec3> out;
    for (const glm::vec3& v : r) out.push_back(glm::dvec3(v));
    return out;
}

TEST(EnvironmentGl, TablesMatchTheCpuTwin) {
    test::glContext();
    ShaderLibrary shaders;
    SkyParams sky;
    sky.width = 256;
    for (std::shared_ptr<const EnvironmentMap> map :
         {realMap("noon_grass_256.hdr"), realMap("hilly_terrain_01_256.hdr"),
          std::shared_ptr<const EnvironmentMap>(makeSkyMap(sky))}) {
        const int n = 32;
        EnvironmentPass pass;
        pass.setMap(map, n);
        pass.buildTables(shaders);
        CubeMapDistribution cpu(*map, n);
        std::vector<glm::vec2> cube = pass.readCube();
        std::vector<gpu::EnvironmentFaceGpu> faces = pass.readFaces();
        std::vector<double> rows = pass.readRowCdf(), cols = pass.readColumnCdf();
        int mismatched = 0;
        double worst = 0.0;
        for (int f = 0; f < 6; ++f) {
            // I_f sums n^2 weights, a few of which differ slightly (below): 1e-3 relative
            // (measured at most 3.7e-4).
            EXPECT_NEAR(faces[size_t(f)].totals.x, cpu.faceImportance(f),
                        1e-3 * cpu.faceImportance(f) + 1e-30)
                << map->source() << " face " << f;
            for (int r = 0; r < n; ++r)
                for (int c = 0; c < n; ++c) {
                    glm::vec2 g = cube[(size_t(f) * n + r) * n + c];
                    double w = cpu.texelWeight(f, c, r), l = cpu.texelLuminance(f, c, r);
                    // Float atan is good to about 1e-5 (llvmpipe), so a subsample or an edge
                    // point near a lat-long texel's border may land in the neighbour where the
                    // CPU's doubles do not. The GPU samples its own tables and reports its own
                    // pdf, so this is no bias; here the tables must agree within 5 % on 99.5 %
                    // of the texels (measured: at most 5 of 6144 off by more on llvmpipe, 2 on
                    // an NVIDIA H200; with acos, NVIDIA's cubic fit moved 112-128).
                    if (std::abs(g.y - w) > 0.05 * w || std::abs(g.x - l) > 0.05 * l + 1e-30)
                        ++mismatched;
                    worst = std::max(worst, std::abs(g.y - w) / w);
                }
            // Each CDF starts at 0, never decreases, and ends at exactly 1 on a lit face.
            const double* colCdf = &cols[size_t(f) * (n + 1)];
            EXPECT_EQ(colCdf[0], 0.0);
            EXPECT_EQ(colCdf[n], faces[size_t(f)].totals.x > 0.f ? 1.0 : 0.0);
            for (int c = 0; c < n; ++c) {
                ASSERT_LE(colCdf[c], colCdf[c + 1]) << f << " " << c;
                const double* rowCdf = &rows[(size_t(f) * n + c) * (n + 1)];
                EXPECT_EQ(rowCdf[0], 0.0);
                for (int r = 0; r < n; ++r) ASSERT_LE(rowCdf[r], rowCdf[r + 1]);
            }
        }
        EXPECT_LE(mismatched, 6 * n * n / 200) << map->source();
        std::printf(
            "[ info ] %s: %d of %d cube texels differ from the CPU by more than 5 %%, "
            "largest relative weight difference %.2e\n",
            map->source().c_str(), mismatched, 6 * n * n, worst);
    }
}

TEST(EnvironmentGl, CdfsResolveTexelsFarBelowTheSun) {
    // A one-texel sun 1e8 times the sky: on its cube face the other texels weigh about 1e-3
    // (the face floor) / 64^2 = 2.4e-7 of the face, below a float CDF's resolution near 1
    // (6e-8 per step), which sampled them at the wrong rate (+12 % facing away from such a sun).
    // Each texel's probability as the sampler reads it (CDF differences) must match its weight
    // over the face's total, summed here in 64-bit from the GPU's own weights.
    test::glContext();
    ShaderLibrary shaders;
    std::vector<glm::vec3> rgb(64 * 32, glm::vec3(0.01f));
    rgb[10 * 64 + 20] = glm::vec3(1e6f);
    auto sun = std::make_shared<EnvironmentMap>(64, 32, rgb, 1.0, 0.0, "sun");
    const int n = 64;
    EnvironmentPass pass;
    pass.setMap(sun, n);
    pass.buildTables(shaders);
    std::vector<glm::vec2> cube = pass.readCube();
    std::vector<double> rows = pass.readRowCdf(), cols = pass.readColumnCdf();
    int sunFace = -1;
    float brightest = 0.f;
    for (size_t t = 0; t < cube.size(); ++t)
        if (cube[t].y > brightest) brightest = cube[t].y, sunFace = int(t / size_t(n * n));
    ASSERT_GE(sunFace, 0);
    double total = 0.0, smallest = 1.0, worst = 0.0;
    for (int t = 0; t < n * n; ++t) total += cube[size_t(sunFace * n * n + t)].y;
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c) {
            double expected = cube[size_t((sunFace * n + r) * n + c)].y / total;
            const double* col = &cols[size_t(sunFace) * (n + 1)];
            const double* row = &rows[(size_t(sunFace) * n + size_t(c)) * (n + 1)];
            double p = (col[c + 1] - col[c]) * (row[r + 1] - row[r]);
            smallest = std::min(smallest, expected);
            worst = std::max(worst, std::abs(p - expected) / expected);
        }
    // The weights are floats summed in float-float on the GPU: 1e-5 relative leaves room for
    // the float rounding of each prefix sum's division, and is 1e3 times below a float CDF's
    // error on the dimmest texels.
    EXPECT_LT(smallest, 1e-6);
    EXPECT_LT(worst, 1e-5);
    std::printf("[ info ] 1e8 sun: smallest texel probability %.3g, worst relative error %.3g\n",
                smallest, worst);
}

TEST(EnvironmentGl, SamplesPassChiSquareAndReportTheCpuPdf) {
    test::glContext();
    ShaderLibrary shaders;
    auto map = realMap("noon_grass_256.hdr");
    const int n = 16, pool = 1 << 15;
    EnvironmentPass pass;
    pass.setMap(map, n);
    pass.buildTables(shaders);
    pass.drawSamples(shaders, 12345u, pool);
    std::vector<gpu::EnvironmentSampleGpu> samples = pass.readSamples();
    CubeMapDistribution cpu(*map, n);
    for (int f = 0; f < 6; ++f) {
        std::vector<double> observed(size_t(n) * n, 0.0), expected(size_t(n) * n, 0.0);
        int pdfMismatch = 0;
        for (int k = 0; k < pool; ++k) {
            const gpu::EnvironmentSampleGpu& s = samples[size_t(f) * pool + size_t(k)];
            glm::dvec3 w(s.direction);
            ASSERT_GT(s.direction.w, 0.f);
            glm::dvec2 ab;
            ASSERT_EQ(cubeFaceOf(w, ab), f);
            int c = std::clamp(int((ab.x + 1.0) * 0.5 * n), 0, n - 1);
            int r = std::clamp(int((ab.y + 1.0) * 0.5 * n), 0, n - 1);
            observed[size_t(r) * n + c] += 1.0;
            // The pdf the shader divides by is the CPU's within 5 %, except where the tables
            // differ (see TablesMatchTheCpuTwin) or a sample lies within float rounding of a
            // texel edge: at most 1 % of the samples.
            double p = cpu.pdfFace(f, w);
            if (std::abs(s.direction.w - p) > 0.05 * p) ++pdfMismatch;
        }
        for (int r = 0; r < n; ++r)
            for (int c = 0; c < n; ++c)
                expected[size_t(r) * n + c] =
                    pool * cpu.texelWeight(f, c, r) / cpu.faceImportance(f);
        test::ChiSquareResult chi = test::chiSquare(observed, expected);
        // A correct sampler fails this 1 time in 1000 per face.
        EXPECT_GT(chi.pValue, 1e-3)
            << "face " << f << " chi2 " << chi.statistic << " dof " << chi.degreesOfFreedom;
        EXPECT_LE(pdfMismatch, pool / 100) << "face " << f;
    }
}

TEST(EnvironmentGl, ShadingPassMatchesTheReference) {
    const int spp = 1 << 15;
    for (const char* file : {"noon_grass_256.hdr", "hilly_terrain_01_256.hdr"}) {
        auto map = realMap(file);
        EnvironmentLighting lighting(map, EnvironmentPass::defaultFaceSize(*map), 256);
        EstimateOptions o;
        o.spp = spp;
        for (const std::string& technique :
             test::unbiasedGpuTechniques(LuminaireKind::Environment)) {
            std::vector<glm::dvec3> gpu = gpuProbe(map, technique, test::cubeNormals26(), spp);
            const TechniqueInfo* t = findTechnique(LuminaireKind::Environment, technique);
            for (size_t i = 0; i < gpu.size(); ++i) {
                glm::dvec3 nrm = test::cubeNormals26()[i];
                double ref = lum(environmentReference(lighting, {}, nrm, o).irradiance);
                // The CPU twin's standard error at the same spp measures this estimator's noise:
                // within 1 % (the issue's figure) plus 4 of those standard errors.
                double se = lum(t->irradiance(test::lightOf(lighting), {}, nrm, o).stdError);
                EXPECT_NEAR(lum(gpu[i]), ref, 0.01 * ref + 4.0 * se)
                    << file << " " << technique << " n " << nrm.x << "," << nrm.y << "," << nrm.z;
            }
        }
        // The Havran lights are deterministic: the GPU sums the same lights as the CPU.
        std::vector<glm::dvec3> havran = gpuProbe(map, "havran2005", test::cubeNormals26(), 1);
        for (size_t i = 0; i < havran.size(); ++i) {
            double cpu =
                lum(environmentHavran(lighting, {}, test::cubeNormals26()[i], o).irradiance);
            EXPECT_NEAR(lum(havran[i]), cpu, 1e-4 * cpu + 1e-6) << file << " " << i;
        }
    }
}

TEST(EnvironmentGl, ConstantMapGivesPiL) {
    const double L = 2.5;
    const int spp = 1 << 15;
    auto map = constantMap(float(L));
    EnvironmentLighting lighting(map, EnvironmentPass::defaultFaceSize(*map), 16);
    EstimateOptions o;
    o.spp = spp;
    for (const std::string& technique : test::unbiasedGpuTechniques(LuminaireKind::Environment)) {
        std::vector<glm::dvec3> e = gpuProbe(map, technique, test::cubeNormals26(), spp);
        const TechniqueInfo* t = findTechnique(LuminaireKind::Environment, technique);
        for (size_t i = 0; i < e.size(); ++i) {
            // No sampler here has the cosine in its pdf, so none is exact on a constant map:
            // 1e-3 plus 4 standard errors of the CPU twin at the same spp.
            double se =
                t->irradiance(test::lightOf(lighting), {}, test::cubeNormals26()[i], o).stdError.x;
            EXPECT_NEAR(e[i].x, kPi * L, 1e-3 * kPi * L + 4.0 * se) << technique << " " << i;
        }
    }
}

TEST(EnvironmentGl, BlackMapsAndHugeSunsStayFinite) {
    auto black = constantMap(0.f);
    std::vector<glm::vec3> rgb(64 * 32, glm::vec3(0.01f));
    rgb[10 * 64 + 20] = glm::vec3(1e6f);  // a one-texel sun 1e8 times the rest
    auto sun = std::make_shared<EnvironmentMap>(64, 32, rgb, 1.0, 0.0, "sun");
    for (const TechniqueInfo& info :
         techniquesOf(LuminaireKind::Environment)) {  // every technique with a GPU pass
        if (info.shader.empty()) continue;
        const std::string technique(info.name);
        for (const glm::dvec3& v : gpuProbe(black, technique, test::cubeNormals26(), 64)) {
            EXPECT_EQ(v, glm::dvec3(0.0)) << technique;  // exactly 0, no NaN
        }
        std::vector<glm::dvec3> e = gpuProbe(sun, technique, test::cubeNormals26(), 4096);
        for (size_t i = 0; i < e.size(); ++i) {
            ASSERT_TRUE(std::isfinite(e[i].x) && std::isfinite(e[i].y) && std::isfinite(e[i].z))
                << technique;
            EXPECT_GE(lum(e[i]), 0.0);
        }
        // Accuracy is not asserted here: for normals facing away from the sun, balanced and
        // uniform-faces send nearly all of the sun's face's samples to the sun behind the
        // surface, and one run misses that face's sky in front by 4-17 % (as the CPU twin does:
        // unbiased over many runs, heavy-tailed in one; Environment.HugeSunOnAFaceHalfBehind...).
    }
}

Scene groundScene(bool withBox) {
    std::string json =
        R"({"geometry": [{"plane": {"center": [0,0,0], "normal": [0,1,0], "size": [10,10]}})";
    if (withBox) json += R"(, {"box": {"center": [0,0.5,0], "size": [1,1,1]}})";
    json += R"(], "luminaires": [], "camera": {"position": [3,2.5,4], "target": [0,0.4,0]}})";
    Scene scene = parseScene(nlohmann::json::parse(json), "ground.json");
    scene.environment = {{"file", "test"}};
    scene.environmentMap = realMap("noon_grass_256.hdr");
    return scene;
}

std::vector<std::string> passNames(const FrameStats& stats) {
    std::vector<std::string> out;
    for (const PassTiming& p : stats.passes) out.push_back(p.name);
    return out;
}
bool has(const std::vector<std::string>& v, const std::string& s) {
    return std::find(v.begin(), v.end(), s) != v.end();
}

TEST(EnvironmentGl, TablesAreBuiltOnlyWhenTheMapChanges) {
    test::glContext();
    ShaderLibrary shaders;
    Renderer renderer(shaders);
    RenderSettings s;
    s.width = 64;
    s.height = 48;
    s.samplesPerFrame = 2;
    renderer.setSettings(s);
    Scene scene = groundScene(false);
    renderer.update(scene, kChangeAll);
    renderer.renderFrame();
    std::vector<std::string> first = passNames(renderer.stats());
    EXPECT_TRUE(has(first, "env:cdf"));
    EXPECT_TRUE(has(first, "env:samples"));
    EXPECT_TRUE(has(first, "shade:environment:balanced"));
    // A single ground plane cannot shadow itself: no shadow variant.
    EXPECT_FALSE(
        has(renderer.plan().stepOfKind(LuminaireKind::Environment)->program.defines, "SHADOWS"));
    renderer.renderFrame();
    std::vector<std::string> second = passNames(renderer.stats());
    EXPECT_FALSE(has(second, "env:cdf"));     // same map: the tables are kept
    EXPECT_TRUE(has(second, "env:samples"));  // a fresh pool of samples every frame
    // A new map (the next frame of a sequence, a moved sun) rebuilds them and restarts.
    scene.environmentMap = realMap("hilly_terrain_01_256.hdr");
    renderer.renderFrame();
    EXPECT_TRUE(has(passNames(renderer.stats()), "env:cdf"));
    EXPECT_EQ(renderer.stats().accumulatedFrames, 1);
    // Background pixels show the map; the image is finite everywhere.
    for (float v : renderer.readLinear()) ASSERT_TRUE(std::isfinite(v));
}

TEST(EnvironmentGl, ARoofShadowsTheGround) {
    // A thin box 1 m above the ground; the camera looks under it at the origin, whose sky it
    // hides by the closed-form rectangle form factor F (see the CPU twin of this test). In
    // illuminance mode the centre pixel holds E = pi L (1 - F).
    test::glContext();
    ShaderLibrary shaders;
    Renderer renderer(shaders);
    Scene scene = parseScene(nlohmann::json::parse(R"({"geometry": [
        {"plane": {"center": [0, 0, 0], "normal": [0, 1, 0], "size": [20, 20]}},
        {"box": {"center": [0.2, 1.025, -0.1], "size": [1.0, 0.05, 0.6]}}],
      "camera": {"position": [3, 0.9, 0], "target": [0, 0, 0], "fov_deg": 10}})"),
                             "roof.json");
    scene.environment = {{"file", "test"}};
    scene.environmentMap = constantMap(1.f);
    double expected = kPi * (1.0 - test::rectangleFormFactor(-0.3, 0.7, -0.4, 0.2, 1.0));
    for (const char* technique : {"balanced", "balanced-mis"}) {
        RenderSettings s;
        s.width = s.height = 33;  // odd: the centre pixel's ray hits the origin
        s.quantity = Quantity::Illuminance;
        s.samplesPerFrame = 256;
        s.maxSamples = 1 << 14;
        s.environmentTechnique = technique;
        renderer.setSettings(s);
        renderer.update(scene, kChangeAll);
        do renderer.renderFrame();
        while (!renderer.converged());
        ASSERT_TRUE(has(renderer.plan().stepOfKind(LuminaireKind::Environment)->program.defines,
                        "SHADOWS"));
        std::vector<float> e = renderer.readLinear();
        double centre = e[(16 * 33 + 16) * 3 + 1];
        // The pixel covers about 6 cm of ground along x (grazing view) where F changes by under
        // 0.3 %; the noise at 2^14 spp is about 0.3 % (CPU twin): 1.5 % holds both with margin,
        // and the roof's F (about 0.17) would be missed by far without shadows.
        EXPECT_NEAR(centre, expected, 0.015 * expected) << technique;
    }
}

TEST(EnvironmentGl, FractionalCountsChangeSmoothly) {
    // Temporal stability of Eq. (4)-(5). Scaling the sky near the zenith changes the face
    // energies, so mu_f(n) and N_f(n) move, while every face's CDF keeps its shape (a black band
    // around the +Y face keeps the scaled texels out of the other faces' weights): with the same
    // seed every frame, the light samples stay put. Fractional N_f (beta weights) then make each
    // probe change smoothly, as the exact change does; whole counts pop when mu_f N_s crosses
    // k + 1/2. Metric: the largest |step - exact step| over 26 normals and 40 steps, relative to E.
    const int w = 64, h = 32, steps = 40, spp = 16;
    auto mapAt = [&](int k) {
        std::vector<glm::vec3> rgb(size_t(w) * h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                double theta = kPi * (y + 0.5) / h, phi = 2.0 * kPi * (x + 0.5) / w;
                double up = std::cos(theta),
                       side = std::sin(theta) *
                              std::max(std::abs(std::cos(phi)), std::abs(std::sin(phi)));
                float v = 1.f + 3.f * float(x % 16 < 4);  // some structure in every face
                if (up > side / 0.8)
                    v *= float(1.0 + 0.03 * k);  // inside the +Y face
                else if (up > side * 0.8)
                    v = 0.f;  // the band around its border
                rgb[size_t(y) * w + x] = glm::vec3(v);
            }
        return std::make_shared<EnvironmentMap>(w, h, std::move(rgb), 1.0, 0.0, "scaled");
    };
    std::vector<std::vector<double>> exact;
    for (int k = 0; k < steps; ++k) {
        EnvironmentLighting lighting(mapAt(k), 16, 16);
        std::vector<double> e;
        for (const glm::dvec3& n : test::cubeNormals26())
            e.push_back(lum(environmentReference(lighting, {}, n, {}).irradiance));
        exact.push_back(e);
    }
    auto worstJump = [&](const char* technique) {
        std::vector<std::vector<glm::dvec3>> e;
        for (int k = 0; k < steps; ++k)
            e.push_back(gpuProbe(mapAt(k), technique, test::cubeNormals26(), spp, 16));
        double worst = 0.0;
        for (int k = 0; k + 1 < steps; ++k)
            for (size_t i = 0; i < exact[0].size(); ++i) {
                double step = lum(e[k + 1][i]) - lum(e[k][i]),
                       truth = exact[k + 1][i] - exact[k][i];
                worst = std::max(worst, std::abs(step - truth) / exact[k][i]);
            }
        return worst;
    };
    double fractional = worstJump("balanced"), whole = worstJump("balanced-integer");
    std::printf(
        "[ info ] largest frame-to-frame deviation from the exact change: fractional N_f %.4f, "
        "whole N_f %.4f\n",
        fractional, whole);
    // Measured (llvmpipe): 0.024 against 0.18. What is left with fractional counts comes from the
    // few cube texels that straddle the band and still change shape; whole counts jump by a
    // sample's worth, about 1/16 of a noisy estimate. Deterministic (fixed seed): the bounds
    // are twice the measured fractional figure, and a factor 3 between the two.
    EXPECT_LT(fractional, 0.05);
    EXPECT_LT(fractional, whole / 3.0);
}

TEST(EnvironmentGl, PlanRunsOnlyWhatTheSceneNeeds) {
    Scene plain = groundScene(false), boxed = groundScene(true);
    glm::mat4 vp = cameraViewProj(boxed.camera, 4.0 / 3.0);
    FramePlan p = planFrame(boxed, vp);
    ASSERT_TRUE(p.stepOfKind(LuminaireKind::Environment));
    EXPECT_TRUE(has(p.stepOfKind(LuminaireKind::Environment)->program.defines,
                    "SHADOWS"));  // the box shadows the ground
    EXPECT_TRUE(p.needsBvh);
    EXPECT_FALSE(planFrame(plain, vp).needsBvh);
    Scene none = groundScene(false);
    none.environmentMap.reset();
    FramePlan q = planFrame(none, vp);
    EXPECT_FALSE(q.stepOfKind(LuminaireKind::Environment));
    EXPECT_FALSE(has(q.passNames(), "env:cdf"));
    // The exact reference is CPU-only: rendering with it is refused with a clear message.
    EXPECT_THROW(planFrame(plain, vp, "environment=reference", Quantity::Radiance), InputError);
    EXPECT_THROW(planFrame(plain, vp, "environment=no-such", Quantity::Radiance), InputError);
    // global-cdf and havran2005 build their tables on the CPU: no cube passes.
    EXPECT_FALSE(has(planFrame(plain, vp, "environment=global-cdf", Quantity::Radiance).passNames(),
                     "env:cdf"));
}

}  // namespace
}  // namespace candela
