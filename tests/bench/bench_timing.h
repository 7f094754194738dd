// bench_timing.h - wall-clock timing shared by the benchmark programs.
#ifndef DSN_BENCH_TIMING_H
#define DSN_BENCH_TIMING_H

#include <algorithm>
#include <chrono>

namespace bench {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// Best of `repeats` timings of `work` (the machine is shared: the minimum is the least disturbed run).
template <typename Work>
double best_time(int repeats, Work work) {
    double best = 1e30;
    for (int i = 0; i < repeats; i++) {
        auto start = Clock::now();
        work();
        best = std::min(best, seconds_since(start));
    }
    return best;
}

} // namespace bench

#endif // DSN_BENCH_TIMING_H
