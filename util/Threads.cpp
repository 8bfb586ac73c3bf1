#include "util/Threads.h"

#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace candela {

void runSlices(int slices, const std::function<void(int slice)>& slice) {
    std::mutex mutex;
    std::exception_ptr failed;
    auto guarded = [&](int s) {
        try {
            slice(s);
        } catch (...) {
            std::lock_guard<std::mutex> lock(mutex);
            if (!failed) failed = std::current_exception();
        }
    };
    std::vector<std::thread> pool;
    std::vector<int> leftOver;
    try {
        pool.reserve(size_t(slices > 1 ? slices - 1 : 0));
        leftOver.reserve(pool.capacity());
    } catch (...) {
        // No room even for the lists: everything on this thread, in order.
        for (int s = 0; s < slices; ++s) guarded(s);
        if (failed) std::rethrow_exception(failed);
        return;
    }
    for (int s = 1; s < slices; ++s) {
        try {
            pool.emplace_back(guarded, s);
        } catch (...) {  // std::system_error: no thread to be had
            leftOver.push_back(s);
        }
    }
    guarded(0);
    for (int s : leftOver) guarded(s);
    for (std::thread& t : pool) t.join();
    if (failed) std::rethrow_exception(failed);
}

void runInParallel(int threads, const std::function<void()>& work) {
    runSlices(threads, [&](int) { work(); });
}

}  // namespace candela
