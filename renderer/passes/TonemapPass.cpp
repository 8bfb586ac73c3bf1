#include "renderer/passes/TonemapPass.h"

#include <algorithm>
#include <cmath>

#include "renderer/ProgramVariants.h"
#include "renderer/RenderSettings.h"

namespace candela {

namespace {

/// 1, 2 or 5 times a power of ten, the smallest of those >= x (x > 0).
double niceStep(double x) {
    double decade = std::pow(10.0, std::floor(std::log10(x)));
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (m * decade >= x * (1.0 - 1e-9)) return m * decade;
    return 10.0 * decade;
}

}  // namespace

FalseColourLegend sanitizedLegend(FalseColourLegend l) {
    if (!std::isfinite(l.min)) l.min = 0.f;
    if (!std::isfinite(l.max)) l.max = l.min + 1.f;
    if (l.logScale) {
        l.min = std::max(l.min, 1e-6f);
        l.max = std::clamp(l.max, l.min * 1.001f, l.min * 1e9f);
    } else if (!(l.max > l.min)) {
        l.max = l.min + std::max(1e-6f, std::abs(l.min) * 1e-3f);
    }
    return l;
}

void fitLegend(FalseColourLegend& legend, float peak) {
    if (!(peak > 0.f) || !std::isfinite(peak)) peak = 1.f;
    double decade = std::pow(10.0, std::floor(std::log10(double(peak))));
    if (legend.logScale) {
        legend.max = float(decade * 10.0);
        legend.min = float(decade * 1e-2);
        return;
    }
    legend.min = 0.f;
    for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
        if (m * decade >= peak * (1.0 - 1e-6)) {
            legend.max = float(m * decade);
            return;
        }
}

std::vector<float> legendTicks(const FalseColourLegend& legend, int target) {
    FalseColourLegend l = sanitizedLegend(legend);
    std::vector<float> ticks;
    double lo = l.min, hi = l.max, eps = 1e-6 * (hi - lo);
    if (l.logScale) {
        int first = int(std::ceil(std::log10(lo) - 1e-9)),
            last = int(std::floor(std::log10(hi) + 1e-9));
        bool fine = std::log10(hi / lo) < 3.5;
        for (int e = first - 1; e <= last; ++e)
            for (double m : {1.0, 2.0, 5.0}) {
                if (m != 1.0 && !fine) continue;
                double v = m * std::pow(10.0, e);
                if (v >= lo * (1 - 1e-6) && v <= hi * (1 + 1e-6)) ticks.push_back(float(v));
            }
        return ticks;
    }
    double step = niceStep((hi - lo) / std::max(1, target));
    double first = std::ceil(lo / step - 1e-9);
    for (int i = 0; (first + i) * step <= hi + eps; ++i) {
        double v = (first + i) * step;
        ticks.push_back(float(std::abs(v) < eps ? 0.0 : v));
    }
    return ticks;
}

std::vector<float> contourLevels(const FalseColourLegend& legend) {
    std::vector<float> levels;
    if (!legend.contours) return levels;
    FalseColourLegend l = sanitizedLegend(legend);
    if (legend.levels.empty()) {
        for (float t : legendTicks(l))
            if (t > l.min && t < l.max) levels.push_back(t);
    } else {
        for (float v : legend.levels)
            if (std::isfinite(v) && (!l.logScale || v > 0.f)) levels.push_back(v);
        std::sort(levels.begin(), levels.end());
        levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
    }
    if (levels.size() > size_t(kMaxContourLevels)) levels.resize(size_t(kMaxContourLevels));
    return levels;
}

void TonemapPass::resize(int width, int height) {
    mWidth = width;
    mHeight = height;
    mDisplay = gl::Texture2D(width, height, GL_RGBA8);
    glTextureParameteri(mDisplay.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(mDisplay.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    mFbo = gl::Framebuffer({&mDisplay}, nullptr);
}

void TonemapPass::execute(ShaderLibrary& shaders, const gl::Texture2D& linear,
                          const gl::Texture2D& luminance, const gl::Texture2D& position,
                          const gl::Texture2D& emission, const RenderSettings& settings) {
    GLuint program = shaders.program(programs::tonemap());
    glUseProgram(program);
    glProgramUniform1i(program, 0, int(settings.toneMap));
    glProgramUniform1f(program, 1, settings.exposure);
    glProgramUniform1f(program, 2, settings.fixedAverage);
    if (settings.toneMap == ToneMapOperator::FalseColour) {
        FalseColourLegend legend = sanitizedLegend(settings.legend);
        std::vector<float> levels = contourLevels(legend);
        glProgramUniform1f(program, 3, legend.min);
        glProgramUniform1f(program, 4, legend.max);
        glProgramUniform1i(program, 5, legend.logScale ? 1 : 0);
        glProgramUniform1i(program, 6, GLint(levels.size()));
        if (!levels.empty()) glProgramUniform1fv(program, 7, GLsizei(levels.size()), levels.data());
    }
    glBindTextureUnit(0, linear.id());
    glBindTextureUnit(1, luminance.id());
    glBindTextureUnit(2, position.id());
    glBindTextureUnit(3, emission.id());
    glBindFramebuffer(GL_FRAMEBUFFER, mFbo.id());
    glViewport(0, 0, mWidth, mHeight);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

}  // namespace candela
