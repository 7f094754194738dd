// bench_timing.h - timing shared by the benchmark programs: the best wall-clock time of several runs, and
// a cost ratio measured in pairs (work and baseline timed back to back, round after round).
#ifndef DSN_BENCH_TIMING_H
#define DSN_BENCH_TIMING_H

#include <algorithm>
#include <chrono>
#include <vector>

#include <time.h>

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

// CPU time of this thread: on a machine shared with other jobs it counts only the time the work ran.
inline double thread_seconds() {
    timespec now;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    return double(now.tv_sec) + 1e-9 * double(now.tv_nsec);
}

template <typename Work>
double thread_time(Work work) {
    const double start = thread_seconds();
    work();
    return thread_seconds() - start;
}

// The cost of `work` over that of `baseline`, both timed in each of `rounds` rounds, back to back and in
// alternating order. The machine's slow phases last longer than a round, so the ratio of one round
// compares the two under the same load: `median` is the median of those ratios; `best` is the best time
// of the work over the best of the baseline.
struct PairedRatio {
    double median, best, baseline_best;
};

template <typename Baseline, typename Work>
PairedRatio paired_ratio(int rounds, Baseline baseline, Work work) {
    std::vector<double> ratios;
    double best_work = 1e30, best_baseline = 1e30;
    for (int round = 0; round < rounds; round++) {
        double work_time, baseline_time;
        if (round % 2 == 0) {
            baseline_time = thread_time(baseline);
            work_time = thread_time(work);
        } else {
            work_time = thread_time(work);
            baseline_time = thread_time(baseline);
        }
        ratios.push_back(work_time / baseline_time);
        best_work = std::min(best_work, work_time);
        best_baseline = std::min(best_baseline, baseline_time);
    }
    std::sort(ratios.begin(), ratios.end());
    return PairedRatio{ratios[ratios.size() / 2], best_work / best_baseline, best_baseline};
}

} // namespace bench

#endif // DSN_BENCH_TIMING_H
