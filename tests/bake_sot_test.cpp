// bake_sot_test.cpp - support masks, the SOT (pruned == reference, synthetic exemplars, reproducibility) and
// the luminance baseline; the real-texture case is skipped when the texture folder is absent.
#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "fixtures/bake_fixtures.h"
#include "offline/bake_internal.h"
#include "runtime/setup/format_bytes.h"

using namespace bake_fixtures;

namespace {

double max_abs(const std::vector<double> &values) {
    double largest = 0;
    for (double value : values) largest = std::max(largest, std::fabs(value));
    return largest;
}

double max_difference(const std::vector<double> &a, const std::vector<double> &b) {
    double largest = 0;
    for (size_t i = 0; i < a.size(); i++) largest = std::max(largest, std::fabs(a[i] - b[i]));
    return largest;
}

} // namespace

TEST_CASE("support_mask: square and disk of radius r, as format.h counts them") {
    for (int radius : {1, 2, 7, 15, 127}) {
        const dsn::Support square = dsn::support_mask(radius, DSN_SHAPE_RECTANGLE);
        const dsn::Support disk = dsn::support_mask(radius, DSN_SHAPE_DISK);
        CHECK(square.size() == (2 * radius + 1) * (2 * radius + 1));
        CHECK(uint32_t(disk.size()) ==
              dsn_support_size(DSN_SHAPE_DISK, uint32_t(2 * radius + 1), uint32_t(2 * radius + 1)));
        CHECK(disk.mask[size_t(radius)] == 1); // (0, -r) is inside
        CHECK(disk.mask[0] == 0);              // the corner is not
    }
    CHECK(dsn::support_mask(15, DSN_SHAPE_DISK).size() == 709);
    CHECK_THROWS_AS(dsn::support_mask(0, DSN_SHAPE_RECTANGLE), std::invalid_argument);
    CHECK_THROWS_AS(dsn::support_mask(128, DSN_SHAPE_RECTANGLE), std::invalid_argument);
    CHECK_THROWS_AS(dsn::support_mask(5, 2), std::invalid_argument);
}

TEST_CASE("the pruned SOT iteration equals the full-FFT reference to float precision") {
    struct Case {
        int width, height, channels, radius;
        uint32_t shape;
    };
    // Odd, even and prime sizes, grey and colour, square and disk, an odd number of packed rows.
    const Case cases[] = {{31, 57, 1, 7, DSN_SHAPE_RECTANGLE},
                          {37, 41, 3, 5, DSN_SHAPE_DISK},
                          {64, 48, 3, 11, DSN_SHAPE_RECTANGLE},
                          {40, 33, 1, 4, DSN_SHAPE_DISK}};
    for (const Case &test : cases) {
        CAPTURE(test.width);
        CAPTURE(test.height);
        const dsn::Image exemplar = random_phase_exemplar(test.width, test.height, test.channels, 11);
        const dsn::GaussianModel model = dsn::gaussian_model(exemplar, true);
        const dsn::Support support = dsn::support_mask(test.radius, test.shape);
        dsn::SotOptions options;
        options.iterations = 30;
        options.seed = 5;
        const dsn::SotResult pruned = dsn::sot_alternating_projections(model.spectrum, support, options);
        options.reference = true;
        const dsn::SotResult reference = dsn::sot_alternating_projections(model.spectrum, support, options);
        REQUIRE(pruned.rme_per_iteration.size() == 30);
        REQUIRE(reference.rme_per_iteration.size() == 30);
        CHECK(max_difference(pruned.texton.values, reference.texton.values) <
              1e-4 * max_abs(reference.texton.values));
        CHECK(max_difference(pruned.rme_per_iteration, reference.rme_per_iteration) < 1e-5);
        // The per-iteration RME is the RME without the zero frequency of the texton returned (measured
        // independently).
        CHECK(dsn::relative_model_error_without_zero_frequency(model.spectrum, pruned.texton) ==
              doctest::Approx(pruned.rme_per_iteration.back()).epsilon(1e-5));
        for (size_t i = 0; i < support.mask.size(); i++)
            if (!support.mask[i])
                for (int c = 0; c < test.channels; c++)
                    CHECK(pruned.texton.values[size_t(c) * support.mask.size() + i] == 0);
    }
}

TEST_CASE(
    "SOT on a synthetic exemplar with a known compact spot: RME without the zero frequency (the "
    "per-iteration figure) <= 0.2 at 1000 iterations; over every frequency, the texton's sum dominates") {
    const dsn::Image exemplar = random_phase_exemplar(64, 64, 3, 101);
    const dsn::GaussianModel model = dsn::gaussian_model(exemplar, false);
    const dsn::Support support = dsn::support_mask(15, DSN_SHAPE_RECTANGLE);
    const uint32_t seed = 3;

    // The start has the exact spectrum (RME 0) but not the support; cropped to it, it is far off.
    const dsn::Spectrum start = dsn::random_phase_start(model.spectrum, seed);
    CHECK(dsn::relative_model_error(model.spectrum, start) < 1e-5);
    const double cropped_start = dsn::relative_model_error_without_zero_frequency(
        model.spectrum, dsn::crop_to_support(dsn::inverse_dft(start), support));

    dsn::SotOptions options;
    options.iterations = 1000;
    options.seed = seed;
    const dsn::SotResult result = dsn::sot_alternating_projections(model.spectrum, support, options);
    MESSAGE("cropped start RME " << cropped_start << ", after 50 " << result.rme_per_iteration[49]
                                 << ", after 1000 " << result.rme_per_iteration.back());
    CHECK(result.rme_per_iteration[49] < cropped_start / 2);
    CHECK(result.rme_per_iteration.back() <= 0.2);
    // The iterations leave T(0) free and this exemplar's spot does not sum to zero: the texton finds the
    // spot, sum included, and that sum is almost all of the RME over every frequency (the paper's).
    const double every = dsn::relative_model_error(model.spectrum, result.texton);
    const double without = result.rme_per_iteration.back();
    MESSAGE("after 1000, over every frequency " << every);
    CHECK(every * every - without * without > 0.9 * every * every);
}

TEST_CASE("SOT is reproducible from its seed, and the early stop ends a stalled run") {
    const dsn::Image exemplar = random_phase_exemplar(48, 40, 1, 7);
    const dsn::GaussianModel model = dsn::gaussian_model(exemplar, true);
    const dsn::Support support = dsn::support_mask(6, DSN_SHAPE_DISK);
    dsn::SotOptions options;
    options.iterations = 40;
    options.seed = 9;
    const dsn::SotResult first = dsn::sot_alternating_projections(model.spectrum, support, options);
    const dsn::SotResult second = dsn::sot_alternating_projections(model.spectrum, support, options);
    CHECK(first.texton.values == second.texton.values);
    CHECK(first.rme_per_iteration == second.rme_per_iteration);
    options.seed = 10;
    CHECK(dsn::sot_alternating_projections(model.spectrum, support, options).texton.values !=
          first.texton.values);

    options.iterations = 100000;
    options.stop_tolerance = 1e-3;
    options.stop_window = 20;
    int calls = 0;
    options.progress = [&calls](int done, int total, double) {
        calls++;
        CHECK(done == calls);
        CHECK(total == 100000);
    };
    const dsn::SotResult stopped = dsn::sot_alternating_projections(model.spectrum, support, options);
    const auto &rme = stopped.rme_per_iteration;
    CHECK(rme.size() < 100000u);
    CHECK(size_t(calls) == rme.size());
    REQUIRE(rme.size() > 20);
    CHECK(rme[rme.size() - 21] - rme.back() < 1e-3);
    CHECK(rme[rme.size() - 22] - rme[rme.size() - 2] >= 1e-3); // it did not stop one iteration late
}

TEST_CASE("the luminance texton is the exemplar's spectrum with one common phase, cropped") {
    const dsn::Image exemplar = random_phase_exemplar(40, 40, 3, 21);
    const dsn::GaussianModel model = dsn::gaussian_model(exemplar, false);
    // With a support covering S - S of the whole torus it would be exact; with a small one it only loses
    // what lies outside. Measure both against the definition: phase-rotated spectrum, inverse, crop.
    const dsn::Support support = dsn::support_mask(9, DSN_SHAPE_RECTANGLE);
    const dsn::Texton texton = dsn::luminance_texton(model.spectrum, support);
    CHECK(texton.channels == 3);
    // Its uncropped version is real with the model's modulus: the cropped one has RME well below 1 but
    // above 0, and its luminance is concentrated at the origin (the maximum of L-weighted values).
    const double rme = dsn::relative_model_error(model.spectrum, texton);
    CHECK(rme > 0);
    CHECK(rme < 1);
    double best = -1;
    int best_index = -1;
    for (int i = 0; i < int(support.mask.size()); i++) {
        const size_t plane = support.mask.size();
        const double luminance = texton.values[size_t(i)] / 3 + texton.values[plane + size_t(i)] / 2 +
                                 texton.values[2 * plane + size_t(i)] / 6;
        if (luminance > best) best = luminance, best_index = i;
    }
    CHECK(best_index == 9 * 19 + 9); // the centre
}

namespace {

struct SotAgainstLuminance { // relative model errors over every frequency (the paper's)
    double rme = 0, rme_luminance = 0;
};

// Bakes the SOT (r = 15, 200 iterations) and the cropped luminance texton for one model, and checks the
// SOT's figures against the baseline's: RME no worse, DSN excess kurtosis <= 0.2 per channel and a fifth of
// the baseline's on average.
SotAgainstLuminance check_sot_beats_luminance(const std::string &name, const dsn::GaussianModel &model) {
    const dsn::Support support = dsn::support_mask(15, DSN_SHAPE_RECTANGLE);
    dsn::SotOptions options;
    options.iterations = 200;
    options.seed = 1;
    const dsn::SotResult sot = dsn::sot_alternating_projections(model.spectrum, support, options);
    const dsn::Texton luminance = dsn::luminance_texton(model.spectrum, support);
    SotAgainstLuminance result;
    result.rme = dsn::relative_model_error(model.spectrum, sot.texton);
    result.rme_luminance = dsn::relative_model_error(model.spectrum, luminance);
    MESSAGE(name << ": without the zero frequency, RME " << sot.rme_per_iteration.back() << " (luminance "
                 << dsn::relative_model_error_without_zero_frequency(model.spectrum, luminance) << ")");
    const std::vector<double> kurtosis = dsn::excess_kurtosis(sot.texton, 30);
    const std::vector<double> kurtosis_luminance = dsn::excess_kurtosis(luminance, 30);
    double mean_kurtosis = 0, mean_kurtosis_luminance = 0;
    for (size_t c = 0; c < kurtosis.size(); c++) {
        CHECK(kurtosis[c] <= 0.2);
        mean_kurtosis += kurtosis[c] / double(kurtosis.size());
        mean_kurtosis_luminance += kurtosis_luminance[c] / double(kurtosis.size());
    }
    MESSAGE(name << ": RME " << result.rme << " (luminance " << result.rme_luminance << "), kurtosis "
                 << mean_kurtosis << " (luminance " << mean_kurtosis_luminance << ")");
    CHECK(result.rme <= result.rme_luminance + 0.005);
    CHECK(mean_kurtosis * 5 <= mean_kurtosis_luminance);
    return result;
}

} // namespace

TEST_CASE("on generated random-phase exemplars of spread-out spots the SOT beats the cropped luminance "
          "texton (r = 15, 200 iterations)") {
    struct Generated {
        int width, height, channels, spot_radius;
        uint32_t seed;
    };
    // Grey and colour, square and not, even and prime sides; spots of radius 14 and 15 fill the support.
    const Generated cases[] = {
        {64, 64, 3, 14, 101}, {127, 80, 1, 15, 3}, {100, 100, 3, 15, 8}, {80, 96, 3, 14, 19}};
    double sum_sot = 0, sum_luminance = 0;
    for (const Generated &test : cases) {
        const std::string name = std::to_string(test.width) + "x" + std::to_string(test.height) + "x" +
                                 std::to_string(test.channels) + " spot radius " +
                                 std::to_string(test.spot_radius);
        CAPTURE(name);
        const dsn::Image exemplar = random_phase_texture(
            random_spot(test.width, test.height, test.channels, test.spot_radius, test.seed), test.seed + 1);
        // Exactly periodic: no periodic component needed.
        const SotAgainstLuminance result =
            check_sot_beats_luminance(name, dsn::gaussian_model(exemplar, false));
        sum_sot += result.rme;
        sum_luminance += result.rme_luminance;
    }
    CHECK(sum_sot < sum_luminance);
}

TEST_CASE("on the 8 named real textures the SOT beats the cropped luminance texton (r = 15, 200 iterations)" *
          doctest::skip(!textures_available())) {
    double sum_sot = 0, sum_luminance = 0;
    for (const std::string &name : named_textures()) {
        CAPTURE(name);
        std::vector<std::string> warnings;
        const dsn::Image exemplar = dsn::load_exemplar(textures_folder() + "/" + name + ".png", &warnings);
        const SotAgainstLuminance result =
            check_sot_beats_luminance(name, dsn::gaussian_model(exemplar, true));
        sum_sot += result.rme;
        sum_luminance += result.rme_luminance;
    }
    CHECK(sum_sot < sum_luminance);
}
