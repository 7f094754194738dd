// bake_contrast_test.cpp - every bake's noise has its exemplar's variance per channel: grey bakes too,
// whose colour transform is the gain sqrt(b / a) (the texton's support loses part of the exemplar's
// variance, 13% of the deviation on some photos, which colour bakes restore with K A K^T = B).
//
// The variances are exact, from the stored asset: the continuous read's is K^2 times the bilinear
// texton's integral sum_a sum_b t[a] t[b] B(b - a) (B the cubic B-spline), the lattice read's is K^2 times
// sum t_l^2 of the lattice texton (RGB: the diagonal of K A K^T); the exemplar's is sum t_u^2 of its
// Gaussian model. Only the 8-bit quantization and the Q8.24 transform separate them, far below 3%.
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "fixtures/bake_fixtures.h"
#include "fixtures/continuous_fixtures.h"
#include "offline/bake_internal.h"

namespace {

double transform_entry(const dsn::AssetFields &fields, uint32_t row, uint32_t column) {
    return fields.color_transform[row * 3 + column] / double(1 << 24);
}

// The output variance of channel c from textons t[k] (value units, side x side) and their cross
// covariances `covariance(k, l)`.
template <typename Covariance>
double output_variance(const dsn::AssetFields &fields, uint32_t c, Covariance covariance) {
    double variance = 0;
    for (uint32_t k = 0; k < fields.channels; k++)
        for (uint32_t l = 0; l < fields.channels; l++)
            variance += transform_entry(fields, c, k) * transform_entry(fields, c, l) * covariance(k, l);
    return variance;
}

// Largest |deviation ratio - 1| over the channels and both reads of a default bake of `exemplar`.
double largest_deviation_error(const dsn::Image &exemplar, uint32_t interpolation) {
    dsn::BakeOptions options;
    options.interpolation = interpolation;
    options.iterations = 300;
    const dsn::BakeResult result = dsn::bake(exemplar, options);
    const dsn::AssetFields &fields = result.fields;
    const dsn::Matrix3 model = dsn::model_covariance(result.model);
    const auto t = continuous_fixtures::texton_values(fields);
    const int side = int(fields.width);
    double error = 0;
    for (uint32_t c = 0; c < fields.channels; c++) {
        const double target = model[c * 3 + c];
        double lattice = 0, continuous = 0;
        if (interpolation == DSN_INTERPOLATION_BILINEAR) {
            continuous = output_variance(fields, c, [&](uint32_t k, uint32_t l) {
                return continuous_fixtures::bilinear_correlation(t[k], t[l], side, 0, 0);
            });
            dsn::AssetFields lattice_fields = fields;
            lattice_fields.texton = fields.lattice_texton;
            lattice_fields.width = fields.lattice_width;
            lattice_fields.height = fields.lattice_height;
            const auto tl = continuous_fixtures::texton_values(lattice_fields);
            lattice = output_variance(fields, c, [&](uint32_t k, uint32_t l) {
                double sum = 0;
                for (size_t i = 0; i < tl[k].size(); i++) sum += tl[k][i] * tl[l][i];
                return sum;
            });
            error = std::max(error, std::fabs(std::sqrt(continuous / target) - 1));
        } else {
            lattice = output_variance(fields, c, [&](uint32_t k, uint32_t l) {
                double sum = 0;
                for (size_t i = 0; i < t[k].size(); i++) sum += t[k][i] * t[l][i];
                return sum;
            });
        }
        error = std::max(error, std::fabs(std::sqrt(lattice / target) - 1));
    }
    return error;
}

// The exemplar's first channel alone: a grey exemplar.
dsn::Image first_channel(const dsn::Image &image) {
    dsn::Image grey = image;
    grey.channels = 1;
    grey.values.resize(size_t(image.width) * size_t(image.height));
    return grey;
}

} // namespace

TEST_CASE("bake contrast: grey and colour bakes keep the exemplar's deviation within 3% (generated)") {
    // A broadband spot within the texton's reach, and a wider one (radius 28 against the texton's 15),
    // whose correlations the support cuts: there the texton's noise loses part of the variance.
    const dsn::Image broadband =
        bake_fixtures::random_phase_texture(bake_fixtures::random_spot(96, 96, 3, 12, 3), 5);
    const dsn::Image wide =
        bake_fixtures::random_phase_texture(bake_fixtures::random_spot(128, 128, 3, 28, 4), 6);
    for (const dsn::Image *image : {&broadband, &wide})
        for (uint32_t interpolation : {DSN_INTERPOLATION_BILINEAR, DSN_INTERPOLATION_LATTICE}) {
            CAPTURE(interpolation);
            const double colour = largest_deviation_error(*image, interpolation);
            const double grey = largest_deviation_error(first_channel(*image), interpolation);
            MESSAGE("deviation of the noise / the exemplar's, largest error: RGB " << colour << ", grey "
                                                                                   << grey);
            CHECK(colour <= 0.03);
            CHECK(grey <= 0.03);
        }
}

TEST_CASE("bake contrast: grey bakes of real photos keep the exemplar's deviation within 3%" *
          doctest::skip(!bake_fixtures::textures_available())) {
    for (const std::string &name : bake_fixtures::named_textures()) {
        CAPTURE(name);
        std::vector<std::string> warnings;
        const dsn::Image grey = first_channel(
            dsn::load_exemplar(bake_fixtures::textures_folder() + "/" + name + ".png", &warnings));
        const double error = largest_deviation_error(grey, DSN_INTERPOLATION_BILINEAR);
        MESSAGE(name << " (grey): deviation of the noise / the exemplar's within " << error);
        CHECK(error <= 0.03);
    }
}
