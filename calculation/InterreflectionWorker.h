#pragma once
// Interreflected light kept up to date in the background, for the editor and headless renders
// (issue 17, part 3): a worker thread owns an Interreflection (calculation/Interreflection.h) and a
// copy of the scene, and works on the newest scene it was handed:
//
// - the geometry changed (or first use): patches and form factors, then every source;
// - a luminaire moved, turned or was swapped, or the environment changed: that source alone
//   (its direct light, then the solution for the change); the others keep their share;
// - nothing changed: nothing runs.
//
// Each source's light is first computed quickly (kQuickSpp samples) and published, then refined
// (kFineSpp) and published again as converged. A newer scene cancels the work under way at the
// next patch. Solutions are published as snapshots the render thread polls (latest()).

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "calculation/Interreflection.h"

namespace candela {

struct Scene;

class InterreflectionWorker {
  public:
    /// Direct-light samples per patch point of the quick and the refined pass.
    static constexpr int kQuickSpp = 4, kFineSpp = 32;

    explicit InterreflectionWorker(InterreflectionOptions options = {});
    ~InterreflectionWorker();  ///< Cancels the work under way and joins the thread.
    InterreflectionWorker(const InterreflectionWorker&) = delete;
    InterreflectionWorker& operator=(const InterreflectionWorker&) = delete;

    /// Hands over the scene as it is now (copied). `geometryChanged`: its surfaces or materials
    /// changed since the last call (the patches and form factors are rebuilt).
    void update(const Scene& scene, bool geometryChanged);
    /// Off: the work stops and the snapshot becomes empty (no interreflected light).
    void setEnabled(bool enabled);
    bool enabled() const { return mEnabled; }

    struct Snapshot {
        uint64_t version = 0;                       ///< Grows with every published solution.
        std::shared_ptr<const RadiosityMesh> mesh;  ///< null: no interreflected light (yet).
        std::vector<glm::vec3> vertexIrradiance;    ///< Interreflected irradiance per mesh vertex.
        bool converged = false;                     ///< Refined, and nothing left to do.
        size_t patches = 0;
    };
    /// The latest published solution (copied).
    Snapshot latest() const;
    uint64_t version() const { return mVersion.load(); }

    struct Status {
        bool busy = false;
        std::string stage;  ///< "form factors", "direct light (quick)", "refining", "solving"...
        double progress = 0.0;   ///< Of the stage, 0..1.
        double lastSeconds = 0;  ///< Wall time of the last finished job.
        std::string error;       ///< The last job's failure (a bad technique), else empty.
    };
    Status status() const;
    /// Blocks until nothing is left to do (headless renders, tests).
    void wait();

  private:
    void run();
    void publish(bool converged);
    void setStage(const std::string& stage, double progress);

    InterreflectionOptions mOptions;
    mutable std::mutex mMutex;
    std::condition_variable mWake, mIdle;
    std::thread mThread;
    bool mQuit = false, mEnabled = true;
    // The job handed over, and whether a newer one waits.
    std::unique_ptr<Scene> mPending;
    bool mPendingGeometry = false, mHasPending = false, mBusy = false;
    std::atomic<bool> mCancel{false};
    std::atomic<uint64_t> mVersion{0};
    Snapshot mSnapshot;
    Status mStatus;
    // The worker thread's own state.
    std::unique_ptr<Scene> mScene, mGeometry;
    std::unique_ptr<Interreflection> mSolver;
    std::shared_ptr<const RadiosityMesh> mMesh;
};

}  // namespace candela
