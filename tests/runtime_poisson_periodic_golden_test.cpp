// runtime_poisson_periodic_golden_test.cpp - the integer Poisson table against the pmf (double), the
// sampled per-cell counts against it (chi-square), exact periodicity (including a period of 1 and
// periods that do not divide 2^32), defined results at the int32 extremes, float/u8 conversions, and a
// golden FNV-1a-64 hash of a fixed asset's output.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <utility>
#include <vector>

#include "fixtures/fnv1a.h"
#include "fixtures/test_assets.h"
#include "runtime/core/poisson_count.h"

namespace {

using dsn_test::LoadedNoise;

// P(N = n) for N ~ Poisson(mean), by logarithms (stable for any n).
double poisson_pmf(double mean, int n) { return std::exp(-mean + n * std::log(mean) - std::lgamma(n + 1.0)); }

double cell_mean(const dsn_noise &noise) {
    double lambda = dsn_state(&noise)->impacts_q16 / 65536.0 / dsn_state(&noise)->asset.support_size;
    return lambda * std::ldexp(1.0, int(2 * dsn_state(&noise)->cell_shift));
}

} // namespace

TEST_CASE("the Poisson table is the rounded CDF of the per-draw mean, to the 2^-32 resolution") {
    const double impacts[] = {0.0625, 1, 5, 30, 100, 1024};
    for (uint32_t side : {1u, 7u, 31u, 101u})
        for (double n_impacts : impacts) {
            auto fields = dsn_test::synthetic_fields(1, side, 8, DSN_SHAPE_RECTANGLE, 1);
            LoadedNoise loaded(fields, dsn_test::make_config(0, n_impacts));
            const dsn_noise &noise = loaded.noise;
            double mean = cell_mean(noise) / dsn_state(&noise)->poisson_parts;
            CAPTURE(side);
            CAPTURE(n_impacts);
            CAPTURE(mean);
            CHECK(mean <= 16.0 + 1e-9);
            REQUIRE(dsn_state(&noise)->poisson_size >= 1);
            REQUIRE(dsn_state(&noise)->poisson_size <= 96);
            double cdf = 0;
            for (uint32_t n = 0; n < dsn_state(&noise)->poisson_size; n++) {
                cdf += poisson_pmf(mean, int(n));
                CHECK(std::abs(double(dsn_state(&noise)->poisson_cdf[n]) - std::ldexp(cdf, 32)) <= 1.0);
            }
            // The table ends where the CDF rounds to 2^32: the mass beyond poisson_size, which is drawn as
            // poisson_size, is at most 2^-33.
            CHECK(std::ldexp(1.0 - cdf, 32) > 0.5 - 1e-3);
            CHECK(std::ldexp(1.0 - cdf - poisson_pmf(mean, int(dsn_state(&noise)->poisson_size)), 32) <
                  0.5 + 1e-3);
            // The guide never skips the answer.
            for (uint32_t bucket = 0; bucket < 64; bucket++) {
                uint32_t guide = dsn_state(&noise)->poisson_guide[bucket];
                CHECK((guide == 0 || dsn_state(&noise)->poisson_cdf[guide - 1] <= (bucket << 26)));
            }
        }
}

TEST_CASE("per-cell counts follow the Poisson law (chi-square over 10^6 cells)") {
    // The last case (1 x 1 texton, 1024 impacts: mean 1024 per cell) sums 64 draws per cell.
    const std::pair<uint32_t, double> cases[] = {{31, 30.0}, {31, 5.0}, {31, 700.0}, {1, 1024.0}};
    for (const auto &test_case : cases) {
        const double impacts = test_case.second;
        auto fields = dsn_test::synthetic_fields(3, test_case.first, 8, DSN_SHAPE_RECTANGLE, 2);
        LoadedNoise loaded(fields, dsn_test::make_config(9, impacts));
        const dsn_noise &noise = loaded.noise;
        const double mean = cell_mean(noise);
        const int cells = 1000;
        std::vector<double> observed(2000);
        for (uint32_t y = 0; y < cells; y++)
            for (uint32_t x = 0; x < cells; x++) {
                uint32_t count = dsn_cell_impulse_count(
                    dsn_state(&noise), dsn_cell_key(dsn_state(&noise), x * 7919u, y * 104729u - 5000u));
                observed[std::min<uint32_t>(count, 1999)] += 1;
            }
        // Bins with expected counts >= 20 (tails merged), chi-square against the exact pmf. Threshold:
        // df + 6 sqrt(2 df), six standard deviations of the chi-square law.
        const double total = double(cells) * cells;
        double chi_square = 0, bin_observed = 0, bin_expected = 0, below = 0;
        int degrees = -1, n = 0;
        while (below < total * (1 - 1e-12) && n < 1999) {
            double expected = total * poisson_pmf(mean, n);
            below += expected;
            bin_observed += observed[size_t(n)], bin_expected += expected;
            n++;
            if (bin_expected >= 20 && total - below >= 20) {
                chi_square += (bin_observed - bin_expected) * (bin_observed - bin_expected) / bin_expected;
                bin_observed = bin_expected = 0;
                degrees++;
            }
        }
        double tail_observed = bin_observed, tail_expected = bin_expected + (total - below);
        for (size_t i = size_t(n); i < observed.size(); i++) tail_observed += observed[i];
        chi_square += (tail_observed - tail_expected) * (tail_observed - tail_expected) / tail_expected;
        degrees++;
        CAPTURE(impacts);
        CAPTURE(mean);
        CAPTURE(degrees);
        CAPTURE(chi_square);
        CHECK(degrees >= 5);
        CHECK(chi_square < degrees + 6 * std::sqrt(2.0 * degrees));
    }
}

TEST_CASE("periodic mode: value(x + Px, y) == value(x, y) == value(x, y + Py), any period") {
    auto fields = dsn_test::synthetic_fields(3, 31, 8, DSN_SHAPE_DISK, 4);
    const uint32_t periods[][2] = {{1, 1}, {1, 0}, {3, 5}, {17, 256}, {31, 32}, {1000, 999}, {65536, 3}};
    dsn_test::TestRandom random(5);
    for (const auto &period : periods) {
        LoadedNoise loaded(fields, dsn_test::make_config(77, 30, period[0], period[1]));
        CAPTURE(period[0]);
        CAPTURE(period[1]);
        int differences = 0;
        for (int trial = 0; trial < 300; trial++) {
            int32_t x = int32_t(random.next() % 2000000000u) - 1000000000,
                    y = int32_t(random.next() % 2000000u) - 1000000;
            int32_t here[3], there[3];
            dsn_lattice_point_fixed(&loaded.noise, x, y, here);
            if (period[0] != 0) {
                dsn_lattice_point_fixed(&loaded.noise, x + int32_t(period[0]) * int32_t(1 + trial % 3), y,
                                        there);
                differences += std::memcmp(here, there, sizeof here) != 0;
            }
            if (period[1] != 0) {
                dsn_lattice_point_fixed(&loaded.noise, x, y - int32_t(period[1]), there);
                differences += std::memcmp(here, there, sizeof here) != 0;
            }
        }
        CHECK(differences == 0);
    }
    // A period of 1 along x: every row is constant, and rows still vary. All impulses then lie in one
    // column: at 200 impacts per pixel the 64 rows are reached by ~19 of them on average, so rows that
    // all equal the mean (no impulse at all) would have probability ~e^-19.
    LoadedNoise rows(fields, dsn_test::make_config(3, 200, 1, 0));
    const int side = 64;
    std::vector<int32_t> tile(size_t(side * side * 3));
    REQUIRE(dsn_lattice_tile_fixed(&rows.noise, INT32_MAX - 20, -4, side, side, tile.data(), nullptr, 0) ==
            DSN_OK);
    int constant_rows = 0, rows_unlike_the_first = 0;
    for (int j = 0; j < side; j++) {
        const int32_t *row = &tile[size_t(j * side * 3)];
        bool constant = true;
        for (int i = 0; i < side * 3; i++) constant &= row[i] == row[i % 3];
        constant_rows += constant;
        rows_unlike_the_first += std::memcmp(row, tile.data(), 3 * sizeof(int32_t)) != 0;
    }
    CHECK(constant_rows == side);
    CHECK(rows_unlike_the_first > 0);
}

TEST_CASE("defined output at the int32 extremes, and the float / u8 conversions") {
    auto fields = dsn_test::synthetic_fields(3, 31, 16, DSN_SHAPE_RECTANGLE, 6);
    LoadedNoise loaded(fields, dsn_test::make_config(1));
    const int32_t corners[] = {INT32_MIN, INT32_MIN + 1, -1, 0, INT32_MAX - 1, INT32_MAX};
    for (int32_t x : corners)
        for (int32_t y : corners) {
            int32_t fixed[3];
            float values[3];
            uint8_t bytes[3];
            dsn_lattice_point_fixed(&loaded.noise, x, y, fixed);
            dsn_lattice_point_float(&loaded.noise, x, y, values);
            dsn_lattice_point_u8(&loaded.noise, x, y, bytes);
            for (int c = 0; c < 3; c++) {
                CHECK(values[c] == float(fixed[c]) / 65536.0f);
                CHECK(bytes[c] == dsn_fixed_to_u8(fixed[c]));
            }
        }
    CHECK(dsn_fixed_to_u8(-5) == 0);
    CHECK(dsn_fixed_to_u8(0) == 0);
    CHECK(dsn_fixed_to_u8(128) == 0);     // 128 * 255 / 65536 = 0.498
    CHECK(dsn_fixed_to_u8(129) == 1);     // 0.502
    CHECK(dsn_fixed_to_u8(32768) == 128); // 127.5 rounds half up
    CHECK(dsn_fixed_to_u8(65535) == 255);
    CHECK(dsn_fixed_to_u8(INT32_MAX) == 255);
    CHECK(dsn_fixed_to_float(INT32_MIN) == -32768.0f);
    CHECK(dsn_fixed_to_float(1) == 1.0f / 65536.0f);
    // Tiles in float and u8 agree with the per-point conversions.
    const uint32_t width = 37, height = 5;
    std::vector<unsigned char> scratch(dsn_lattice_tile_scratch_size(&loaded.noise, width, height) + 1);
    std::vector<float> tile_float(width * height * 3);
    std::vector<uint8_t> tile_u8(width * height * 3);
    REQUIRE(dsn_lattice_tile_float(&loaded.noise, INT32_MAX - 10, INT32_MIN, width, height, tile_float.data(),
                                   scratch.data() + 1, scratch.size() - 1) == DSN_OK);
    REQUIRE(dsn_lattice_tile_u8(&loaded.noise, INT32_MAX - 10, INT32_MIN, width, height, tile_u8.data(),
                                scratch.data(), scratch.size()) == DSN_OK);
    int differences = 0;
    for (uint32_t j = 0; j < height; j++)
        for (uint32_t i = 0; i < width; i++) {
            float values[3];
            uint8_t bytes[3];
            dsn_lattice_point_float(&loaded.noise, int32_t(uint32_t(INT32_MAX - 10) + i),
                                    int32_t(uint32_t(INT32_MIN) + j), values);
            dsn_lattice_point_u8(&loaded.noise, int32_t(uint32_t(INT32_MAX - 10) + i),
                                 int32_t(uint32_t(INT32_MIN) + j), bytes);
            for (uint32_t c = 0; c < 3; c++) {
                differences += tile_float[(j * width + i) * 3 + c] != values[c];
                differences += tile_u8[(j * width + i) * 3 + c] != bytes[c];
            }
        }
    CHECK(differences == 0);
}

TEST_CASE("golden: a fixed asset and seed give a committed FNV-1a-64 of the output") {
    // Fixed integers only (no FFT, no libm in the asset): a 9 x 9 RGB texton from a closed formula.
    dsn::AssetFields fields;
    fields.channels = 3;
    fields.width = fields.height = 9;
    for (int row = 0; row < 9; row++)
        for (int column = 0; column < 9; column++)
            for (int c = 0; c < 3; c++)
                fields.texton.push_back(((row * 37 + column * 11 + c * 53) % 255) - 127);
    const uint32_t scales[3] = {1u << 30, 3u << 28, 5u << 27};
    const int32_t means[3] = {8388608, 6000000, 10000000};
    const int32_t transform[9] = {16777216, 1000000,  -500000, 2000000, 15000000,
                                  0,        -1000000, 3000000, 17000000};
    for (int c = 0; c < 3; c++) fields.scale[c] = scales[c], fields.mean[c] = means[c];
    for (int i = 0; i < 9; i++) fields.color_transform[i] = transform[i];
    LoadedNoise loaded(fields, dsn_test::make_config(20240601, 12.5, 0, 0));
    std::vector<int32_t> tile(64 * 48 * 3);
    REQUIRE(dsn_lattice_tile_fixed(&loaded.noise, -32, INT32_MAX - 23, 64, 48, tile.data(), nullptr, 0) ==
            DSN_OK);
    uint64_t hash = dsn_test::fnv1a64_int32(tile.data(), tile.size());
    LoadedNoise periodic(fields, dsn_test::make_config(7, 30, 48, 17));
    REQUIRE(dsn_lattice_tile_fixed(&periodic.noise, INT32_MIN, -5, 64, 48, tile.data(), nullptr, 0) ==
            DSN_OK);
    uint64_t periodic_hash = dsn_test::fnv1a64_int32(tile.data(), tile.size());
    CHECK(hash == 0x1C06CBF837B80642u);
    CHECK(periodic_hash == 0x53A5A0AC1FB490EDu);
}
