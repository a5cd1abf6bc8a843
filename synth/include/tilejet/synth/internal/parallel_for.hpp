#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace tilejet::synth::detail {

// Runs fn(i) for i in [0, n) on `threads` threads (0: all cores), items handed out one at a
// time so that uneven items (a slow quilt, a large bucket) balance. The first exception thrown
// by any fn stops the handing out and is rethrown here once every thread has finished: it never
// reaches std::terminate. `progress`, when given, hears how many items are done, from the
// calling thread, about every 100 ms and once at the end.
template <typename F>
void parallel_for(size_t n, int threads, F&& fn,
                  const std::function<void(size_t done)>& progress = {}) {
    if (threads <= 0) threads = int(std::max(1u, std::thread::hardware_concurrency()));
    const size_t workers = std::min(n, size_t(threads));
    if (workers <= 1) {
        for (size_t i = 0; i < n; ++i)
            fn(i);
        if (progress) progress(n);
        return;
    }
    std::atomic<size_t> next{0}, done{0}, running{workers};
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
                        ++done;
                    } catch (...) {
                        const std::lock_guard lock(failure_mutex);
                        if (!failure) failure = std::current_exception();
                        next = n;
                    }
                }
                --running;
            });
        if (progress) {
            auto last = std::chrono::steady_clock::now();
            while (running.load() > 0) {
                std::this_thread::sleep_for(std::chrono::milliseconds(10));
                if (std::chrono::steady_clock::now() - last >= std::chrono::milliseconds(100)) {
                    progress(done.load());
                    last = std::chrono::steady_clock::now();
                }
            }
        }
    }
    if (failure) std::rethrow_exception(failure);
    if (progress) progress(n);
}

}  // namespace tilejet::synth::detail
