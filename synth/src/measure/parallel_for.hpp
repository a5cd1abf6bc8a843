#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace tilejet::synth::detail {

// Runs fn(i) for i in [0, n) on `threads` threads (0: all cores), items handed out one at a
// time so that uneven items (a slow quilt, a large bucket) balance. The first exception thrown
// by any fn stops the handing out and is rethrown here once every thread has finished.
template <typename F>
void parallel_for(size_t n, int threads, F&& fn) {
    if (threads <= 0) threads = int(std::max(1u, std::thread::hardware_concurrency()));
    const size_t workers = std::min(n, size_t(threads));
    if (workers <= 1) {
        for (size_t i = 0; i < n; ++i)
            fn(i);
        return;
    }
    std::atomic<size_t> next{0};
    std::exception_ptr failure;
    std::mutex failure_mutex;
    {
        std::vector<std::jthread> pool;
        pool.reserve(workers);
        for (size_t w = 0; w < workers; ++w)
            pool.emplace_back([&] {
                for (size_t i = next++; i < n; i = next++) {
                    try {
                        fn(i);
                    } catch (...) {
                        const std::lock_guard lock(failure_mutex);
                        if (!failure) failure = std::current_exception();
                        next = n;
                    }
                }
            });
    }
    if (failure) std::rethrow_exception(failure);
}

}  // namespace tilejet::synth::detail
