// synth_test.cpp - RPN and ADSN synthesis (offline/synth.h): the statistics each method keeps, the spot
// extension, the block 2-D DFT and the refused inputs.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "offline/bake_internal.h"
#include "offline/synth.h"

namespace {

using Covariance = std::array<std::array<double, 3>, 3>;

// A colour exemplar whose channels correlate, with a ramp across it (so its periodic component differs
// from it) and a wave of amplitude `wave` across the rows.
dsn::Image correlated_exemplar(int width, int height, unsigned seed, double wave = 0.1) {
    dsn::Image image;
    image.width = width;
    image.height = height;
    image.channels = 3;
    image.values.resize(size_t(width) * size_t(height) * 3);
    std::vector<double> a(size_t(width) * size_t(height)), b(a.size());
    for (size_t i = 0; i < a.size(); i++) {
        seed = seed * 1664525u + 1013904223u;
        a[i] = double(seed >> 8) / 16777216.0;
        seed = seed * 1664525u + 1013904223u;
        b[i] = double(seed >> 8) / 16777216.0;
    }
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++) {
            const size_t i = size_t(y) * size_t(width) + size_t(x);
            const size_t right = size_t(y) * size_t(width) + size_t((x + 1) % width);
            const double smooth = 0.5 * (a[i] + a[right]);
            const double ramp = 0.3 * x / width + wave * std::sin(0.4 * y);
            image.at(x, y, 0) = 0.2 + 0.5 * smooth + ramp;
            image.at(x, y, 1) = 0.1 + 0.3 * smooth + 0.3 * b[i] + 0.5 * ramp;
            image.at(x, y, 2) = 0.6 - 0.2 * smooth + 0.1 * b[i];
        }
    return image;
}

std::array<double, 3> channel_means(const dsn::Image &image) {
    std::array<double, 3> means = {0, 0, 0};
    const size_t plane = size_t(image.width) * size_t(image.height);
    for (int c = 0; c < image.channels; c++) {
        for (size_t i = 0; i < plane; i++) means[size_t(c)] += image.values[size_t(c) * plane + i];
        means[size_t(c)] /= double(plane);
    }
    return means;
}

// The empirical covariance (1/N) sum (f_c - mean_c)(f_d - mean_d) of the channels.
Covariance channel_covariance(const dsn::Image &image) {
    const std::array<double, 3> means = channel_means(image);
    const size_t plane = size_t(image.width) * size_t(image.height);
    Covariance covariance = {};
    for (int c = 0; c < image.channels; c++)
        for (int d = 0; d < image.channels; d++) {
            double sum = 0;
            for (size_t i = 0; i < plane; i++)
                sum += (image.values[size_t(c) * plane + i] - means[size_t(c)]) *
                       (image.values[size_t(d) * plane + i] - means[size_t(d)]);
            covariance[size_t(c)][size_t(d)] = sum / double(plane);
        }
    return covariance;
}

// ADSN's expected covariance sum_x t_c(x) t_d(x) and the standard deviation of its empirical covariance
// over the white noise: with a_xi = Re(T_c(xi) conj T_d(xi)) / N, the estimate is sum a_xi E_xi where
// E_xi = |W(xi)|^2 / N is exponential of mean 1 (E_-xi = E_xi) or chi-square with one degree of freedom
// at the self-conjugate frequencies, so its variance is 2 sum a_xi^2 in both cases.
struct Expected {
    double value = 0, deviation = 0;
};
Expected adsn_covariance(const dsn::Spectrum &spot, int c, int d) {
    const size_t plane = spot.plane_size();
    Expected expected;
    double squares = 0;
    for (size_t i = 1; i < plane; i++) {
        const std::complex<double> tc = spot.values[size_t(c) * plane + i];
        const std::complex<double> td = spot.values[size_t(d) * plane + i];
        const double a = (tc * std::conj(td)).real() / double(plane);
        expected.value += a;
        squares += a * a;
    }
    expected.deviation = std::sqrt(2 * squares);
    return expected;
}

dsn::SynthesisOptions options_for(int width, int height, dsn::SynthesisMethod method, uint32_t seed) {
    dsn::SynthesisOptions options;
    options.width = width;
    options.height = height;
    options.method = method;
    options.seed = seed;
    return options;
}

double largest_modulus(const dsn::Spectrum &spectrum) {
    double largest = 0;
    for (const std::complex<float> &value : spectrum.values)
        largest = std::max(largest, double(std::abs(value)));
    return largest;
}

} // namespace

TEST_CASE("synth: the smooth transition rises from 0 to 1, symmetric about 1/2") {
    CHECK(dsn::smooth_transition(-1) == 0);
    CHECK(dsn::smooth_transition(0) == 0);
    CHECK(dsn::smooth_transition(1) == 1);
    CHECK(dsn::smooth_transition(2) == 1);
    CHECK(dsn::smooth_transition(0.5) == doctest::Approx(0.5).epsilon(1e-15));
    double previous = 0;
    for (int i = 1; i < 100; i++) {
        const double s = i / 100.0, value = dsn::smooth_transition(s);
        CHECK(value >= previous);
        if (s <= 0.9) CHECK(value > previous); // beyond, 1 - h(s) < 1e-16: 1 in double
        CHECK(value + dsn::smooth_transition(1 - s) == doctest::Approx(1.0).epsilon(1e-12));
        previous = value;
    }
    // Flat at both ends (every derivative is 0 there): far below a linear ramp near 0.
    CHECK(dsn::smooth_transition(0.05) < 1e-8);
}

TEST_CASE("synth: the block 2-D DFT equals the reference DFT, sizes from 64 x 64 up") {
    for (const auto &size :
         {std::pair<int, int>(64, 64), std::pair<int, int>(80, 72), std::pair<int, int>(67, 33)}) {
        const dsn::Image image = correlated_exemplar(size.first, size.second, 5);
        const dsn::Spectrum reference = dsn::forward_dft(image);
        const size_t plane = reference.plane_size();
        std::vector<std::complex<float>> values(plane);
        int steps = 0;
        for (size_t i = 0; i < plane; i++) values[i] = float(image.values[i]);
        dsn::dft_2d_in_place(values.data(), size.first, size.second, false, [&](int done) { steps = done; });
        CHECK(steps == dsn::dft_2d_block_count(size.first, size.second));
        // Float transforms of a few thousand points: agreement to 1e-5 of the largest coefficient.
        const double tolerance = 1e-5 * largest_modulus(reference);
        double worst = 0;
        for (size_t i = 0; i < plane; i++)
            worst = std::max(worst, double(std::abs(values[i] - reference.values[i])));
        CHECK(worst <= tolerance);
        dsn::dft_2d_in_place(values.data(), size.first, size.second, true, nullptr);
        worst = 0;
        for (size_t i = 0; i < plane; i++)
            worst = std::max(worst, std::abs(double(values[i].real()) / double(plane) - image.values[i]));
        CHECK(worst <= 1e-5);
    }
}

TEST_CASE("synth: RPN at the exemplar size keeps the periodic component's spectrum modulus, mean and "
          "colour covariance") {
    const dsn::Image exemplar = correlated_exemplar(96, 80, 11);
    const dsn::Image periodic = dsn::periodic_component(exemplar);
    const dsn::Spectrum periodic_spectrum = dsn::forward_dft(periodic);
    const dsn::Image rpn = dsn::synthesize(exemplar, options_for(96, 80, dsn::SynthesisMethod::rpn, 3));
    REQUIRE(rpn.width == 96);
    REQUIRE(rpn.height == 80);
    REQUIRE(rpn.channels == 3);
    const dsn::Spectrum rpn_spectrum = dsn::forward_dft(rpn);
    const size_t plane = periodic_spectrum.plane_size();
    // |RPN^| = |p^| at every frequency, and the channels share one phase: RPN_c^ conj(RPN_d^) = p_c^
    // conj(p_d^). Float transforms: 1e-5 of the largest coefficient.
    const double tolerance = 1e-5 * largest_modulus(periodic_spectrum);
    double worst_modulus = 0, worst_cross = 0, phase_moved = 0;
    for (size_t i = 0; i < plane; i++) {
        for (int c = 0; c < 3; c++) {
            const std::complex<double> r = rpn_spectrum.values[size_t(c) * plane + i];
            const std::complex<double> p = periodic_spectrum.values[size_t(c) * plane + i];
            worst_modulus = std::max(worst_modulus, std::abs(std::abs(r) - std::abs(p)));
            phase_moved = std::max(phase_moved, std::abs(r - p));
            const std::complex<double> r_next = rpn_spectrum.values[size_t((c + 1) % 3) * plane + i];
            const std::complex<double> p_next = periodic_spectrum.values[size_t((c + 1) % 3) * plane + i];
            worst_cross = std::max(worst_cross, std::abs(r * std::conj(r_next) - p * std::conj(p_next)) /
                                                    std::max(1.0, std::abs(p) + std::abs(p_next)));
        }
    }
    CHECK(worst_modulus <= tolerance);
    CHECK(worst_cross <= tolerance);
    CHECK(phase_moved > 100 * tolerance); // the phases did change: not the periodic component itself

    const std::array<double, 3> exemplar_means = channel_means(exemplar), rpn_means = channel_means(rpn);
    const Covariance expected = channel_covariance(periodic), measured = channel_covariance(rpn);
    for (size_t c = 0; c < 3; c++) {
        CHECK(rpn_means[c] == doctest::Approx(exemplar_means[c]).epsilon(1e-6));
        for (size_t d = 0; d < 3; d++)
            CHECK(measured[c][d] == doctest::Approx(expected[c][d]).epsilon(1e-4).scale(expected[c][c]));
    }
}

TEST_CASE("synth: ADSN keeps the mean exactly and the colour covariance within its sampling error") {
    // A faint wave: the variance spread over many frequencies, so the sampling error is small.
    const dsn::Image exemplar = correlated_exemplar(96, 80, 12, 0.01);
    const dsn::GaussianModel model = dsn::gaussian_model(exemplar, true);
    const dsn::Spectrum spot_spectrum = dsn::forward_dft(model.t_u);
    const std::array<double, 3> exemplar_means = channel_means(exemplar);
    for (uint32_t seed : {1u, 2u, 3u}) {
        const dsn::Image adsn =
            dsn::synthesize(exemplar, options_for(96, 80, dsn::SynthesisMethod::adsn, seed));
        const std::array<double, 3> means = channel_means(adsn);
        const Covariance measured = channel_covariance(adsn);
        for (int c = 0; c < 3; c++) {
            CHECK(means[size_t(c)] == doctest::Approx(exemplar_means[size_t(c)]).epsilon(1e-6));
            for (int d = 0; d < 3; d++) {
                const Expected expected = adsn_covariance(spot_spectrum, c, d);
                // The bound has power: the sampling error is a few percent of the variance here.
                if (c == d) CHECK(expected.deviation < 0.05 * expected.value);
                CHECK(std::abs(measured[size_t(c)][size_t(d)] - expected.value) <= 4 * expected.deviation);
            }
        }
    }
}

TEST_CASE("synth: the extended spot keeps each channel's variance, sums to 0 and fades at its border") {
    const dsn::Image exemplar = correlated_exemplar(64, 48, 13);
    const dsn::GaussianModel model = dsn::gaussian_model(exemplar, true);
    const dsn::SynthesisDomain domain = dsn::synthesis_domain(64, 48, 200, 100);
    CHECK(domain.width == 200);
    CHECK(domain.height == 100);
    CHECK(domain.extend_x);
    CHECK(domain.extend_y);
    const dsn::Image spot = dsn::extended_spot(model, domain, 0.2);
    const size_t plane = size_t(domain.width) * size_t(domain.height);
    const int offset_x = (200 - 64) / 2, offset_y = (100 - 48) / 2;
    for (int c = 0; c < 3; c++) {
        double spot_energy = 0, model_energy = 0, sum = 0, outside = 0;
        for (size_t i = 0; i < plane; i++) {
            const double value = spot.values[size_t(c) * plane + i];
            spot_energy += value * value;
            sum += value;
            const int x = int(i % size_t(domain.width)), y = int(i / size_t(domain.width));
            if (x < offset_x || x >= offset_x + 64 || y < offset_y || y >= offset_y + 48)
                outside = std::max(outside, std::abs(value));
        }
        for (int y = 0; y < 48; y++)
            for (int x = 0; x < 64; x++) model_energy += model.t_u.at(x, y, c) * model.t_u.at(x, y, c);
        CHECK(spot_energy == doctest::Approx(model_energy).epsilon(1e-6));
        CHECK(std::abs(sum) <= 1e-6 * std::sqrt(model_energy));
        CHECK(outside == 0);
        // The outermost ring of the pasted spot is attenuated to almost nothing; its middle is not.
        double ring = 0, middle = 0;
        for (int x = 0; x < 64; x++) {
            ring = std::max(ring, std::abs(spot.at(offset_x + x, offset_y, c)));
            ring = std::max(ring, std::abs(spot.at(offset_x + x, offset_y + 47, c)));
        }
        for (int y = 0; y < 48; y++) {
            ring = std::max(ring, std::abs(spot.at(offset_x, offset_y + y, c)));
            ring = std::max(ring, std::abs(spot.at(offset_x + 63, offset_y + y, c)));
        }
        for (int y = 20; y < 28; y++)
            for (int x = 28; x < 36; x++)
                middle = std::max(middle, std::abs(spot.at(offset_x + x, offset_y + y, c)));
        CHECK(ring < 1e-3 * middle);
    }
    // An axis that is not extended is left whole: a wider output with the exemplar's height.
    const dsn::SynthesisDomain wide = dsn::synthesis_domain(64, 48, 128, 48);
    CHECK(wide.extend_x);
    CHECK_FALSE(wide.extend_y);
    const dsn::Image wide_spot = dsn::extended_spot(model, wide, 0.2);
    for (int y = 0; y < 48; y++) CHECK(wide_spot.at(32 + 32, y, 0) != 0);
}

TEST_CASE("synth: a larger RPN keeps the exemplar's mean and each channel's variance exactly") {
    const dsn::Image exemplar = correlated_exemplar(64, 48, 14);
    const dsn::Image periodic = dsn::periodic_component(exemplar);
    // 128 x 96 factors well: the FFT domain is the output, so the RPN's variance is the spot's.
    const dsn::Image rpn = dsn::synthesize(exemplar, options_for(128, 96, dsn::SynthesisMethod::rpn, 4));
    const Covariance expected = channel_covariance(periodic), measured = channel_covariance(rpn);
    const std::array<double, 3> exemplar_means = channel_means(exemplar), means = channel_means(rpn);
    for (size_t c = 0; c < 3; c++) {
        CHECK(means[c] == doctest::Approx(exemplar_means[c]).epsilon(1e-6));
        CHECK(measured[c][c] == doctest::Approx(expected[c][c]).epsilon(1e-4));
    }
    // ADSN of the same extended spot: the covariance of the spot within its sampling error.
    const dsn::GaussianModel model = dsn::gaussian_model(exemplar, true);
    const dsn::Spectrum spot_spectrum =
        dsn::forward_dft(dsn::extended_spot(model, dsn::synthesis_domain(64, 48, 128, 96), 0.2));
    const dsn::Image adsn = dsn::synthesize(exemplar, options_for(128, 96, dsn::SynthesisMethod::adsn, 4));
    const Covariance adsn_measured = channel_covariance(adsn);
    for (int c = 0; c < 3; c++)
        for (int d = 0; d < 3; d++) {
            const Expected spot_covariance = adsn_covariance(spot_spectrum, c, d);
            CHECK(std::abs(adsn_measured[size_t(c)][size_t(d)] - spot_covariance.value) <=
                  4 * spot_covariance.deviation);
        }
}

TEST_CASE("synth: any output size, reproducible from the seed") {
    const dsn::Image exemplar = correlated_exemplar(64, 48, 15);
    for (const auto method : {dsn::SynthesisMethod::adsn, dsn::SynthesisMethod::rpn}) {
        // 101 x 67: the FFT runs on a larger well-factored domain and the output is a part of it; 30 x 20:
        // smaller than the exemplar.
        for (const auto &size :
             {std::pair<int, int>(101, 67), std::pair<int, int>(30, 20), std::pair<int, int>(1, 1)}) {
            const dsn::Image first =
                dsn::synthesize(exemplar, options_for(size.first, size.second, method, 9));
            const dsn::Image again =
                dsn::synthesize(exemplar, options_for(size.first, size.second, method, 9));
            const dsn::Image other =
                dsn::synthesize(exemplar, options_for(size.first, size.second, method, 10));
            CHECK(first.width == size.first);
            CHECK(first.height == size.second);
            CHECK(first.values == again.values);
            CHECK(first.values != other.values);
            for (double value : first.values) CHECK(std::isfinite(value));
        }
    }
    const dsn::SynthesisDomain domain = dsn::synthesis_domain(64, 48, 101, 67);
    CHECK(domain.width >= 101);
    CHECK(domain.height >= 67);
    CHECK(dsn::synthesis_memory_bytes(64, 48, 3, 16384, 16384) == uint64_t(16384) * 16384 * (16 + 24));
}

TEST_CASE("synth: bad options and unusable exemplars are refused with a message") {
    const dsn::Image exemplar = correlated_exemplar(32, 32, 16);
    auto refuses = [&](dsn::SynthesisOptions options, const char *fragment) {
        try {
            dsn::synthesize(exemplar, options);
            FAIL("accepted: " << fragment);
        } catch (const std::invalid_argument &error) {
            CHECK(std::string(error.what()).find(fragment) != std::string::npos);
        }
    };
    refuses(options_for(0, 10, dsn::SynthesisMethod::adsn, 0), "output width 0 out of range 1..16384");
    refuses(options_for(10, 16385, dsn::SynthesisMethod::adsn, 0), "output height 16385 out of range");
    dsn::SynthesisOptions options = options_for(10, 10, dsn::SynthesisMethod::rpn, 0);
    for (double alpha : {0.0, -0.1, 0.51, std::numeric_limits<double>::quiet_NaN()}) {
        options.alpha = alpha;
        refuses(options, "alpha must be within (0, 0.5]");
    }
    dsn::Image constant = exemplar;
    std::fill(constant.values.begin(), constant.values.end(), 0.5);
    CHECK_THROWS_WITH_AS(dsn::synthesize(constant, options_for(10, 10, dsn::SynthesisMethod::adsn, 0)),
                         doctest::Contains("constant image"), std::runtime_error);
    dsn::Image empty;
    CHECK_THROWS_AS(dsn::synthesize(empty, options_for(10, 10, dsn::SynthesisMethod::adsn, 0)),
                    std::runtime_error);
}
