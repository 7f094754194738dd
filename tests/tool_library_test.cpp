// tool_library_test.cpp - the tools' shared library (offline/tools, libdsn_tools.a) where a script cannot
// reach it: the flag suggestion's thresholds, the asset reader's limit and reasons, and the bake progress
// bar's fraction against the baker's own early stop.
#include <doctest/doctest.h>

#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

#include "fixtures/bake_fixtures.h"
#include "offline/bake_internal.h"
#include "offline/tools/asset_file.h"
#include "offline/tools/bake_progress.h"
#include "offline/tools/command_line.h"

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

TEST_CASE("the asset reader reads up to the largest asset, and names images and other files") {
    const std::string folder = "/tmp/dsn-tool-library-test-" + std::to_string(::getpid());
    REQUIRE(std::system(("mkdir -p " + folder).c_str()) == 0);
    auto write = [&folder](const std::string &name, const std::vector<unsigned char> &bytes) {
        const std::string path = folder + "/" + name;
        std::FILE *file = std::fopen(path.c_str(), "wb");
        REQUIRE(file != nullptr);
        REQUIRE(std::fwrite(bytes.data(), 1, bytes.size(), file) == bytes.size());
        std::fclose(file);
        return path;
    };
    // The format's largest asset: its texton and every known section at their largest, far above what
    // dsn-bake writes (a 255 x 255 RGB 16-bit texton alone is 390 150 bytes).
    CHECK(dsn::largest_asset_bytes() > 4 * 390150u);
    const std::string largest = write("largest.dsnt", std::vector<unsigned char>(dsn::largest_asset_bytes()));
    CHECK(dsn::read_asset_file(largest).size() == dsn::largest_asset_bytes());
    const std::string larger =
        write("larger.dsnt", std::vector<unsigned char>(dsn::largest_asset_bytes() + 1));
    CHECK_THROWS_WITH_AS(dsn::read_asset_file(larger),
                         (larger + " is too large: larger than the limit of " +
                          std::to_string(dsn::largest_asset_bytes()) + " bytes for a dsn asset")
                             .c_str(),
                         std::runtime_error);
    CHECK_THROWS_WITH_AS(dsn::read_asset_file(folder + "/missing.dsnt"),
                         ("cannot read " + folder + "/missing.dsnt: No such file or directory").c_str(),
                         std::runtime_error);
    dsn_asset asset;
    const std::string png = write("wood.png", {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13});
    CHECK_THROWS_WITH_AS(dsn::load_asset_file(png, asset),
                         (png + " is an image, not a dsn asset: bake it first: dsn-bake " + png + " -o " +
                          folder + "/wood.dsnt")
                             .c_str(),
                         std::runtime_error);
    const std::string text =
        write("notes.dsnt", {'h', 'e', 'l', 'l', 'o', '\n', 'w', 'o', 'r', 'l', 'd', '\n'});
    CHECK_THROWS_WITH_AS(dsn::load_asset_file(text, asset),
                         (text + " is not a dsn asset: " + dsn_error_message(DSN_ERR_BAD_MAGIC)).c_str(),
                         std::runtime_error);
    REQUIRE(std::system(("rm -rf " + folder).c_str()) == 0);
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
