// bake_progress.h - how far a bake's texton optimization is, for dsn-bake's progress bar (part of
// libdsn_tools.a). The iterations end at their limit or at the early stop (the relative model error
// improving by less than a tolerance over a window of iterations), whichever comes first, so the bar
// shows the larger of the two fractions and reaches 1 when the run ends either way.
#ifndef DSN_TOOLS_BAKE_PROGRESS_H
#define DSN_TOOLS_BAKE_PROGRESS_H

#include <vector>

namespace dsn {

// The early stop as the baker applies it (offline/sot.cpp): after more than `window` iterations and at
// least `minimum_iterations`, stop when rme[n - 1 - window] - rme[n - 1] < tolerance; tolerance 0 never
// stops early.
struct EarlyStopRule {
    double tolerance = 0;
    int window = 50;
    int minimum_iterations = 0;
};

// The fraction of the run done after rme.size() iterations of at most `total`: the larger of the
// iterations' fraction and how near the early stop is, the improvement over the window on a log scale
// from the first one measured (0) to the tolerance (1), held below 1 until the stop may act (the window
// and the minimum iterations done). In [0, 1]; exactly 1 after the iteration that stops the run.
double bake_progress_fraction(const std::vector<double> &rme, int total, const EarlyStopRule &rule);

} // namespace dsn

#endif // DSN_TOOLS_BAKE_PROGRESS_H
