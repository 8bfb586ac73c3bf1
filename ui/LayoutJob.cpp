#include "ui/LayoutJob.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "scene/SceneIo.h"
#include "ui/EditorState.h"
#include "util/Error.h"

namespace candela::ui {

namespace {

/// Thrown from the progress callback to stop a proposal that is no longer wanted.
struct Cancelled {};

}  // namespace

LayoutJob::LayoutJob(const Scene& scene, LayoutRequest request)
    : mRequest(std::move(request)), mScene(scene.clone()) {
    mWorker = std::thread([this] {
        try {
            LayoutResult result = proposeLayout(mScene, mRequest, [this](const std::string& s) {
                if (mCancel.load()) throw Cancelled{};
                std::lock_guard<std::mutex> lock(mMutex);
                mStatus = s;
            });
            mResult = std::move(result);
        } catch (const Cancelled&) {
            mError = "cancelled";
        } catch (const std::exception& e) {
            mError = e.what();
        }
        mDone.store(true);
    });
}

LayoutJob::~LayoutJob() {
    mCancel.store(true);
    if (mWorker.joinable()) mWorker.join();
}

std::string LayoutJob::status() const {
    std::lock_guard<std::mutex> lock(mMutex);
    return mStatus;
}

bool acceptLayout(EditorState& state, const LayoutRequest& request, const LayoutResult& result) {
    const LayoutCandidate* best = result.best();
    if (!best) {
        reportError(state, "No arrangement met the target: nothing to accept");
        return false;
    }
    try {
        // Through the scene file: the same document `candela layout --out` writes.
        Scene laidOut = parseScene(applyLayout(state.scene, request, result), state.scene.path);
        std::string label = "Layout of " + std::to_string(best->count()) + " " + request.name;
        applyEdit(state, label, kChangeLuminaires, [&](Scene& s) {
            s.luminaires = std::move(laidOut.luminaires);
            s.layouts = std::move(laidOut.layouts);
        });
        state.selectedLuminaire = -1;
        state.alsoSelected.clear();
        state.measure.surfaces.reset();  // computed for the luminaires replaced
        char text[200];
        std::snprintf(text, sizeof text,
                      "%s: %d luminaires (%d x %d), Em %.1f lx, U0 %.3f on %s (one undo step)",
                      label.c_str(), best->count(), best->columns, best->rows, best->em, best->u0,
                      result.area.c_str());
        setStatus(state, text);
        return true;
    } catch (const std::exception& e) {
        reportError(state, std::string("Cannot apply the layout: ") + e.what());
        return false;
    }
}

nlohmann::json layoutLuminaireEntry(const std::string& file, const std::string& variant) {
    std::string ext = std::filesystem::path(file).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    nlohmann::json entry = {{"type", ext == ".gldf" ? "gldf" : "photometric"},
                            {"file", std::filesystem::absolute(file).lexically_normal().string()}};
    if (!variant.empty()) entry["variant"] = variant;
    return entry;
}

}  // namespace candela::ui
