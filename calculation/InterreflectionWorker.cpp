#include "calculation/InterreflectionWorker.h"

#include <algorithm>
#include <chrono>

#include "scene/Scene.h"
#include "util/Error.h"

namespace candela {

InterreflectionWorker::InterreflectionWorker(InterreflectionOptions options)
    : mOptions(std::move(options)) {
    // One core stays with the render thread (and llvmpipe), so the editor keeps its frame rate.
    if (mOptions.threads <= 0) mOptions.threads = std::max(1, workerThreads(0) - 1);
    mThread = std::thread([this] { run(); });
}

InterreflectionWorker::~InterreflectionWorker() {
    {
        std::lock_guard<std::mutex> lock(mMutex);
        mQuit = true;
        mCancel = true;
    }
    mWake.notify_all();
    mThread.join();
}

void InterreflectionWorker::update(const Scene& scene, bool geometryChanged) {
    auto copy = std::make_unique<Scene>(scene.clone());
    {
        std::lock_guard<std::mutex> lock(mMutex);
        mPending = std::move(copy);
        mPendingGeometry = mPendingGeometry || geometryChanged;
        mHasPending = mEnabled;
        if (mEnabled) mCancel = true;  // the work under way is for an older scene
    }
    mWake.notify_all();
}

void InterreflectionWorker::setEnabled(bool enabled) {
    {
        std::lock_guard<std::mutex> lock(mMutex);
        if (enabled == mEnabled) return;
        mEnabled = enabled;
        if (!enabled) {
            mCancel = true;
            mHasPending = false;
            mSnapshot = Snapshot{};
            mSnapshot.version = ++mVersion;
        } else if (mPending) {
            // Start again from the last scene handed over (its geometry may be new to the solver).
            mPendingGeometry = true;
            mHasPending = true;
        }
    }
    mWake.notify_all();
}

InterreflectionWorker::Snapshot InterreflectionWorker::latest() const {
    std::lock_guard<std::mutex> lock(mMutex);
    return mSnapshot;
}

InterreflectionWorker::Status InterreflectionWorker::status() const {
    std::lock_guard<std::mutex> lock(mMutex);
    Status s = mStatus;
    s.busy = mBusy || mHasPending;
    return s;
}

void InterreflectionWorker::wait() {
    std::unique_lock<std::mutex> lock(mMutex);
    mIdle.wait(lock, [this] { return !mBusy && !mHasPending; });
}

void InterreflectionWorker::setStage(const std::string& stage, double progress) {
    std::lock_guard<std::mutex> lock(mMutex);
    mStatus.stage = stage;
    mStatus.progress = progress;
}

void InterreflectionWorker::publish(bool converged) {
    Snapshot s;
    bool light = mSolver && mSolver->hasInterreflection();
    if (light) {
        s.mesh = mMesh;
        s.patches = mMesh->patches.size();
        const std::vector<glm::dvec3>& v = mSolver->indirectAtVertices();
        s.vertexIrradiance.reserve(v.size());
        for (const glm::dvec3& e : v) s.vertexIrradiance.push_back(glm::vec3(e));
    }
    s.converged = converged;
    std::lock_guard<std::mutex> lock(mMutex);
    s.version = ++mVersion;
    mSnapshot = std::move(s);
}

void InterreflectionWorker::run() {
    for (;;) {
        std::unique_ptr<Scene> scene;
        bool geometry = false;
        {
            std::unique_lock<std::mutex> lock(mMutex);
            mBusy = false;
            mIdle.notify_all();
            mWake.wait(lock, [this] { return mQuit || mHasPending; });
            if (mQuit) return;
            // Keep a copy for a later setEnabled(true); the worker takes another.
            scene = std::make_unique<Scene>(mPending->clone());
            geometry = mPendingGeometry || !mSolver;
            mPendingGeometry = false;
            mHasPending = false;
            mBusy = true;
            mCancel = false;
            mStatus.error.clear();
        }
        auto start = std::chrono::steady_clock::now();
        std::string stage;
        Progress progress;
        progress.cancel = &mCancel;
        progress.report = [&](double f) { setStage(stage, f); };
        try {
            if (geometry) {
                stage = "patches";
                setStage(stage, 0.0);
                mSolver = std::make_unique<Interreflection>(*scene, mOptions);
                mMesh = std::make_shared<RadiosityMesh>(mSolver->mesh());
                if (!mSolver->mesh().reflects()) {
                    publish(true);  // black surfaces: nothing to reflect, no pass
                    continue;
                }
                stage = "form factors";
                if (!mSolver->buildTransfer(progress)) {
                    mSolver.reset();  // redo from the start with the newer scene
                    continue;
                }
            }
            if (!mSolver->mesh().reflects()) continue;
            stage = "direct light";
            if (!mSolver->sync(*scene, kQuickSpp, progress)) continue;
            publish(false);
            if (mCancel) continue;
            stage = "refining";
            if (!mSolver->refine(kFineSpp, progress)) continue;
            publish(true);
        } catch (const std::exception& e) {
            std::lock_guard<std::mutex> lock(mMutex);
            mStatus.error = e.what();
            mSolver.reset();
        }
        std::lock_guard<std::mutex> lock(mMutex);
        mStatus.lastSeconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        mStatus.stage = "idle";
    }
}

}  // namespace candela
