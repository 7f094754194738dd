// parallel.cpp - parallel_ranges: one std::thread per extra range, joined before returning; when no
// thread can be started, the calling thread runs the ranges left.
#include "parallel.h"

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <system_error>
#include <vector>

#if !defined(__wasi__)
#include <thread>
#endif

namespace dsn {

unsigned bake_thread_count() {
#if defined(__wasi__)
    return 1;
#else
    unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    if (const char *chosen = std::getenv("DSN_BAKE_THREADS")) {
        char *end = nullptr;
        const unsigned long value = std::strtoul(chosen, &end, 10);
        if (end != chosen && *end == '\0' && value >= 1)
            threads = unsigned(std::min<unsigned long>(value, kMaxBakeThreads));
    }
    return std::min(kMaxBakeThreads, threads);
#endif
}

void parallel_ranges(size_t count, size_t minimum_per_thread,
                     const std::function<void(size_t, size_t)> &body) {
    if (count == 0) return;
    const size_t by_size = std::max<size_t>(1, count / std::max<size_t>(1, minimum_per_thread));
    const size_t ranges = std::min<size_t>(bake_thread_count(), by_size);
#if defined(__wasi__)
    (void)ranges;
    body(0, count);
#else
    auto range_begin = [&](size_t range) { return count * range / ranges; };
    if (ranges == 1) {
        body(0, count);
        return;
    }
    std::vector<std::exception_ptr> failures(ranges);
    auto run = [&](size_t range) {
        try {
            body(range_begin(range), range_begin(range + 1));
        } catch (...) {
            failures[range] = std::current_exception();
        }
    };
    std::vector<std::thread> helpers;
    helpers.reserve(ranges - 1);
    try {
        for (size_t range = 1; range < ranges; range++) helpers.emplace_back(run, range);
    } catch (const std::system_error &) {
        // No thread to be had: the ranges not started run here.
    }
    run(0);
    for (size_t range = 1 + helpers.size(); range < ranges; range++) run(range);
    for (std::thread &helper : helpers) helper.join();
    for (const std::exception_ptr &failure : failures)
        if (failure) std::rethrow_exception(failure);
#endif
}

} // namespace dsn
