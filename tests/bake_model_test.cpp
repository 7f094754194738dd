// bake_model_test.cpp - DFTs, periodic component, Gaussian model and the bilinear interpolation target.
#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>

#include "fixtures/bake_fixtures.h"
#include "offline/bake_internal.h"

namespace {

dsn::Image noise_image(int width, int height, int channels, unsigned seed) {
    dsn::Image image;
    image.width = width;
    image.height = height;
    image.channels = channels;
    for (int i = 0; i < width * height * channels; i++) {
        seed = seed * 1664525u + 1013904223u;
        image.values.push_back(double(seed >> 8) / 16777216.0);
    }
    return image;
}

double max_difference(const dsn::Image &a, const dsn::Image &b) {
    double largest = 0;
    for (size_t i = 0; i < a.values.size(); i++)
        largest = std::max(largest, std::fabs(a.values[i] - b.values[i]));
    return largest;
}

} // namespace

TEST_CASE("forward_dft and inverse_dft are inverse, and forward_dft matches a direct DFT") {
    const dsn::Image image = noise_image(31, 57, 3, 1); // prime sizes: kissfft's generic radix
    const dsn::Spectrum spectrum = dsn::forward_dft(image);
    CHECK(max_difference(dsn::inverse_dft(spectrum), image) < 1e-5);
    const int xi1 = 3, xi2 = 11, c = 2;
    std::complex<double> direct = 0;
    for (int y = 0; y < image.height; y++)
        for (int x = 0; x < image.width; x++)
            direct += image.at(x, y, c) *
                      std::polar(1.0, -2 * M_PI * (double(xi1 * x) / 31 + double(xi2 * y) / 57));
    const std::complex<double> fast = spectrum.values[size_t(c) * 31 * 57 + size_t(xi2) * 31 + size_t(xi1)];
    CHECK(std::abs(fast - direct) < 1e-4 * std::abs(direct) + 1e-4);
}

TEST_CASE("periodic_component keeps the mean, leaves a border-matched image alone and removes border jumps") {
    // An image whose opposite borders agree: Lap_int u == Lap u, so p == u.
    dsn::Image matched = noise_image(20, 16, 1, 2);
    for (int y = 0; y < 16; y++) matched.at(19, y, 0) = matched.at(0, y, 0);
    for (int x = 0; x < 20; x++) matched.at(x, 15, 0) = matched.at(x, 0, 0);
    CHECK(max_difference(dsn::periodic_component(matched), matched) < 1e-5);

    // A horizontal ramp has a jump of 1 across the vertical border; its periodic component has none left
    // beyond the size of an ordinary step.
    dsn::Image ramp;
    ramp.width = 40, ramp.height = 30, ramp.channels = 1;
    for (int y = 0; y < 30; y++)
        for (int x = 0; x < 40; x++) ramp.values.push_back(x / 39.0);
    const dsn::Image periodic = dsn::periodic_component(ramp);
    double mean_in = 0, mean_out = 0, border_jump = 0;
    for (size_t i = 0; i < ramp.values.size(); i++) mean_in += ramp.values[i], mean_out += periodic.values[i];
    for (int y = 0; y < 30; y++)
        border_jump = std::max(border_jump, std::fabs(periodic.at(39, y, 0) - periodic.at(0, y, 0)));
    CHECK(std::fabs(mean_in - mean_out) / double(ramp.values.size()) < 1e-6);
    CHECK(border_jump < 2.0 / 39);
}

TEST_CASE("gaussian_model: per-channel mean, t_u carries the variance, constant images are refused") {
    const dsn::Image image = noise_image(24, 18, 3, 3);
    const dsn::GaussianModel model = dsn::gaussian_model(image, false);
    const size_t plane = 24 * 18;
    for (int c = 0; c < 3; c++) {
        double mean = 0, variance = 0, energy = 0;
        for (size_t i = 0; i < plane; i++) mean += image.values[size_t(c) * plane + i];
        mean /= double(plane);
        for (size_t i = 0; i < plane; i++) {
            variance += std::pow(image.values[size_t(c) * plane + i] - mean, 2) / double(plane);
            energy += std::pow(model.t_u.values[size_t(c) * plane + i], 2);
        }
        CHECK(model.mean[size_t(c)] == doctest::Approx(mean).epsilon(1e-12));
        CHECK(energy == doctest::Approx(variance).epsilon(1e-12)); // sum t_u^2 = variance
    }
    dsn::Image constant = image;
    for (double &value : constant.values) value = 0.25;
    CHECK_THROWS_WITH_AS(dsn::gaussian_model(constant, true), doctest::Contains("constant image"),
                         std::runtime_error);
    constant.values[5] = 0.5; // one differing pixel is a texture
    CHECK_NOTHROW(dsn::gaussian_model(constant, true));
}

TEST_CASE("interpolation_target divides the modulus by sqrt of the sampled cubic B-spline") {
    const dsn::GaussianModel model = dsn::gaussian_model(noise_image(16, 12, 1, 4), false);
    CHECK(dsn::interpolation_target(model.spectrum, DSN_INTERPOLATION_LATTICE).values ==
          model.spectrum.values);
    const dsn::Spectrum target = dsn::interpolation_target(model.spectrum, DSN_INTERPOLATION_BILINEAR);
    const int xi1 = 8, xi2 = 3; // xi1 = M/2: cos = -1, factor 1/3; xi2 = N/4: cos = 0, factor 2/3
    const size_t index = size_t(xi2) * 16 + size_t(xi1);
    const double expected = std::abs(model.spectrum.values[index]) / std::sqrt((1.0 / 3) * (2.0 / 3));
    CHECK(std::abs(target.values[index]) == doctest::Approx(expected).epsilon(1e-6));
    CHECK(target.values[0] == model.spectrum.values[0]); // the factor is 1 at the origin
    CHECK_THROWS_AS(dsn::interpolation_target(model.spectrum, 7), std::invalid_argument);
}
