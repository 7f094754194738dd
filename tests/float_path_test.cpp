// float_path_test.cpp - the float path of dsn.h (dsn_noise_load, dsn_sample, dsn_noise_mean_float): the
// shortest program works on lattice- and bilinear-baked assets, gives the long form's bits exactly, refuses
// null and damaged input with a zeroed output, and its mean is what the samples average to.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "dsn/dsn.h"
#include "fixtures/noise_theory.h"
#include "fixtures/test_assets.h"

using dsn_test::synthetic_fields;

namespace {

std::vector<unsigned char> asset_bytes(uint32_t channels, uint32_t interpolation, uint64_t seed) {
    dsn::AssetFields fields = synthetic_fields(channels, 9, 8, DSN_SHAPE_DISK, seed);
    fields.interpolation = interpolation;
    fields.mean[0] = int32_t(0.4321 * DSN_Q24_ONE); // not a round number: its float is a real rounding
    return dsn::encode_asset(fields);
}

// The long form of dsn_noise_load: load, defaults, seed, and the flag the float path sets for a lattice
// asset.
struct LongForm {
    dsn_asset asset{};
    dsn_noise noise{};
    int init(const std::vector<unsigned char> &bytes, uint32_t seed, bool allow_lattice) {
        int err = dsn_asset_load(&asset, bytes.data(), bytes.size());
        if (err != DSN_OK) return err;
        dsn_config config;
        dsn_config_defaults(&config);
        config.seed = seed;
        if (allow_lattice) config.flags = DSN_FLAG_ALLOW_LATTICE_CONTINUOUS;
        return dsn_noise_init(&noise, &asset, &config);
    }
};

// Coordinates of every kind: integers, fractions, negatives, subnormals, huge values, NaN and infinities.
std::vector<float> test_coordinates() {
    std::vector<float> values = {0.0f,
                                 -0.0f,
                                 0.5f,
                                 10.25f,
                                 -3.5f,
                                 1e-3f,
                                 -1e-3f,
                                 1e-40f,
                                 -1e-40f,
                                 123456.78f,
                                 -98765.4f,
                                 4294967296.5f,
                                 1e30f,
                                 -1e30f,
                                 std::numeric_limits<float>::max(),
                                 std::numeric_limits<float>::quiet_NaN(),
                                 std::numeric_limits<float>::infinity(),
                                 -std::numeric_limits<float>::infinity()};
    dsn_test::TestRandom random(77);
    for (int i = 0; i < 40; i++) values.push_back(float(random.range(-200000, 200000)) / 64.0f);
    return values;
}

} // namespace

TEST_CASE("the shortest program: load with a seed, then sample, on lattice- and bilinear-baked assets") {
    for (uint32_t interpolation : {DSN_INTERPOLATION_LATTICE, DSN_INTERPOLATION_BILINEAR})
        for (uint32_t channels : {1u, 3u}) {
            CAPTURE(interpolation);
            CAPTURE(channels);
            const std::vector<unsigned char> bytes = asset_bytes(channels, interpolation, 5);

            dsn_noise noise;
            float rgb[DSN_MAX_CHANNELS];
            REQUIRE(dsn_noise_load(&noise, bytes.data(), bytes.size(), 1234) == DSN_OK);
            REQUIRE(dsn_sample(&noise, 10.25f, -3.5f, rgb) == DSN_OK);

            CHECK(dsn_noise_channels(&noise) == channels);
            CHECK(dsn_continuous_check(&noise) == DSN_OK);
            // Not a constant: nearby points differ, and the values are finite.
            float other[DSN_MAX_CHANNELS];
            REQUIRE(dsn_sample(&noise, 13.75f, -1.0f, other) == DSN_OK);
            CHECK(std::memcmp(rgb, other, channels * sizeof(float)) != 0);
            for (uint32_t c = 0; c < channels; c++) CHECK(std::isfinite(rgb[c]));
        }
}

TEST_CASE("dsn_noise_load and dsn_sample give the long form's bits exactly") {
    for (uint32_t interpolation : {DSN_INTERPOLATION_LATTICE, DSN_INTERPOLATION_BILINEAR})
        for (uint32_t channels : {1u, 3u}) {
            CAPTURE(interpolation);
            CAPTURE(channels);
            const std::vector<unsigned char> bytes = asset_bytes(channels, interpolation, 6);
            const uint32_t seed = 0xC0FFEEu;
            dsn_noise noise;
            REQUIRE(dsn_noise_load(&noise, bytes.data(), bytes.size(), seed) == DSN_OK);
            LongForm full;
            REQUIRE(full.init(bytes, seed, interpolation == DSN_INTERPOLATION_LATTICE) == DSN_OK);
            // Without the flag: the lattice mode is the same noise (the flag only opens the continuous mode).
            LongForm plain;
            REQUIRE(plain.init(bytes, seed, false) == DSN_OK);

            const std::vector<float> coordinates = test_coordinates();
            for (size_t i = 0; i < coordinates.size(); i++) {
                const float x = coordinates[i], y = coordinates[(i * 7 + 3) % coordinates.size()];
                CAPTURE(x);
                CAPTURE(y);
                CHECK(dsn_coordinate_from_float(x) == dsn_coordinate_from_double(double(x)));
                float short_form[DSN_MAX_CHANNELS] = {}, long_form[DSN_MAX_CHANNELS] = {};
                REQUIRE(dsn_sample(&noise, x, y, short_form) == DSN_OK);
                REQUIRE(dsn_continuous_point_float(&full.noise, double(x), double(y), long_form) == DSN_OK);
                CHECK(std::memcmp(short_form, long_form, sizeof short_form) == 0);
                // And the fixed-point form, converted.
                int32_t fixed[DSN_MAX_CHANNELS] = {};
                REQUIRE(dsn_continuous_point_fixed(&full.noise, dsn_coordinate_from_float(x),
                                                   dsn_coordinate_from_float(y), fixed) == DSN_OK);
                for (uint32_t c = 0; c < channels; c++) {
                    const float converted = dsn_fixed_to_float(fixed[c]);
                    CHECK(std::memcmp(&short_form[c], &converted, sizeof(float)) == 0);
                }
                // The lattice functions on the loaded noise equal those of a noise without the flag.
                const int32_t lx = int32_t(i * 1000003u), ly = int32_t(i * 7919u) - 5000;
                int32_t loaded_point[DSN_MAX_CHANNELS] = {}, plain_point[DSN_MAX_CHANNELS] = {};
                dsn_lattice_point_fixed(&noise, lx, ly, loaded_point);
                dsn_lattice_point_fixed(&plain.noise, lx, ly, plain_point);
                CHECK(std::memcmp(loaded_point, plain_point, sizeof loaded_point) == 0);
            }
        }
}

TEST_CASE("the float path refuses null and damaged input, with the output zeroed") {
    const std::vector<unsigned char> bytes = asset_bytes(3, DSN_INTERPOLATION_LATTICE, 7);
    dsn_noise noise;
    float out[DSN_MAX_CHANNELS] = {7, 7, 7};

    CHECK(dsn_noise_load(nullptr, bytes.data(), bytes.size(), 1) == DSN_ERR_NULL);
    CHECK(dsn_noise_load(&noise, nullptr, bytes.size(), 1) == DSN_ERR_NULL);
    CHECK(dsn_noise_channels(&noise) == 0);

    // Damaged: a flipped texton byte (the CRC catches it), a cut file, a text-mode transfer.
    std::vector<unsigned char> damaged = bytes;
    damaged[DSN_FORMAT_HEADER_SIZE + 10] ^= 0x40u;
    // A successful load first, so that the failure must clear what was there.
    REQUIRE(dsn_noise_load(&noise, bytes.data(), bytes.size(), 1) == DSN_OK);
    CHECK(dsn_noise_load(&noise, damaged.data(), damaged.size(), 1) == DSN_ERR_CRC);
    CHECK(dsn_noise_channels(&noise) == 0);
    CHECK(dsn_sample(&noise, 1.5f, 2.5f, out) == DSN_ERR_NULL);
    CHECK(out[0] == 0.0f);
    out[0] = 7;
    CHECK(dsn_noise_mean_float(&noise, out) == DSN_ERR_NULL);
    CHECK(out[0] == 0.0f);
    CHECK(dsn_noise_load(&noise, bytes.data(), bytes.size() - 5, 1) == DSN_ERR_TRUNCATED);
    CHECK(dsn_noise_load(&noise, bytes.data(), 3, 1) == DSN_ERR_TRUNCATED);
    damaged = bytes;
    damaged[4] = '\n';
    CHECK(dsn_noise_load(&noise, damaged.data(), damaged.size(), 1) == DSN_ERR_TEXT_MODE);
    damaged[0] = 'P';
    CHECK(dsn_noise_load(&noise, damaged.data(), damaged.size(), 1) == DSN_ERR_BAD_MAGIC);
    CHECK(dsn_noise_channels(&noise) == 0);

    // Null arguments of the other two.
    out[0] = 7;
    CHECK(dsn_sample(nullptr, 0.0f, 0.0f, out) == DSN_ERR_NULL);
    CHECK(out[0] == 0.0f);
    out[0] = 7;
    CHECK(dsn_noise_mean_float(nullptr, out) == DSN_ERR_NULL);
    CHECK(out[0] == 0.0f);
    REQUIRE(dsn_noise_load(&noise, bytes.data(), bytes.size(), 1) == DSN_OK);
    CHECK(dsn_sample(&noise, 0.0f, 0.0f, nullptr) == DSN_ERR_NULL);
    CHECK(dsn_noise_mean_float(&noise, nullptr) == DSN_ERR_NULL);

    // A lattice-baked asset configured by the long form without the flag: dsn_sample says why, every
    // channel zeroed.
    LongForm strict;
    REQUIRE(strict.init(bytes, 1, false) == DSN_OK);
    float rgb[DSN_MAX_CHANNELS] = {7, 7, 7};
    CHECK(dsn_sample(&strict.noise, 0.5f, 0.5f, rgb) == DSN_ERR_CONTINUOUS_MISMATCH);
    CHECK(rgb[0] == 0.0f);
    CHECK(rgb[1] == 0.0f);
    CHECK(rgb[2] == 0.0f);
    // Its mean is still defined: the mean does not depend on the mode.
    CHECK(dsn_noise_mean_float(&strict.noise, rgb) == DSN_OK);
}

// Sites 32 texels apart (beyond the 9 x 9 texton's reach, 2 r + 2 = 10) at random fractional positions are
// independent samples of the noise; their average is within a few standard errors (sd / sqrt(n), estimated
// from the samples) of the mean, plus the output's own resolution (the offset is rounded in Q16.16).
TEST_CASE("dsn_noise_mean_float is the asset's mean, and what many samples average to") {
    for (uint32_t interpolation : {DSN_INTERPOLATION_LATTICE, DSN_INTERPOLATION_BILINEAR})
        for (uint32_t channels : {1u, 3u}) {
            CAPTURE(interpolation);
            CAPTURE(channels);
            const std::vector<unsigned char> bytes = asset_bytes(channels, interpolation, 8);
            dsn_noise noise;
            REQUIRE(dsn_noise_load(&noise, bytes.data(), bytes.size(), 99) == DSN_OK);
            float mean[DSN_MAX_CHANNELS] = {};
            REQUIRE(dsn_noise_mean_float(&noise, mean) == DSN_OK);
            dsn_asset asset;
            REQUIRE(dsn_asset_load(&asset, bytes.data(), bytes.size()) == DSN_OK);
            for (uint32_t c = 0; c < channels; c++)
                CHECK(mean[c] == float(double(asset.mean[c]) / double(DSN_Q24_ONE)));

            const int samples = 20000, spacing = 32;
            std::vector<double> values[DSN_MAX_CHANNELS], lattice_values[DSN_MAX_CHANNELS];
            dsn_test::TestRandom random(3);
            for (int i = 0; i < samples; i++) {
                const int site_x = (i % 200) * spacing, site_y = (i / 200) * spacing - 1600;
                const float x = float(site_x) + float(random.next() % 4096u) / 4096.0f;
                const float y = float(site_y) + float(random.next() % 4096u) / 4096.0f;
                float value[DSN_MAX_CHANNELS];
                REQUIRE(dsn_sample(&noise, x, y, value) == DSN_OK);
                float lattice[DSN_MAX_CHANNELS];
                dsn_lattice_point_float(&noise, site_x, site_y, lattice);
                for (uint32_t c = 0; c < channels; c++) {
                    values[c].push_back(value[c]);
                    lattice_values[c].push_back(lattice[c]);
                }
            }
            for (uint32_t c = 0; c < channels; c++) {
                CAPTURE(c);
                for (const std::vector<double> *set : {&values[c], &lattice_values[c]}) {
                    double average, standard_error;
                    dsn_test::mean_with_error(*set, &average, &standard_error);
                    CAPTURE(average);
                    CAPTURE(standard_error);
                    CHECK(standard_error > 0.0);
                    CHECK(std::fabs(average - double(mean[c])) <= 4 * standard_error + 1.0 / 65536);
                }
            }
        }
}
