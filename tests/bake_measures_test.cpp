// bake_measures_test.cpp - relative model error, DSN excess kurtosis, colour transform and quantization
// (the real-texture case is skipped when the texture folder is absent).
#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>

#include "fixtures/bake_fixtures.h"
#include "offline/bake_internal.h"

using namespace bake_fixtures;

namespace {

dsn::Texton texton_of(int radius, int channels, std::initializer_list<double> pattern) {
    dsn::Texton texton;
    texton.support = dsn::support_mask(radius, DSN_SHAPE_RECTANGLE);
    texton.channels = channels;
    texton.values.assign(texton.support.mask.size() * size_t(channels), 0.0);
    size_t i = 0;
    for (double value : pattern) texton.values[i++] = value;
    return texton;
}

dsn::Matrix3 transform_covariance(const dsn::Matrix3 &k, const dsn::Matrix3 &a) { // K A K^T
    dsn::Matrix3 result{};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            for (int p = 0; p < 3; p++)
                for (int q = 0; q < 3; q++)
                    result[size_t(i * 3 + j)] +=
                        k[size_t(i * 3 + p)] * a[size_t(p * 3 + q)] * k[size_t(j * 3 + q)];
    return result;
}

double relative_difference(const dsn::Matrix3 &a, const dsn::Matrix3 &b) {
    double difference = 0, norm = 0;
    for (size_t i = 0; i < 9; i++) difference += (a[i] - b[i]) * (a[i] - b[i]), norm += b[i] * b[i];
    return std::sqrt(difference / norm);
}

} // namespace

TEST_CASE("relative_model_error: 0 for the model and any phase of it, 1 for nothing, sqrt 2 for twice") {
    const dsn::GaussianModel model = dsn::gaussian_model(random_phase_exemplar(32, 24, 3, 1), false);
    CHECK(dsn::relative_model_error(model.spectrum, model.spectrum) < 1e-6);
    CHECK(dsn::relative_model_error(model.spectrum, dsn::random_phase_start(model.spectrum, 4)) < 1e-5);
    dsn::Spectrum zero = model.spectrum, twice = model.spectrum;
    for (auto &value : zero.values) value = 0;
    for (auto &value : twice.values) value *= 2.0f;
    CHECK(dsn::relative_model_error(model.spectrum, zero) == doctest::Approx(1.0).epsilon(1e-9));
    // |T_u|^2 + 4|T_u|^2 - 4|T_u|^2 = |T_u|^2 per frequency: RME 1.
    CHECK(dsn::relative_model_error(model.spectrum, twice) == doctest::Approx(1.0).epsilon(1e-6));
    // A texton equal to the spot itself is an exact answer.
    const dsn::Texton spot =
        dsn::crop_to_support(known_spot(32, 24, 3), dsn::support_mask(9, DSN_SHAPE_RECTANGLE));
    const dsn::Spectrum spot_spectrum = dsn::texton_spectrum(spot, 32, 24);
    CHECK(dsn::relative_model_error(spot_spectrum, spot) < 1e-6);
    CHECK(dsn::relative_model_error(spot_spectrum, dsn::luminance_texton(spot_spectrum, spot.support)) >
          0.01);
}

TEST_CASE("relative_model_error sums every frequency as the SOT paper does: a texton with a non-zero sum "
          "adds its |T(0)|^2, which relative_model_error_without_zero_frequency leaves out") {
    const dsn::GaussianModel model = dsn::gaussian_model(random_phase_exemplar(40, 36, 3, 2), false);
    double model_energy = 0; // sum over every frequency and channel of |T_u|^2; T_u(0) = 0
    for (const auto &value : model.spectrum.values) model_energy += std::norm(std::complex<double>(value));
    const size_t plane = model.spectrum.plane_size();
    for (int c = 0; c < 3; c++) CHECK(std::abs(model.spectrum.values[size_t(c) * plane]) < 1e-5);
    // t_u cropped to a small support: its values do not sum to zero.
    const dsn::Texton cropped =
        dsn::crop_to_support(dsn::inverse_dft(model.spectrum), dsn::support_mask(6, DSN_SHAPE_RECTANGLE));
    const size_t points = cropped.support.mask.size();
    double sum_squares = 0;
    for (int c = 0; c < 3; c++) {
        double sum = 0;
        for (size_t i = 0; i < points; i++) sum += cropped.values[size_t(c) * points + i];
        sum_squares += sum * sum;
    }
    const double every = dsn::relative_model_error(model.spectrum, cropped);
    const double without = dsn::relative_model_error_without_zero_frequency(model.spectrum, cropped);
    MESSAGE("cropped t_u: RME " << every << ", without the zero frequency " << without
                                << ", |T(0)|^2 / |T_u|^2 " << sum_squares / model_energy);
    REQUIRE(sum_squares / model_energy > 1e-3); // a texton that does have a sum worth measuring
    // The two differ by exactly the zero frequency's term: T(0) = sum_x t(x) per channel, and T_u(0) = 0
    // leaves no cross term there.
    CHECK(every * every == doctest::Approx(without * without + sum_squares / model_energy).epsilon(1e-6));
    CHECK(every > without);
    // The same texton with each channel's sum removed over the support: the definitions agree.
    dsn::Texton centred = cropped;
    for (int c = 0; c < 3; c++) {
        double sum = 0;
        for (size_t i = 0; i < points; i++) sum += centred.values[size_t(c) * points + i];
        for (size_t i = 0; i < points; i++) centred.values[size_t(c) * points + i] -= sum / double(points);
    }
    CHECK(dsn::relative_model_error(model.spectrum, centred) ==
          doctest::Approx(dsn::relative_model_error_without_zero_frequency(model.spectrum, centred))
              .epsilon(1e-6));
}

TEST_CASE("excess_kurtosis is sum t^4 / (lambda (sum t^2)^2), lambda = impacts / |S|") {
    // One non-zero value: |S| / impacts. A constant texton: 1 / impacts.
    CHECK(dsn::excess_kurtosis(texton_of(2, 1, {0.3}), 30)[0] == doctest::Approx(25.0 / 30));
    dsn::Texton constant = texton_of(2, 1, {});
    for (double &value : constant.values) value = -0.1;
    CHECK(dsn::excess_kurtosis(constant, 30)[0] == doctest::Approx(1.0 / 30));
    CHECK(dsn::excess_kurtosis(constant, 10)[0] == doctest::Approx(1.0 / 10));
    CHECK(dsn::excess_kurtosis(texton_of(2, 3, {}), 30) == std::vector<double>{0, 0, 0});
    CHECK_THROWS_AS(dsn::excess_kurtosis(constant, 0), std::invalid_argument);
}

TEST_CASE("symmetric_eigen reconstructs the matrix with orthonormal eigenvectors") {
    const dsn::Matrix3 matrix = {4, 1, -2, 1, 3, 0.5, -2, 0.5, 5};
    std::array<double, 3> values;
    dsn::Matrix3 vectors;
    dsn::symmetric_eigen(matrix, values, vectors);
    dsn::Matrix3 rebuilt{}, gram{};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++) {
                rebuilt[size_t(i * 3 + j)] +=
                    vectors[size_t(i * 3 + k)] * values[size_t(k)] * vectors[size_t(j * 3 + k)];
                gram[size_t(i * 3 + j)] += vectors[size_t(k * 3 + i)] * vectors[size_t(k * 3 + j)];
            }
    for (size_t i = 0; i < 9; i++) {
        CHECK(rebuilt[i] == doctest::Approx(matrix[i]).epsilon(1e-12));
        CHECK(gram[i] == doctest::Approx(i % 4 == 0 ? 1.0 : 0.0).epsilon(1e-12));
    }
}

TEST_CASE(
    "color_transform: K A K^T = B, the gain sqrt(b / a) for grey, bounded and finite for a singular A") {
    const dsn::Matrix3 a = {2e-4, 5e-5, 1e-5, 5e-5, 1e-4, 2e-5, 1e-5, 2e-5, 3e-4};
    const dsn::Matrix3 b = {3e-4, 1e-4, 0, 1e-4, 2e-4, 4e-5, 0, 4e-5, 4e-4};
    CHECK(relative_difference(transform_covariance(dsn::color_transform(a, b, 3), a), b) < 1e-12);
    const dsn::Matrix3 grey = dsn::color_transform(a, b, 1);
    CHECK(grey[0] == doctest::Approx(std::sqrt(b[0] / a[0])).epsilon(1e-15));
    for (size_t i = 1; i < 9; i++) CHECK(grey[i] == 0);
    CHECK(dsn::color_transform({}, b, 1) == dsn::Matrix3{1, 0, 0, 0, 0, 0, 0, 0, 0});
    CHECK(dsn::color_transform({}, b, 3) == dsn::Matrix3{1, 0, 0, 0, 1, 0, 0, 0, 1});
    // A grey texton in an RGB asset: A has rank 1. K stays finite and within the Q8.24 range.
    const dsn::Matrix3 rank_one = {1e-4, 1e-4, 1e-4, 1e-4, 1e-4, 1e-4, 1e-4, 1e-4, 1e-4};
    for (double entry : dsn::color_transform(rank_one, b, 3)) {
        CHECK(std::isfinite(entry));
        CHECK(std::fabs(entry) <= dsn::kColorTransformLimit);
    }
}

namespace {

// The SOT of an exemplar (r = 15, 100 iterations), then K from its covariance A to the exemplar's B: the
// covariance of K t, measured from its values, is within 1% of B.
void check_colour_transform(const std::string &name, const dsn::Image &exemplar) {
    CAPTURE(name);
    const dsn::GaussianModel model = dsn::gaussian_model(exemplar, true);
    dsn::SotOptions options;
    options.iterations = 100;
    const dsn::SotResult sot =
        dsn::sot_alternating_projections(model.spectrum, dsn::support_mask(15, DSN_SHAPE_RECTANGLE), options);
    const dsn::Matrix3 a = dsn::texton_covariance(sot.texton, DSN_INTERPOLATION_LATTICE);
    const dsn::Matrix3 b = dsn::model_covariance(model);
    const dsn::Matrix3 k = dsn::color_transform(a, b, 3);
    // The transformed texton K t, measured from its values (not from A).
    dsn::Texton transformed = sot.texton;
    const size_t plane = sot.texton.support.mask.size();
    for (size_t i = 0; i < plane; i++)
        for (size_t row = 0; row < 3; row++) {
            double sum = 0;
            for (size_t column = 0; column < 3; column++)
                sum += k[row * 3 + column] * sot.texton.values[column * plane + i];
            transformed.values[row * plane + i] = sum;
        }
    const double before = relative_difference(a, b);
    const double after =
        relative_difference(dsn::texton_covariance(transformed, DSN_INTERPOLATION_LATTICE), b);
    MESSAGE(name << ": colour covariance error: " << before << " before K, " << after << " after");
    CHECK(after < 0.01);
}

} // namespace

TEST_CASE("the colour covariance of the transformed SOT matches the exemplar's within 1%") {
    check_colour_transform("known compact spot", random_phase_exemplar(64, 64, 3, 31));
    check_colour_transform("spread-out spot", random_phase_texture(random_spot(72, 64, 3, 14, 33), 34));
}

TEST_CASE("on real textures the colour covariance of the transformed SOT matches the exemplar's within 1%" *
          doctest::skip(!textures_available())) {
    for (const char *name : {"animal_leather", "wood_bark", "paper_crinklepaper"}) {
        std::vector<std::string> warnings;
        check_colour_transform(name, dsn::load_exemplar(textures_folder() + "/" + name + ".png", &warnings));
    }
}

TEST_CASE("texton_covariance for bilinear weights the lags by the sampled cubic B-spline") {
    dsn::Texton texton = texton_of(1, 1, {});
    texton.values[4] = 1; // a single impulse at the centre: lag 0 only, weight (2/3)^2
    CHECK(dsn::texton_covariance(texton, DSN_INTERPOLATION_BILINEAR)[0] == doctest::Approx(4.0 / 9));
    texton.values[5] = 1; // and its right neighbour: 2 (2/3)^2 + 2 (1/6)(2/3)
    CHECK(dsn::texton_covariance(texton, DSN_INTERPOLATION_BILINEAR)[0] ==
          doctest::Approx(8.0 / 9 + 2.0 / 9));
    CHECK(dsn::texton_covariance(texton, DSN_INTERPOLATION_LATTICE)[0] == doctest::Approx(2.0));
}

TEST_CASE(
    "quantize: per-channel scale from max |t|, error at most half a step, raw scale = round(scale 2^40)") {
    dsn::Texton texton = texton_of(2, 3, {});
    for (size_t i = 0; i < texton.values.size(); i++)
        texton.values[i] = std::sin(double(i) * 1.7) * (i < 25 ? 0.01 : 0.003);
    for (size_t i = 25; i < 50; i++) texton.values[i] = 0; // an all-zero channel still gets a valid scale
    for (int bits : {8, 16}) {
        const dsn::QuantizedTexton quantized = dsn::quantize(texton, bits);
        const int32_t limit = bits == 8 ? 127 : 32767;
        const dsn::Texton back = dsn::dequantize(quantized, texton.support, 3);
        for (size_t c = 0; c < 3; c++) {
            double largest = 0;
            int32_t largest_q = 0;
            for (size_t i = 0; i < 25; i++) {
                largest = std::max(largest, std::fabs(texton.values[c * 25 + i]));
                largest_q = std::max(largest_q, std::abs(quantized.values[i * 3 + c]));
            }
            CHECK(quantized.scale_raw[c] >= 1u);
            if (largest == 0) continue;
            CHECK(quantized.scale_raw[c] == uint32_t(std::round(largest / limit * 1099511627776.0)));
            CHECK(largest_q == limit);
            const double step = quantized.scale_raw[c] / 1099511627776.0;
            for (size_t i = 0; i < 25; i++)
                CHECK(std::fabs(back.values[c * 25 + i] - texton.values[c * 25 + i]) <=
                      step / 2 * (1 + 1e-9));
        }
    }
    CHECK_THROWS_AS(dsn::quantize(texton, 12), std::invalid_argument);
}
