#pragma once
// A layout proposed in the editor (calculation/Layout.h): computed on a worker thread over a copy
// of the scene while the editor stays responsive, with each arrangement's progress, and accepted
// as one undo step against the scene as it is then.

#include <atomic>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "calculation/Layout.h"
#include "scene/Scene.h"

namespace candela::ui {

struct EditorState;

class LayoutJob {
  public:
    /// Starts proposeLayout(scene, request) on a worker thread (the scene is copied).
    LayoutJob(const Scene& scene, LayoutRequest request);
    /// Cancels a running proposal (at its next arrangement) and waits for the worker.
    ~LayoutJob();
    LayoutJob(const LayoutJob&) = delete;
    LayoutJob& operator=(const LayoutJob&) = delete;

    bool done() const { return mDone.load(); }
    /// The last progress line ("5 x 3, 15 luminaires: 582.5 lx, U0 0.647").
    std::string status() const;
    /// Once done: the proposal, or empty with error() saying why.
    const std::optional<LayoutResult>& result() const { return mResult; }
    const std::string& error() const { return mError; }
    const LayoutRequest& request() const { return mRequest; }

  private:
    LayoutRequest mRequest;
    Scene mScene;
    std::atomic<bool> mDone{false}, mCancel{false};
    mutable std::mutex mMutex;
    std::string mStatus;
    std::optional<LayoutResult> mResult;
    std::string mError;
    std::thread mWorker;
};

/// The layout's chosen arrangement applied to the editor's scene as it is now (the luminaires
/// over the layout's rectangle replaced by the grid, calculation/Layout.h applyLayout), as one
/// undo step. False, with the error reported, when there is no chosen arrangement or it cannot
/// be applied.
bool acceptLayout(EditorState& state, const LayoutRequest& request, const LayoutResult& result);

/// The scene-file luminaire entry of a file for a layout: "photometric" or "gldf" by its
/// extension, the file absolute, the GLDF variant when given.
nlohmann::json layoutLuminaireEntry(const std::string& file, const std::string& variant);

}  // namespace candela::ui
