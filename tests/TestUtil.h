#pragma once
// Helpers shared by the tests: statistics for sampler tests and a GL context for *_gltest.cpp.

#include <gtest/gtest.h>

#include <cstddef>
#include <cstring>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

#include "luminaires/GpuTable.h"
#include "luminaires/Registry.h"
#include "luminaires/environment/EnvironmentLight.h"
#include "util/Error.h"

namespace candela {
class GlContext;
class Renderer;
struct RenderSettings;
struct Scene;
}  // namespace candela

namespace candela::test {

/// The names of a kind's techniques with a GPU pass that state they are unbiased (the samplers a
/// statistical test holds against a reference), in the registry's order.
inline std::vector<std::string> unbiasedGpuTechniques(LuminaireKind kind) {
    std::vector<std::string> out;
    for (const TechniqueInfo& t : techniquesOf(kind))
        if (t.progressive && !t.shader.empty() && t.limits.accuracy == StatedLimits::Unbiased)
            out.emplace_back(t.name);
    return out;
}

/// The environment as a source over tables a test built (its face size, its Havran lights), for
/// the registry's estimators: a placed luminaire on an EnvironmentLight model; it refers to
/// `lighting`, which must outlive it.
inline Luminaire lightOf(const EnvironmentLighting& lighting) {
    return *placedEnvironment(std::make_shared<const EnvironmentLight>(
        std::shared_ptr<const EnvironmentLighting>(std::shared_ptr<void>(), &lighting),
        Quantities::Radiometric));
}

/// Upper tail of the chi-square distribution with k degrees of freedom: P(X >= x).
double chiSquareSurvival(double x, double k);

struct ChiSquareResult {
    double statistic = 0.0;
    int degreesOfFreedom = 0;
    double pValue = 0.0;
};

/// Pearson's test of observed counts against expected counts. Cells whose expected count is
/// below 5 are pooled into one cell (the usual validity rule). The expected counts should sum
/// to the number of samples; mass outside the cells may be passed as one more cell.
ChiSquareResult chiSquare(const std::vector<double>& observed, const std::vector<double>& expected);

/// The message of the InputError that `f` throws (a test failure if it throws none).
template <class F>
std::string inputError(F f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    ADD_FAILURE() << "expected an InputError";
    return {};
}

/// One offscreen context for the whole GL test binary (created on first use; OSMesa unless
/// CANDELA_GL=egl picks a GPU driver, see createOffscreenContext).
GlContext& glContext();

/// Renders `scene` with `settings` until the renderer converges and returns the linear image
/// (RGB floats, rows as Renderer::readLinear gives them).
std::vector<float> renderConverged(Renderer& renderer, const Scene& scene,
                                   const RenderSettings& settings);

/// Runs a test compute shader (a path relative to shaders/, e.g. "../tests/shaders/x.comp") with
/// 64-wide groups over `count` inputs: `record` (a luminaire's gpuData) at binding 1, the inputs
/// at binding 6, the outputs at 7, the count in uniform location 0. Returns the output bytes.
/// `tables` (gpuTables(luminaire)), when given, are bound at their texture units.
std::vector<std::byte> runComputeTest(const std::string& shader,
                                      const std::vector<std::byte>& record, const void* inputs,
                                      size_t inputBytes, size_t count, size_t outputBytes,
                                      const GpuTables* tables = nullptr);

template <class Out, class In>
std::vector<Out> runComputeTest(const std::string& shader, const std::vector<std::byte>& record,
                                const std::vector<In>& in, const GpuTables* tables = nullptr) {
    std::vector<std::byte> bytes = runComputeTest(shader, record, in.data(), in.size() * sizeof(In),
                                                  in.size(), in.size() * sizeof(Out), tables);
    std::vector<Out> out(in.size());
    std::memcpy(out.data(), bytes.data(), bytes.size());
    return out;
}

/// The 26 unit directions from the centre of a cube to its face centres, edge midpoints and
/// corners (the normals the environment tests probe).
std::vector<glm::dvec3> cubeNormals26();

/// Form factor from a point at the origin (normal +Y) to the rectangle [x0, x1] x [z0, z1] in the
/// plane y = h > 0: the fraction of a uniform sky's irradiance the rectangle blocks. Closed form
/// (the corner rectangle of Howell's catalogue, C-11) combined by superposition.
double rectangleFormFactor(double x0, double x1, double z0, double z1, double h);

/// Folder of the test data (tests/data) and of the repository.
std::string dataDir();
std::string sourceDir();

}  // namespace candela::test
