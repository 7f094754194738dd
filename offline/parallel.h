// parallel.h - runs the independent parts of one loop of the baker on the machine's cores (the FFT
// passes of the transforms and of the texton's iterations). Internal to libdsn_bake.a.
//
// The callers make every part compute the same numbers whatever thread runs it, and combine per-part
// results in a fixed order, so a bake gives the same bits on one thread or many. The wasm32-wasi baker
// (no threads in wasi) runs the parts one after the other.
#ifndef DSN_OFFLINE_PARALLEL_H
#define DSN_OFFLINE_PARALLEL_H

#include <cstddef>
#include <functional>

namespace dsn {

// Threads a parallel loop uses, the caller's included: the environment variable DSN_BAKE_THREADS when it
// holds a positive number (1 on a machine shared with other work), else the hardware's; at most
// kMaxBakeThreads.
constexpr unsigned kMaxBakeThreads = 8;
unsigned bake_thread_count();

// Transform points a parallel part should hold at least (a 1-D transform of n points is a few n
// nanoseconds): below about 30 microseconds of work, starting a thread costs more than it saves.
constexpr size_t kPointsPerThread = size_t(1) << 15;
inline size_t items_per_thread(size_t points_per_item) {
    return points_per_item >= kPointsPerThread ? 1
                                               : kPointsPerThread / (points_per_item ? points_per_item : 1);
}

// Calls body(begin, end) on contiguous ranges that cover [0, count) exactly once, at most one range per
// thread, the first on the calling thread; returns when all are done. An exception thrown by a body is
// rethrown here (the first one) after every thread has finished. Loops shorter than `minimum_per_thread`
// items per thread use fewer threads: a thread costs tens of microseconds to start.
void parallel_ranges(size_t count, size_t minimum_per_thread,
                     const std::function<void(size_t, size_t)> &body);

} // namespace dsn

#endif // DSN_OFFLINE_PARALLEL_H
