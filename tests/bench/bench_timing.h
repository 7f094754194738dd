// bench_timing.h - timing shared by the benchmark programs: the best wall-clock or thread CPU time of
// several runs, and jobs timed in rounds (each job once per round) to compare them under the same load.
#ifndef DSN_BENCH_TIMING_H
#define DSN_BENCH_TIMING_H

#include <algorithm>
#include <chrono>
#include <functional>
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

template <typename Work>
double best_thread_time(int repeats, Work work) {
    double best = 1e30;
    for (int i = 0; i < repeats; i++) best = std::min(best, thread_time(work));
    return best;
}

// Thread CPU times of each job, every job run once per round for `rounds` rounds, the order rotating each
// round: the machine's slow phases last longer than a round, so they fall on all the jobs alike, and no
// job always runs right after the same one. times[job][round].
inline std::vector<std::vector<double>> timed_rounds(int rounds,
                                                     const std::vector<std::function<void()>> &jobs) {
    std::vector<std::vector<double>> times(jobs.size());
    for (int round = 0; round < rounds; round++)
        for (size_t k = 0; k < jobs.size(); k++) {
            const size_t job = (k + size_t(round)) % jobs.size();
            times[job].push_back(thread_time(jobs[job]));
        }
    return times;
}

inline double fastest(const std::vector<double> &times) {
    return *std::min_element(times.begin(), times.end());
}

// The median over the rounds of work[round] / baseline[round]: the two compared under the same load.
inline double median_ratio(const std::vector<double> &work, const std::vector<double> &baseline) {
    std::vector<double> ratios;
    for (size_t round = 0; round < work.size(); round++) ratios.push_back(work[round] / baseline[round]);
    std::sort(ratios.begin(), ratios.end());
    return ratios[ratios.size() / 2];
}

// The cost of `work` over that of `baseline`, timed in rounds (timed_rounds): `median` is median_ratio,
// `best` the best time of the work over the best of the baseline.
struct PairedRatio {
    double median, best, baseline_best;
};

template <typename Baseline, typename Work>
PairedRatio paired_ratio(int rounds, Baseline baseline, Work work) {
    const auto times = timed_rounds(rounds, {baseline, work});
    return PairedRatio{median_ratio(times[1], times[0]), fastest(times[1]) / fastest(times[0]),
                       fastest(times[0])};
}

} // namespace bench

#endif // DSN_BENCH_TIMING_H
