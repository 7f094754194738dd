// tool_library_test.cpp - the tools' shared library (offline/tools, libdsn_tools.a) where a script cannot
// reach it: the flag suggestion's thresholds, and the bake progress bar's fraction against the baker's own
// early stop.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "../offline/bake_internal.h"
#include "../offline/tools/bake_progress.h"
#include "../offline/tools/command_line.h"
#include "fixtures/bake_fixtures.h"

TEST_CASE("nearest_flag guesses a close misspelling, and nothing for short or far ones") {
    const std::vector<std::string> known = {"-o", "--output", "--radius", "--seed", "--size", "--iterations"};
    CHECK(dsn::nearest_flag("--raduis", known) == "--radius"); // a swap of neighbours is one edit
    CHECK(dsn::nearest_flag("--RADIUS", known) == "--radius"); // letter case
    CHECK(dsn::nearest_flag("-radius", known) == "--radius");  // dashes
    CHECK(dsn::nearest_flag("--iteratoins", known) == "--iterations");
    CHECK(dsn::nearest_flag("--itrations", known) == "--iterations");
    CHECK(dsn::nearest_flag("--szie", known) == "--size");
    CHECK(dsn::nearest_flag("--sed", known) == "--seed"); // --seed and --size: the nearer one
    CHECK(dsn::nearest_flag("--out", known) == "");       // 3 edits: too far
    CHECK(dsn::nearest_flag("-p", known) == "");          // one letter: never guessed
    CHECK(dsn::nearest_flag("--sz", known) == "");        // 2 edits in 4 letters: more than a third
    CHECK(dsn::nearest_flag("--radius", {}) == "");
}

TEST_CASE("the bake progress reaches 1 exactly when the early stop ends the run, and not before") {
    const dsn::Image exemplar = bake_fixtures::random_phase_exemplar(48, 40, 1, 7);
    const dsn::GaussianModel model = dsn::gaussian_model(exemplar, true);
    const dsn::Support support = dsn::support_mask(6, DSN_SHAPE_DISK);
    for (int minimum : {0, 150}) {
        CAPTURE(minimum);
        dsn::SotOptions options;
        options.iterations = 100000;
        options.stop_tolerance = 1e-3;
        options.stop_window = 20;
        options.minimum_iterations = minimum;
        dsn::EarlyStopRule rule;
        rule.tolerance = options.stop_tolerance;
        rule.window = options.stop_window;
        rule.minimum_iterations = minimum;
        std::vector<double> rme, fractions;
        options.progress = [&](int, int total, double value) {
            rme.push_back(value);
            fractions.push_back(dsn::bake_progress_fraction(rme, total, rule));
        };
        const dsn::SotResult result = dsn::sot_alternating_projections(model.spectrum, support, options);
        REQUIRE(result.stop == dsn::SotStop::Converged);
        REQUIRE(fractions.size() == result.rme_per_iteration.size());
        CHECK(fractions.size() >= size_t(minimum));
        CHECK(fractions.back() == 1.0);
        for (size_t i = 0; i + 1 < fractions.size(); i++) {
            CAPTURE(i);
            REQUIRE(fractions[i] < 1.0);
            REQUIRE(fractions[i] >= 0.0);
        }
        // The iterations' own fraction would have shown almost nothing.
        CHECK(double(fractions.size()) / options.iterations < 0.01);
    }
    // Without the early stop the bar is the iterations' fraction, 1 at the last one.
    dsn::EarlyStopRule never;
    CHECK(dsn::bake_progress_fraction(std::vector<double>(40, 0.5), 80, never) == 0.5);
    CHECK(dsn::bake_progress_fraction(std::vector<double>(80, 0.5), 80, never) == 1.0);
}
