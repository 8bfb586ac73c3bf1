#include "report/Screenshot.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <system_error>

#include "renderer/ImageFile.h"
#include "scene/SceneIo.h"
#include "util/Error.h"
#include "util/FileOutput.h"

namespace candela {

namespace fs = std::filesystem;

void PassTotals::add(const FrameStats& stats) {
    if (stats.passes.empty()) return;
    for (const PassTiming& p : stats.passes)
        if (p.name == "gbuffer") {
            mTotals.clear();
            break;
        }
    for (const PassTiming& p : stats.passes) {
        auto it = std::find_if(mTotals.begin(), mTotals.end(),
                               [&](const PassTiming& t) { return t.name == p.name; });
        if (it == mTotals.end())
            mTotals.push_back(p);
        else
            it->gpuMs += p.gpuMs;
    }
    mLastFrame = stats.passes;
}

double PassTotals::totalGpuMs() const {
    double sum = 0.0;
    for (const PassTiming& p : mTotals) sum += p.gpuMs;
    return sum;
}

fs::path nextFreeStem(const fs::path& dir, const std::string& prefix) {
    for (int n = 0; n < 100000; ++n) {
        char number[16];
        std::snprintf(number, sizeof number, "-%03d", n);
        fs::path stem = dir / (prefix + number);
        bool taken = false;
        for (const char* ext : {".png", ".exr", ".json"}) {
            fs::path p = stem;
            p += ext;
            taken = taken || fs::exists(p);
        }
        if (!taken) return stem;
    }
    throw InputError(dir.string() + ": no free " + prefix + "-NNN name left");
}

nlohmann::json cameraToJsonObject(const Camera& camera) {
    auto vec = [](const glm::dvec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); };
    return {{"position", vec(camera.position)},
            {"target", vec(camera.target)},
            {"fov_deg", camera.fovDeg}};
}

std::string utcTimestamp() {
    std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
    std::tm tm{};
    gmtime_r(&now, &tm);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return text;
}

namespace {

nlohmann::json passesJson(const std::vector<PassTiming>& passes) {
    nlohmann::json out = nlohmann::json::array();
    for (const PassTiming& p : passes) out.push_back({{"name", p.name}, {"gpu_ms", p.gpuMs}});
    return out;
}

}  // namespace

ScreenshotFiles writeScreenshot(const fs::path& dir, const Scene& scene, const Renderer& renderer,
                                const PassTotals& passes) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw InputError(dir.string() + ": cannot create folder (" + ec.message() + ")");
    fs::path stem = nextFreeStem(dir, "shot");
    ScreenshotFiles files;
    files.png = stem.string() + ".png";
    files.exr = stem.string() + ".exr";
    files.json = stem.string() + ".json";

    const RenderSettings& settings = renderer.settings();
    const gl::Texture2D& display = renderer.displayTexture();
    int width = display.width(), height = display.height();
    writeImage8(files.png, width, height, renderer.readDisplay());
    writeImageFloat(files.exr, width, height, renderer.readLinear());

    nlohmann::json lums = nlohmann::json::array();
    for (const auto& lum : scene.luminaires) {
        nlohmann::json j = luminaireToJson(*lum);
        j["technique"] = lum->technique;
        lums.push_back(std::move(j));
    }
    const FrameStats& stats = renderer.stats();
    nlohmann::json sidecar = {
        {"scene", scene.path},
        {"timestamp", utcTimestamp()},
        {"png", files.png},
        {"exr", files.exr},
        {"render_size", {width, height}},
        {"samples_per_pixel", stats.samplesPerPixel},
        {"accumulated_frames", stats.accumulatedFrames},
        {"converged", stats.converged},
        {"tonemap",
         {{"operator", settings.toneMap == ToneMapOperator::Reinhard ? "reinhard" : "exponential"},
          {"exposure", settings.exposure}}},
        {"camera", cameraToJsonObject(scene.camera)},
        {"luminaires", std::move(lums)},
        {"passes", passesJson(passes.totals())},
        {"last_frame_passes", passesJson(passes.lastFrame())},
        {"total_gpu_ms", passes.totalGpuMs()},
    };
    writeFileAtomically(files.json, sidecar.dump(2) + "\n");
    return files;
}

}  // namespace candela
