#pragma once
// Running work on several threads without ending the program when something fails: a worker's
// exception (std::bad_alloc above all) comes back to the calling thread instead of calling
// std::terminate, and a thread the system cannot start (memory or a process limit) is done
// without instead of leaving the started ones joinable while the exception unwinds (which also
// terminates).

#include <functional>

namespace candela {

/// Runs slice(0 .. slices-1), slice 0 on the calling thread and the others each on a thread of
/// its own, waits for all, and rethrows on the calling thread the first exception one threw. A
/// slice whose thread cannot be started runs on the calling thread after slice 0.
void runSlices(int slices, const std::function<void(int slice)>& slice);

/// Runs `work` on the calling thread and on threads - 1 more at once (runSlices): each call must
/// take its items from a shared counter until none are left, so that a thread that could not
/// be started only leaves its share to the others.
void runInParallel(int threads, const std::function<void()>& work);

}  // namespace candela
