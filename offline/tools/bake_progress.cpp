// bake_progress.cpp - the fraction of a bake done, iterations or early stop (bake_progress.h).
#include "bake_progress.h"

#include <algorithm>
#include <cmath>

namespace dsn {

double bake_progress_fraction(const std::vector<double> &rme, int total, const EarlyStopRule &rule) {
    const size_t done = rme.size();
    const double iterations = total > 0 ? std::min(1.0, double(done) / total) : 1.0;
    const size_t window = size_t(std::max(1, rule.window));
    if (!(rule.tolerance > 0) || done <= window) return iterations;
    const double improvement = rme[done - 1 - window] - rme[done - 1];
    const double first = rme[0] - rme[window];
    double nearness = 1; // an improvement below the tolerance: the stop's condition holds
    if (!(improvement < rule.tolerance))
        nearness =
            first <= improvement ? 0 : std::log(first / improvement) / std::log(first / rule.tolerance);
    // The stop acts only once the window and the minimum iterations are done.
    const double allowed =
        double(done) / double(std::max<size_t>(size_t(std::max(0, rule.minimum_iterations)), window + 1));
    return std::max(iterations, std::min({1.0, nearness, allowed}));
}

} // namespace dsn
