// Helpers shared by the environment-map tests (environment_test.cpp, environment_sky_test.cpp):
// maps from a texel function, written images, temporary folders and error text.
#pragma once

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "luminaires/environment/Environment.h"
#include "shaders/shared/Constants.h"
#include "util/Error.h"

namespace candela::envtest {

using gpu::kPi;  // the one definition, shaders/shared/Constants.h

using TexelFn = std::function<glm::vec3(int x, int y)>;

inline std::shared_ptr<EnvironmentMap> makeMap(int w, int h, const TexelFn& fn,
                                               double rotationDeg = 0.0) {
    std::vector<glm::vec3> rgb(size_t(w) * size_t(h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) rgb[size_t(y) * size_t(w) + size_t(x)] = fn(x, y);
    return std::make_shared<EnvironmentMap>(w, h, std::move(rgb), 1.0, rotationDeg, "test map");
}

inline std::string inputError(const std::function<void()>& fn) {
    try {
        fn();
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

#define EXPECT_CONTAINS(text, part) \
    EXPECT_NE(std::string(text).find(part), std::string::npos) << text

inline std::string tempDir(const std::string& name) {
    std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                ("candela_env_" + name + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir.string();
}

inline void writeImage(const std::string& path, int w, int h, const std::vector<float>& rgb) {
    auto out = OIIO::ImageOutput::create(path);
    ASSERT_TRUE(out) << path;
    OIIO::ImageSpec spec(w, h, 3, OIIO::TypeDesc::FLOAT);
    ASSERT_TRUE(out->open(path, spec));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, rgb.data()));
    ASSERT_TRUE(out->close());
}

inline double lum(const glm::dvec3& c) {
    return luminanceOf(c);
}
}  // namespace candela::envtest
