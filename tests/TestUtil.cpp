#include "tests/TestUtil.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "renderer/Renderer.h"
#include "renderer/ShaderLibrary.h"
#include "renderer/context/GlContext.h"
#include "renderer/gl/GlObjects.h"
#include "renderer/passes/LuminairePass.h"

namespace candela::test {

// Regularised upper incomplete gamma Q(a, x), by series for x < a + 1 and by the continued
// fraction (modified Lentz) otherwise (Numerical Recipes' split; our own implementation).
static double gammaQ(double a, double x) {
    if (x <= 0.0) return 1.0;
    double lnPrefix = a * std::log(x) - x - std::lgamma(a);
    if (x < a + 1.0) {
        double term = 1.0 / a, sum = term;
        for (int n = 1; n < 10000 && std::abs(term) > std::abs(sum) * 1e-16; ++n) {
            term *= x / (a + n);
            sum += term;
        }
        return std::clamp(1.0 - sum * std::exp(lnPrefix), 0.0, 1.0);
    }
    const double tiny = 1e-300;
    double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
    for (int i = 1; i < 10000; ++i) {
        double an = -i * (i - a);
        b += 2.0;
        d = an * d + b;
        if (std::abs(d) < tiny) d = tiny;
        c = b + an / c;
        if (std::abs(c) < tiny) c = tiny;
        d = 1.0 / d;
        double delta = d * c;
        h *= delta;
        if (std::abs(delta - 1.0) < 1e-16) break;
    }
    return std::clamp(std::exp(lnPrefix) * h, 0.0, 1.0);
}

double chiSquareSurvival(double x, double k) {
    return gammaQ(0.5 * k, 0.5 * x);
}

ChiSquareResult chiSquare(const std::vector<double>& observed,
                          const std::vector<double>& expected) {
    ChiSquareResult r;
    double pooledObs = 0.0, pooledExp = 0.0;
    int cells = 0;
    for (size_t i = 0; i < observed.size(); ++i) {
        if (expected[i] < 5.0) {
            pooledObs += observed[i];
            pooledExp += expected[i];
            continue;
        }
        double d = observed[i] - expected[i];
        r.statistic += d * d / expected[i];
        ++cells;
    }
    if (pooledExp > 0.0) {
        double d = pooledObs - pooledExp;
        r.statistic += d * d / pooledExp;
        ++cells;
    } else if (pooledObs > 0.0) {
        r.statistic = 1e300;  // samples where the pdf says none can be
    }
    r.degreesOfFreedom = std::max(1, cells - 1);
    r.pValue = chiSquareSurvival(r.statistic, r.degreesOfFreedom);
    return r;
}

namespace {

/// Every GL context a test makes reports to this (KHR_debug, synchronous): a GL error fails the
/// test that caused it, whatever the build type.
void failOnGlError(bool error, const char* message) {
    if (error) ADD_FAILURE() << "GL error: " << message;
}

const bool kGlErrorsFail = (setGlDebugHandler(&failOnGlError), true);

}  // namespace

GlContext& glContext() {
    (void)kGlErrorsFail;
    static std::unique_ptr<GlContext> context = createOffscreenContext();
    context->makeCurrent();
    return *context;
}

std::vector<float> renderConverged(Renderer& renderer, const Scene& scene,
                                   const RenderSettings& settings) {
    renderer.setSettings(settings);
    renderer.update(scene, kChangeAll);
    do renderer.renderFrame();
    while (!renderer.converged());
    return renderer.readLinear();
}

std::vector<std::byte> runComputeTest(const std::string& shader,
                                      const std::vector<std::byte>& record, const void* inputs,
                                      size_t inputBytes, size_t count, size_t outputBytes,
                                      const GpuTables* tables) {
    glContext();
    ShaderLibrary shaders;
    ProgramKey key;
    key.compute = shader;
    GLuint program = shaders.program(key);
    gl::Buffer lights(GLsizeiptr(record.size()), record.data());
    gl::Buffer in(GLsizeiptr(inputBytes), inputs);
    gl::Buffer out(GLsizeiptr(outputBytes), nullptr, GL_DYNAMIC_STORAGE_BIT | GL_MAP_READ_BIT);
    lights.bindBase(GL_SHADER_STORAGE_BUFFER, 1);
    in.bindBase(GL_SHADER_STORAGE_BUFFER, 6);
    out.bindBase(GL_SHADER_STORAGE_BUFFER, 7);
    std::vector<gl::TextureArray> textures;
    if (tables)
        for (const GpuTable& t : *tables) {
            textures.push_back(uploadGpuTable(t));
            glBindTextureUnit(GLuint(t.unit), textures.back().id());
        }
    glUseProgram(program);
    glProgramUniform1i(program, 0, int(count));
    glDispatchCompute(GLuint((count + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<std::byte> result(outputBytes);
    glGetNamedBufferSubData(out.id(), 0, GLsizeiptr(outputBytes), result.data());
    return result;
}

std::vector<glm::dvec3> cubeNormals26() {
    std::vector<glm::dvec3> out;
    for (int x = -1; x <= 1; ++x)
        for (int y = -1; y <= 1; ++y)
            for (int z = -1; z <= 1; ++z)
                if (x || y || z) out.push_back(glm::normalize(glm::dvec3(x, y, z)));
    return out;
}

std::string dataDir() {
    return CANDELA_TEST_DATA;
}
std::string sourceDir() {
    return CANDELA_SOURCE_DIR;
}

double rectangleFormFactor(double x0, double x1, double z0, double z1, double h) {
    // The rectangle [0, a] x [0, b] with a corner above the point: with X = a/h and Y = b/h,
    // F = 1/(2 pi) [X/sqrt(1+X^2) atan(Y/sqrt(1+X^2)) + Y/sqrt(1+Y^2) atan(X/sqrt(1+Y^2))],
    // odd in a and in b, so signed corners add up to any rectangle.
    auto corner = [h](double a, double b) {
        double X = a / h, Y = b / h, sx = std::sqrt(1.0 + X * X), sy = std::sqrt(1.0 + Y * Y);
        return (X / sx * std::atan(Y / sx) + Y / sy * std::atan(X / sy)) /
               (2.0 * 3.14159265358979323846);
    };
    return corner(x1, z1) - corner(x0, z1) - corner(x1, z0) + corner(x0, z0);
}

}  // namespace candela::test
