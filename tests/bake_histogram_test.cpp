// bake_histogram_test.cpp - the baker's side of the histogram-preserving output (format 1.2): the colour
// basis, the Gaussianization, the tables' arithmetic, the Gaussian-space deviation against the runtime's
// output, and (through the runtime) the histograms and autocorrelations of synthesized textures.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "dsn/dsn.h"
#include "fixtures/bake_fixtures.h"
#include "fixtures/histogram_measures.h"
#include <doctest/doctest.h>

namespace {

using namespace histogram_measures;

// A random-phase texture: a Gaussian field with unit variance (bake_fixtures::spot_noise_field).
dsn::Image random_phase_field(int size, int channels, uint32_t seed) {
    return bake_fixtures::spot_noise_field(size, channels, seed, 0, 1);
}

enum class Tone { Skewed, Binary, TwoColour, Identity };

// The field through a tone curve, into [0, 1]: (a) exp, strongly right-skewed (skewness ~ 2.6 at this
// slope), (b) a threshold at 0.4 standard deviations (two levels, 34% light) per channel, or of channel
// 0 into two colours, (c) linear (Gaussian).
dsn::Image toned(const dsn::Image &field, Tone tone) {
    dsn::Image image = field;
    if (tone == Tone::TwoColour) {
        const double light[3] = {0.8, 0.6, 0.3}, dark[3] = {0.2, 0.25, 0.4};
        const size_t plane = size_t(field.width) * size_t(field.height);
        for (size_t i = 0; i < plane; i++)
            for (int c = 0; c < field.channels; c++)
                image.values[size_t(c) * plane + i] = field.values[i] > 0.4 ? light[c] : dark[c];
        return image;
    }
    for (double &value : image.values) {
        if (tone == Tone::Skewed)
            value = std::min(1.0, 0.05 + 0.06 * std::exp(0.9 * value));
        else if (tone == Tone::Binary)
            value = value > 0.4 ? 0.8 : 0.25;
        else
            value = std::clamp(0.5 + 0.12 * value, 0.0, 1.0);
    }
    return image;
}

dsn::BakeResult bake(const dsn::Image &exemplar, bool histogram, int radius = 10) {
    dsn::BakeOptions options;
    options.radius = radius;
    options.histogram = histogram;
    return dsn::bake(exemplar, options);
}

} // namespace

TEST_CASE("histogram: the normal quantile inverts the normal distribution function") {
    // Up to 5: beyond, normal_cdf(x) rounds to within a few ulps of 1, which the inverse cannot undo.
    for (double x = -8; x <= 5; x += 0.125)
        CHECK(dsn::normal_quantile(dsn::normal_cdf(x)) == doctest::Approx(x).epsilon(1e-9));
    CHECK(dsn::normal_quantile(0.5) == doctest::Approx(0).scale(1).epsilon(1e-15));
    CHECK(dsn::normal_quantile(0.975) == doctest::Approx(1.959963984540054).epsilon(1e-13));
    CHECK_THROWS_AS(dsn::normal_quantile(0), std::invalid_argument);
    CHECK_THROWS_AS(dsn::normal_quantile(1), std::invalid_argument);
}

TEST_CASE("histogram: the empirical quantile puts rank i at probability (i + 0.5) / n") {
    const std::vector<double> sorted = {1, 2, 4, 8};
    for (size_t i = 0; i < sorted.size(); i++)
        CHECK(dsn::empirical_quantile(sorted, (double(i) + 0.5) / 4) == sorted[i]);
    CHECK(dsn::empirical_quantile(sorted, 0.5) == 3);  // half way between ranks 1 and 2
    CHECK(dsn::empirical_quantile(sorted, 0.01) == 1); // the extremes beyond
    CHECK(dsn::empirical_quantile(sorted, 0.999) == 8);
}

TEST_CASE("histogram: principal components decorrelate, strongest first, with a fixed sign") {
    const dsn::Image image = toned(random_phase_field(64, 3, 2), Tone::Skewed);
    const dsn::ColourBasis basis = dsn::principal_components(image);
    const dsn::HistogramModel model = dsn::histogram_model(image);
    REQUIRE(model.sorted.size() == 3);
    CHECK(basis.variances[0] >= basis.variances[1]);
    CHECK(basis.variances[1] >= basis.variances[2]);
    for (int k = 0; k < 3; k++) {
        double largest = 0;
        for (int c = 0; c < 3; c++)
            if (std::fabs(basis.vectors[size_t(c * 3 + k)]) > std::fabs(largest))
                largest = basis.vectors[size_t(c * 3 + k)];
        CHECK(largest > 0);
        for (int m = 0; m < 3; m++) {
            double dot = 0;
            for (int c = 0; c < 3; c++)
                dot += basis.vectors[size_t(c * 3 + k)] * basis.vectors[size_t(c * 3 + m)];
            CHECK(dot == doctest::Approx(k == m ? 1 : 0).scale(1).epsilon(1e-12));
        }
        // The decorrelated channel's variance is the eigenvalue, and its mean 0.
        double sum = 0, square = 0;
        for (double value : model.sorted[size_t(k)]) sum += value, square += value * value;
        const double n = double(model.sorted[size_t(k)].size());
        CHECK(sum / n == doctest::Approx(0).scale(1).epsilon(1e-12));
        CHECK(square / n == doctest::Approx(basis.variances[size_t(k)]).epsilon(1e-9));
        CHECK(std::is_sorted(model.sorted[size_t(k)].begin(), model.sorted[size_t(k)].end()));
    }
}

TEST_CASE("histogram: Gaussianization keeps the order, ties together, and gives zero mean, unit variance") {
    for (Tone tone : {Tone::Skewed, Tone::Binary}) {
        const dsn::Image image = toned(random_phase_field(64, 1, 4), tone);
        const dsn::Image gaussian = dsn::gaussianize(image, dsn::histogram_model(image));
        const size_t n = gaussian.values.size();
        double sum = 0, square = 0, cubes = 0;
        for (double value : gaussian.values)
            sum += value, square += value * value, cubes += value * value * value;
        CHECK(sum / double(n) == doctest::Approx(0).scale(1).epsilon(1e-12));
        CHECK(square / double(n) == doctest::Approx(1).epsilon(1e-12));
        if (tone == Tone::Skewed) // symmetric ranks: no skewness left (of 2.6 before)
            CHECK(std::fabs(cubes / double(n)) < 0.01);
        for (size_t i = 0; i + 1 < n; i += 7) {
            const double a = image.values[i], b = image.values[i + 1];
            const double ga = gaussian.values[i], gb = gaussian.values[i + 1];
            CHECK((a < b ? ga < gb : a > b ? ga > gb : ga == gb));
        }
    }
}

TEST_CASE("histogram: the smoothed table is the exact Gaussian average of the piecewise-linear table") {
    const double low = -4, step = 0.125;
    std::vector<double> table(65);
    for (size_t i = 0; i < table.size(); i++) { // a step, a ramp and a kink
        const double x = low + double(i) * step;
        table[i] = x < -1 ? -0.5 : x < 1 ? 0.3 * x : 0.3 + 0.1 * (x - 1) * (x - 1);
    }
    for (double y : {-3.9, -1.0, 0.0, 0.37, 2.5})
        for (double rho : {0.0, 0.05, 0.4, 1.3}) {
            // Reference: the midpoint rule over +-10 rho, 200000 intervals.
            double expected;
            if (rho == 0) {
                expected = dsn::smoothed_table_value(table, low, step, y, 1e-300);
            } else {
                const int intervals = 200000;
                const double h = 20.0 / intervals;
                double sum = 0;
                for (int i = 0; i < intervals; i++) {
                    const double z = -10 + (i + 0.5) * h, x = y + rho * z;
                    const double position = std::clamp((x - low) / step, 0.0, 64.0);
                    const size_t j = std::min<size_t>(size_t(position), 63);
                    const double f = table[j] + (position - double(j)) * (table[j + 1] - table[j]);
                    sum += f * std::exp(-0.5 * z * z) / std::sqrt(2 * 3.14159265358979323846) * h;
                }
                expected = sum;
            }
            CHECK(dsn::smoothed_table_value(table, low, step, y, rho) ==
                  doctest::Approx(expected).epsilon(1e-8));
        }
}

TEST_CASE("histogram: the Gaussian-space deviation is the runtime's output deviation (Campbell)") {
    // The plain (1.1) asset of a Gaussianized exemplar: its output's standard deviation over a large tile
    // against the analytic one, within 4 standard errors of a sample variance of a correlated field,
    // sqrt(2 sum_lags rho^2 / N) relative (rho from the exemplar's own autocorrelation, which the noise
    // reproduces; lags beyond 2r + 2 are uncorrelated).
    for (uint32_t interpolation : {DSN_INTERPOLATION_BILINEAR, DSN_INTERPOLATION_LATTICE})
        for (int channels : {1, 3}) {
            const dsn::Image exemplar = toned(random_phase_field(96, channels, 6), Tone::Skewed);
            dsn::BakeOptions options;
            options.radius = 6;
            options.histogram = true;
            options.interpolation = interpolation;
            const dsn::BakeResult result = dsn::bake(exemplar, options);
            REQUIRE(result.gaussian_deviations.size() == 1 + result.fields.pyramid.size());
            dsn::AssetFields plain = result.fields;
            plain.histogram.tables.clear();
            const int size = 512;
            const std::vector<float> out = synthesize(dsn::encode_asset(plain), size, 3);
            for (int c = 0; c < channels; c++) {
                const std::vector<double> values = channel_of(out, channels, c);
                double mean = 0, square = 0;
                for (double value : values) mean += value;
                mean /= double(values.size());
                for (double value : values) square += (value - mean) * (value - mean);
                const double measured = square / double(values.size());
                const double predicted = std::pow(result.gaussian_deviations[0][size_t(c)], 2);
                double energy = 0;
                for (double rho : autocorrelation(channel_of(dsn::gaussianize(exemplar, result.histogram), c),
                                                  96, 96, 14, true))
                    energy += rho * rho;
                const double relative_error = std::sqrt(2 * energy / double(values.size()));
                INFO("channel " << c << " interpolation " << interpolation << ": measured " << measured
                                << " predicted " << predicted << " (standard error " << relative_error
                                << ")");
                CHECK(std::fabs(measured / predicted - 1) < 4 * relative_error);
                // The channel's share of the variance (its variance over the strongest one's; 1 for the
                // strongest), not exactly: the periodic component and the texton's error move it by a few
                // percent.
                const dsn::ColourBasis &basis = result.histogram.basis;
                CHECK(predicted ==
                      doctest::Approx(basis.variances[size_t(c)] / basis.variances[0]).epsilon(0.15));
            }
            // Every pyramid level removes variance, and the coarsest removes most of it.
            for (size_t l = 1; l < result.gaussian_deviations.size(); l++)
                for (int c = 0; c < channels; c++)
                    CHECK(result.gaussian_deviations[l][size_t(c)] <
                          result.gaussian_deviations[l - 1][size_t(c)]);
        }
}

TEST_CASE("histogram: the mapping's fields") {
    const dsn::Image exemplar = toned(random_phase_field(96, 3, 8), Tone::Binary);
    const dsn::BakeResult result = bake(exemplar, true, 6);
    const dsn::HistogramMapping &mapping = result.fields.histogram;
    const size_t levels = 1 + result.fields.pyramid.size();
    const size_t n = 129;
    CHECK(mapping.entry_count == n);
    CHECK(mapping.step_shift == 4);
    CHECK(mapping.input_low_q16 == -(4 << 16));
    CHECK(mapping.level_count == levels);
    REQUIRE(mapping.tables.size() == levels * 3 * n);
    for (int c = 0; c < 3; c++) {
        CHECK(mapping.centre[c] == std::lround(result.histogram.basis.mean[size_t(c)] * (1 << 24)));
        for (int k = 0; k < 3; k++)
            CHECK(mapping.rotation[c * 3 + k] ==
                  std::lround(result.histogram.basis.vectors[size_t(c * 3 + k)] * (1 << 24)));
    }
    for (int k = 0; k < 3; k++) {
        const std::vector<double> &sorted = result.histogram.sorted[size_t(k)];
        for (size_t l = 0; l < levels; l++) {
            const int32_t *table = &mapping.tables[(l * 3 + size_t(k)) * n];
            CHECK(std::is_sorted(table, table + n)); // monotone at every level
            // Within the channel's range (Q3.12 rounding aside).
            CHECK(table[0] >= std::lround(sorted.front() * 4096) - 1);
            CHECK(table[n - 1] <= std::lround(sorted.back() * 4096) + 1);
        }
        // Level 0's ends are the extremes; expected is the channel's mean (0) up to the table's resolution.
        CHECK(mapping.tables[size_t(k) * n] == std::lround(sorted.front() * 4096));
        CHECK(mapping.tables[size_t(k) * n + n - 1] == std::lround(sorted.back() * 4096));
        // The ramp of 1/16 between two table nodes moves the mean by at most (1/32) phi(0) of a jump.
        CHECK(std::fabs(mapping.expected_q16[k] / 65536.0) < 0.025 * (sorted.back() - sorted.front()));
    }
}

namespace {

// What a bake's synthesis keeps of its exemplar, per channel: W1 of the histograms and the spectrum
// error, with the sampling noise of both for a tile of this size.
// W1 both in the exemplar's channels and in its decorrelated ones (the channels the tables map).
struct Kept {
    std::vector<double> w1, w1_decorrelated, spectrum, w1_noise, spectrum_noise;
    std::vector<double> variance_share; // of each decorrelated channel, to the strongest one's
};

Kept kept(const dsn::Image &exemplar, const dsn::BakeResult &result, int tile) {
    const int radius = (int(result.fields.width) - 1) / 2, reach = 2 * radius;
    const std::vector<float> out = synthesize(result.asset, tile, 5, 1000, -700);
    const dsn::ColourBasis basis = dsn::principal_components(exemplar);
    std::vector<double> targets[3], outputs[3];
    for (int c = 0; c < exemplar.channels; c++)
        targets[c] = channel_of(exemplar, c), outputs[c] = channel_of(out, exemplar.channels, c);
    Kept measured;
    for (int c = 0; c < exemplar.channels; c++) {
        const std::vector<double> &target = targets[c], &output = outputs[c];
        measured.w1.push_back(wasserstein1(output, target));
        measured.w1_decorrelated.push_back(
            wasserstein1(decorrelated_channel(outputs, output.size(), basis, c),
                         decorrelated_channel(targets, target.size(), basis, c)));
        measured.variance_share.push_back(basis.variances[size_t(c)] / basis.variances[0]);
        const std::vector<double> target_correlation =
            autocorrelation(target, exemplar.width, exemplar.height, reach, true);
        measured.spectrum.push_back(
            spectrum_error(autocorrelation(output, tile, tile, reach, false), target_correlation));
        // Sampling noise for the tile's N values: an autocorrelation's variance at any lag is
        // sum_lags rho^2 / N (Bartlett), so the window's L lags add sqrt(L sum rho^2 / N) to the
        // error's numerator; a quantile's standard error is about deviation sqrt(sum rho^2 / N), and so
        // is W1's.
        double energy = 0, mean = 0, square = 0;
        for (double rho : target_correlation) energy += rho * rho;
        for (double value : target) mean += value;
        mean /= double(target.size());
        for (double value : target) square += (value - mean) * (value - mean);
        const double n = double(output.size());
        measured.spectrum_noise.push_back(std::sqrt(double(target_correlation.size()) * energy / n) /
                                          std::sqrt(energy));
        measured.w1_noise.push_back(std::sqrt(square / double(target.size())) * std::sqrt(energy / n));
    }
    return measured;
}

} // namespace

TEST_CASE("histogram: skewed and two-level tones keep their histogram, Gaussian ones lose nothing") {
    // 128 x 128 random-phase textures through tone curves, r = 10, a 512 x 512 continuous tile. W1 of the
    // plain bake is the distance between a Gaussian and the tones; the histogram-preserving bake must
    // cut it to a third at least. Its spectrum error: on monotone tone curves of a Gaussian field (a, c)
    // the Gaussianized exemplar is the field itself, so the output is the exemplar's process and its
    // error is the plain bake's (the texton's model error and the sampling noise) within 4 standard
    // errors; a two-level exemplar (b) is Gaussianized to two values whose correlations the threshold
    // shrinks again (for a threshold at the median rho -> (2/pi) asin rho, at most 0.21 lower), so its
    // error may exceed the plain bake's by up to 0.25. W1 is cut to a third in the decorrelated channels
    // the tables map, in every case (in the channels that hold a visible share of the variance, 10% of
    // the strongest one's as in the verdict: the others are flat up to noise); in the exemplar's own
    // channels too, except where three channels
    // thresholded each on its own make eight colours whose decorrelated channels are not independent:
    // the mapping, one table per decorrelated channel, cannot give back that joint law, and there only
    // has to beat the plain bake.
    struct Case {
        Tone tone;
        int channels;
        std::string name;
    };
    for (const Case &test :
         {Case{Tone::Skewed, 1, "skewed grey"}, Case{Tone::Skewed, 3, "skewed RGB"},
          Case{Tone::Binary, 1, "binary grey"}, Case{Tone::TwoColour, 3, "two-colour RGB"},
          Case{Tone::Binary, 3, "binary RGB, channels thresholded apart"},
          Case{Tone::Identity, 1, "Gaussian grey"}, Case{Tone::Identity, 3, "Gaussian RGB"}}) {
        const dsn::Image exemplar = toned(random_phase_field(128, test.channels, 12), test.tone);
        const Kept plain = kept(exemplar, bake(exemplar, false), 512);
        const Kept mapped = kept(exemplar, bake(exemplar, true), 512);
        for (int c = 0; c < test.channels; c++) {
            const size_t i = size_t(c);
            MESSAGE(test.name << " channel " << c << ": W1 " << mapped.w1[i] << " vs plain " << plain.w1[i]
                              << " (ratio " << mapped.w1[i] / plain.w1[i] << ", noise " << plain.w1_noise[i]
                              << "; decorrelated channel " << c << ": ratio "
                              << mapped.w1_decorrelated[i] / plain.w1_decorrelated[i] << "); spectrum error "
                              << mapped.spectrum[i] << " vs plain " << plain.spectrum[i] << " (noise "
                              << plain.spectrum_noise[i] << ")");
            if (test.tone == Tone::Identity) {
                CHECK(mapped.w1[i] <= plain.w1[i] + 4 * plain.w1_noise[i]);
                CHECK(std::fabs(mapped.spectrum[i] - plain.spectrum[i]) <= 4 * plain.spectrum_noise[i]);
            } else {
                if (plain.variance_share[i] >= 0.1)
                    CHECK(mapped.w1_decorrelated[i] <= plain.w1_decorrelated[i] / 3);
                CHECK(mapped.w1[i] <=
                      (test.tone == Tone::Binary && test.channels == 3 ? 1 : 1.0 / 3) * plain.w1[i]);
                const double allowed = test.tone == Tone::Skewed ? 4 * plain.spectrum_noise[i] : 0.25;
                CHECK(mapped.spectrum[i] <= plain.spectrum[i] + allowed);
            }
        }
    }
}

TEST_CASE("histogram: a grey picture stored as RGB bakes, its empty channels mapped to a constant") {
    dsn::Image grey = toned(random_phase_field(64, 1, 14), Tone::Skewed), rgb = grey;
    rgb.channels = 3;
    rgb.values.insert(rgb.values.end(), grey.values.begin(), grey.values.end());
    rgb.values.insert(rgb.values.end(), grey.values.begin(), grey.values.end());
    const dsn::BakeResult result = bake(rgb, true, 6);
    const std::vector<float> out = synthesize(result.asset, 64, 1);
    for (size_t i = 0; i < out.size(); i += 3) {
        CHECK(out[i + 1] == doctest::Approx(out[i]).epsilon(1e-3));
        CHECK(out[i + 2] == doctest::Approx(out[i]).epsilon(1e-3));
    }
}

TEST_CASE("histogram: the prefiltered tables keep a filtered pixel's mean at the exemplar's") {
    // A two-level exemplar (34% light): the filtered evaluation at footprints of 2 to 32 texels averages
    // to the exemplar's mean within 4 standard errors of a mean over an area A of 509^2 texels (96^2
    // points 5.3 texels apart): variance sigma^2 sum_lags rho / A, which filtering does not change (it
    // keeps the spectrum at frequency 0), with sigma and rho the exemplar's (lags within the texton's
    // reach). The same asset with level 0's table at every level drifts towards the dark tone, beyond
    // that tolerance from 4 texels on and beyond twice it at 8. Beyond the coarsest level both give
    // `expected`, which sits within (1/32) phi(0) of the jump of the exemplar's mean (the table's linear
    // ramp across the step).
    const dsn::Image exemplar = toned(random_phase_field(128, 1, 21), Tone::Binary);
    const dsn::BakeResult result = bake(exemplar, true);
    dsn::AssetFields unfiltered = result.fields;
    const size_t entries = unfiltered.histogram.entry_count;
    for (size_t l = 1; l < unfiltered.histogram.level_count; l++)
        std::copy(unfiltered.histogram.tables.begin(), unfiltered.histogram.tables.begin() + long(entries),
                  unfiltered.histogram.tables.begin() + long(l * entries));
    const std::vector<unsigned char> unfiltered_bytes = dsn::encode_asset(unfiltered);
    double exemplar_mean = 0, exemplar_variance = 0, correlation_area = 0;
    for (double value : exemplar.values) exemplar_mean += value;
    exemplar_mean /= double(exemplar.values.size());
    for (double value : exemplar.values) exemplar_variance += std::pow(value - exemplar_mean, 2);
    exemplar_variance /= double(exemplar.values.size());
    for (double rho : autocorrelation(exemplar.values, 128, 128, 20, true)) correlation_area += rho;
    const int side = 96;
    const double spacing = 5.3,
                 tolerance = 4 * std::sqrt(exemplar_variance * correlation_area) / (side * spacing);
    for (double width : {2.0, 4.0, 8.0, 32.0}) {
        double means[2] = {0, 0};
        for (int which = 0; which < 2; which++) {
            const std::vector<unsigned char> &bytes = which == 0 ? result.asset : unfiltered_bytes;
            dsn_noise noise;
            REQUIRE(dsn_noise_load(&noise, bytes.data(), bytes.size(), 4) == DSN_OK);
            dsn_footprint footprint;
            REQUIRE(dsn_footprint_from_float(&footprint, width, 0, 0, width, 1) == DSN_OK);
            for (int j = 0; j < side; j++)
                for (int i = 0; i < side; i++) {
                    float value;
                    REQUIRE(dsn_filtered_point_float(&noise, 3.1 + i * spacing, 7.9 + j * spacing, &footprint,
                                                     &value) == DSN_OK);
                    means[which] += value / (side * side);
                }
        }
        MESSAGE("footprint " << width << ": mean " << means[0] << " (level 0's table everywhere: " << means[1]
                             << "), exemplar " << exemplar_mean << ", tolerance " << tolerance);
        CHECK(std::fabs(means[0] - exemplar_mean) < tolerance);
        if (width >= 4 && width <= 8) CHECK(std::fabs(means[1] - exemplar_mean) > tolerance);
        if (width == 8) CHECK(std::fabs(means[1] - exemplar_mean) > 2 * tolerance);
        if (width >= 32) CHECK(std::fabs(means[0] - exemplar_mean) < 0.4 / 32 * (0.8 - 0.25));
    }
}
