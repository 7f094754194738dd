// continuous_test.cpp - the continuous mode's exact behaviour: coordinate conversion from IEEE bits,
// the lattice-asset error, the bilinear sum against a brute-force reference over every nearby cell, the
// read's error against exact real bilinear interpolation (exhaustive over the weights), the
// steps between neighbouring pixels at 64x magnification against the derivative's bound, the per-point
// evaluator of every kernel against the default kernel's, grid tiles against per-point calls,
// and periodicity.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "fixtures/continuous_fixtures.h"
#include "runtime/core/bilinear_texton.h"
#include "runtime/core/impulse_position.h"
#include "runtime/core/poisson_count.h"
#include "runtime/kernels/kernels.h"

using namespace continuous_fixtures;

namespace {

const int64_t one = int64_t(1) << 32;

// Brute force: the point's value from every impulse of every cell within a generous box (or, periodic,
// of every cell of the period, with all the copies that can reach), with exact integer tent weights on
// the point truncated to 16 fraction bits and its offset from each impulse floored to 8 (the weights'
// bits), then the normalization in long double. Independent of the
// runtime's cell walk and offset arithmetic; shares only the impulse process (cell_hash.h,
// impulse_position.h).
std::vector<long double> reference_value(const dsn_noise *noise, int64_t x, int64_t y) {
    const uint32_t shift = dsn_state(noise)->cell_shift, channels = dsn_noise_channels(noise);
    const int64_t rx = dsn_state(noise)->radius[0], ry = dsn_state(noise)->radius[1];
    const uint32_t period[2] = {dsn_state(noise)->period[0], dsn_state(noise)->period[1]};
    // Points in Q16 (truncated), on the torus of 2^48, or reduced to [0, P) when periodic.
    int64_t point[2] = {x >> 16, y >> 16};
    for (int axis = 0; axis < 2; axis++) {
        if (period[axis]) {
            int64_t p16 = int64_t(period[axis]) << 16;
            int64_t signed_point =
                int64_t(int32_t(uint32_t(uint64_t(point[axis]) >> 16))) * 65536 + (point[axis] & 0xFFFF);
            point[axis] = ((signed_point % p16) + p16) % p16;
        }
    }
    std::vector<__int128> sums(channels, 0);
    auto cells_of = [&](int axis, int64_t radius, std::vector<uint32_t> &cells,
                        std::vector<int64_t> &shifts) {
        const int64_t c = int64_t(1) << shift;
        if (period[axis] == 0) {
            int64_t whole = point[axis] >> 16;
            for (int64_t lattice = whole - radius - 2 - c; lattice <= whole + radius + 2 + c; lattice += c) {
                cells.push_back(uint32_t(uint64_t(lattice)) >> shift);
                // Impulse positions are taken relative to the point's own wrap of the torus.
                shifts.push_back((lattice >> shift) - int64_t(uint32_t(uint64_t(lattice)) >> shift));
            }
        } else {
            for (uint32_t cell = 0; (uint64_t(cell) << shift) < period[axis]; cell++) {
                cells.push_back(cell);
                shifts.push_back(0);
            }
        }
    };
    std::vector<uint32_t> cells_x, cells_y;
    std::vector<int64_t> wraps_x, wraps_y;
    cells_of(0, rx, cells_x, wraps_x);
    cells_of(1, ry, cells_y, wraps_y);
    const int copies_x = period[0] ? int(rx + 2) / int(period[0]) + 2 : 0;
    const int copies_y = period[1] ? int(ry + 2) / int(period[1]) + 2 : 0;
    for (size_t j = 0; j < cells_y.size(); j++)
        for (size_t i = 0; i < cells_x.size(); i++) {
            uint32_t key = dsn_cell_key(dsn_state(noise), cells_x[i], cells_y[j]);
            uint32_t count = dsn_cell_impulse_count(dsn_state(noise), key);
            for (uint32_t k = 0; k < count; k++) {
                uint32_t hash = dsn_impulse_hash(dsn_state(noise), key, k);
                // Impulse position in Q16 (16 - shift fraction bits, scaled up).
                int64_t px = (int64_t(cells_x[i]) + wraps_x[i]) * (int64_t(1) << (16 + shift)) +
                             (int64_t(dsn_impulse_bits_x(hash)) << shift);
                int64_t py = (int64_t(cells_y[j]) + wraps_y[j]) * (int64_t(1) << (16 + shift)) +
                             (int64_t(dsn_impulse_bits_y(hash)) << shift);
                if (period[0] && (px >> 16) >= int64_t(period[0])) continue;
                if (period[1] && (py >> 16) >= int64_t(period[1])) continue;
                for (int my = -copies_y; my <= copies_y; my++)
                    for (int mx = -copies_x; mx <= copies_x; mx++) {
                        int64_t dx = point[0] - px - int64_t(mx) * (int64_t(period[0]) << 16);
                        int64_t dy = point[1] - py - int64_t(my) * (int64_t(period[1]) << 16);
                        if (period[0] == 0) dx = int64_t(uint64_t(dx) << 16) >> 16; // the 2^32 torus, in Q16
                        if (period[1] == 0) dy = int64_t(uint64_t(dy) << 16) >> 16;
                        dx -= dx & 0xFF, dy -= dy & 0xFF; // floored to 2^-8 texel
                        for (int64_t b = -ry; b <= ry; b++) {
                            int64_t wy = 65536 - std::llabs(dy - b * 65536);
                            if (wy <= 0) continue;
                            for (int64_t a = -rx; a <= rx; a++) {
                                int64_t wx = 65536 - std::llabs(dx - a * 65536);
                                if (wx <= 0) continue;
                                for (uint32_t c = 0; c < channels; c++)
                                    sums[c] += __int128(dsn_asset_texton_value(&dsn_state(noise)->asset,
                                                                               uint32_t(b + ry),
                                                                               uint32_t(a + rx), c)) *
                                               wx * wy;
                            }
                        }
                    }
            }
        }
    std::vector<long double> out(channels);
    for (uint32_t c = 0; c < channels; c++) {
        long double value = dsn_state(noise)->offset[c];
        for (uint32_t k = 0; k < channels; k++)
            value += (long double)dsn_state(noise)->gain[c * 3 + k] * (long double)sums[k] / 4294967296.0L;
        out[c] = value / std::ldexp(1.0L, int(dsn_state(noise)->gain_shift));
    }
    return out;
}

int64_t random_coordinate(std::mt19937_64 &random) {
    switch (random() % 4) {
    case 0:
        return int64_t(random()); // anywhere on the torus
    case 1:
        return int64_t(uint64_t(INT32_MAX - 40 + int64_t(random() % 80)) << 32) + int64_t(random() >> 32);
    case 2:
        return int64_t(uint64_t(random() % 200) << 32) - 100 * one + int64_t(random() >> 32);
    default:
        return (int64_t(random() % 100) - 50) * one; // lattice points
    }
}

} // namespace

TEST_CASE("continuous: float and double coordinates convert from their bits, rounding down, modulo 2^32") {
    CHECK(dsn_coordinate_from_double(0.0) == 0);
    CHECK(dsn_coordinate_from_double(-0.0) == 0);
    CHECK(dsn_coordinate_from_double(1.5) == one + one / 2);
    CHECK(dsn_coordinate_from_double(-0.25) == -one / 4);
    CHECK(dsn_coordinate_from_double(-3.0) == -3 * one);
    CHECK(dsn_coordinate_from_double(2147483647.0) == int64_t(2147483647) * one);
    CHECK(dsn_coordinate_from_double(2147483648.0) == INT64_MIN);               // wraps to -2^31
    CHECK(dsn_coordinate_from_double(4294967296.0 + 7.5) == 7 * one + one / 2); // modulo 2^32 texels
    CHECK(dsn_coordinate_from_double(1e300) == 0);                              // a multiple of 2^64
    CHECK(dsn_coordinate_from_double(std::ldexp(1.0, -33)) == 0);               // below one unit: down
    CHECK(dsn_coordinate_from_double(-std::ldexp(1.0, -33)) == -1);
    CHECK(dsn_coordinate_from_double(-std::numeric_limits<double>::denorm_min()) == -1);
    CHECK(dsn_coordinate_from_double(std::numeric_limits<double>::denorm_min()) == 0);
    CHECK(dsn_coordinate_from_double(std::nan("")) == 0);
    CHECK(dsn_coordinate_from_double(std::numeric_limits<double>::infinity()) == 0);
    CHECK(dsn_coordinate_from_double(-std::numeric_limits<double>::infinity()) == 0);
    CHECK(dsn_coordinate_from_float(std::numeric_limits<float>::quiet_NaN()) == 0);
    CHECK(dsn_coordinate_from_float(-1.75f) == -one - 3 * one / 4);

    // Against exact long double arithmetic (64-bit mantissa on x86, enough for these magnitudes), and
    // float against double on random bit patterns.
    std::mt19937_64 random(11);
    for (int i = 0; i < 200000; i++) {
        double value = std::ldexp(double(int64_t(random())) / 9.2233720368547758e18, int(random() % 40) - 8);
        long double scaled = std::floor((long double)value * 4294967296.0L);
        int64_t expected = int64_t(scaled); // |value| < 2^31 here
        REQUIRE(dsn_coordinate_from_double(value) == expected);
        uint32_t bits = uint32_t(random());
        float single;
        std::memcpy(&single, &bits, 4);
        if (std::isfinite(single))
            REQUIRE(dsn_coordinate_from_float(single) == dsn_coordinate_from_double(single));
    }
}

TEST_CASE("continuous: a lattice-baked asset is refused unless explicitly allowed") {
    dsn::AssetFields fields = random_texton_asset(3, 3, 8, 1);
    fields.interpolation = DSN_INTERPOLATION_LATTICE;
    auto refused = make_noise(fields, 1);
    int32_t out[3] = {5, 5, 5};
    float values[3];
    CHECK(dsn_continuous_check(&refused->noise) == DSN_ERR_CONTINUOUS_MISMATCH);
    CHECK(dsn_continuous_point_fixed(&refused->noise, 0, 0, out) == DSN_ERR_CONTINUOUS_MISMATCH);
    CHECK((out[0] == 0 && out[1] == 0 && out[2] == 0));
    CHECK(dsn_continuous_point_float(&refused->noise, 1.5, 2.5, values) == DSN_ERR_CONTINUOUS_MISMATCH);
    dsn_grid grid = {0, 0, one, 0, 0, one};
    int32_t tile[4 * 4 * 3]; // an erring tile zeroes all its pixels: the caller holds them all
    CHECK(dsn_continuous_tile_fixed(&refused->noise, &grid, 4, 4, tile, nullptr, 0) ==
          DSN_ERR_CONTINUOUS_MISMATCH);
    auto allowed = make_noise(fields, 1, 0, 0, 0, DSN_FLAG_ALLOW_LATTICE_CONTINUOUS);
    CHECK(dsn_continuous_point_fixed(&allowed->noise, one / 3, 5 * one, out) == DSN_OK);
    CHECK(dsn_continuous_check(nullptr) == DSN_ERR_NULL);
    CHECK(dsn_continuous_point_fixed(&allowed->noise, 0, 0, nullptr) == DSN_ERR_NULL);
    CHECK(dsn_continuous_tile_fixed(&allowed->noise, &grid, 0, 4, tile, nullptr, 0) == DSN_ERR_TILE_SIZE);
    CHECK(dsn_continuous_tile_fixed(&allowed->noise, nullptr, 1, 1, tile, nullptr, 0) == DSN_ERR_NULL);
    // Non-finite float coordinates are the point 0.
    float at_nan[3], at_zero[3];
    dsn_continuous_point_float(&allowed->noise, std::nan(""), -std::numeric_limits<double>::infinity(),
                               at_nan);
    dsn_continuous_point_float(&allowed->noise, 0.0, 0.0, at_zero);
    CHECK(std::memcmp(at_nan, at_zero, sizeof at_nan) == 0);
}

TEST_CASE("continuous: the value is the bilinear sum over every impulse (brute-force reference)") {
    struct Case {
        uint32_t channels, radius, bits, impacts, period_x, period_y;
    };
    const Case cases[] = {{3, 3, 8, 30, 0, 0},   {1, 6, 16, 5, 0, 0}, {3, 2, 16, 200, 0, 0},
                          {1, 4, 8, 30, 37, 64}, {3, 3, 8, 10, 5, 0}, {1, 0, 16, 30, 0, 0}};
    std::mt19937_64 random(5);
    for (const Case &c : cases) {
        auto noise = make_noise(random_texton_asset(c.channels, c.radius, c.bits, c.radius + c.bits),
                                uint32_t(random()), c.impacts << 16, c.period_x, c.period_y);
        CAPTURE(c.channels);
        CAPTURE(c.radius);
        CAPTURE(c.period_x);
        CAPTURE(dsn_state(&noise->noise)->cell_shift);
        for (int i = 0; i < 60; i++) {
            int64_t x = random_coordinate(random), y = random_coordinate(random);
            int32_t out[3];
            REQUIRE(dsn_continuous_point_fixed(&noise->noise, x, y, out) == DSN_OK);
            std::vector<long double> expected = reference_value(&noise->noise, x, y);
            for (uint32_t k = 0; k < c.channels; k++) {
                CAPTURE(x);
                CAPTURE(y);
                REQUIRE(std::fabs((long double)out[k] - expected[k]) <= 1.0L); // final rounding only
            }
        }
    }
}

// One impulse's read through the runtime's bracket and add_bilinear, on a 3 x 3 single-channel texton
// whose top-left 2 x 2 texels are `corners` (a, b above, c, d below), at the offset (-1 + fx, -1 + fy),
// fx and fy the Q0.32 fractions: the sum, times 2^32 (Q.32), as a signed integer.
int64_t read_cell(const int32_t corners[4], uint32_t bits, uint32_t fx, uint32_t fy) {
    unsigned char texton[18] = {};
    const uint32_t at[4] = {0, 1, 3, 4};
    for (int k = 0; k < 4; k++)
        for (uint32_t byte = 0; byte < bits / 8; byte++)
            texton[at[k] * (bits / 8) + byte] = (unsigned char)(uint32_t(corners[k]) >> (8 * byte));
    dsn_asset asset{};
    asset.texton = texton, asset.channels = 1, asset.bits = bits, asset.width = 3, asset.height = 3;
    uint32_t row = 0, row_weight = 0, column = 0, column_weight = 0;
    if (!bracket(-one + int64_t(fx), 1, &column, &column_weight) ||
        !bracket(-one + int64_t(fy), 1, &row, &row_weight) || row != 0 || column != 0)
        return std::numeric_limits<int64_t>::min(); // no read: the caller's comparison fails
    uint64_t sum = 0;
    add_bilinear(&asset, row, row_weight, column, column_weight, &sum);
    return int64_t(sum);
}

// Real bilinear interpolation of the corners at the fractions (Q0.32), times 2^64: exact.
__int128 exact_bilinear(const int32_t corners[4], uint64_t fx, uint64_t fy) {
    const __int128 full = __int128(1) << 32;
    return (full - fx) * (full - fy) * corners[0] + __int128(fx) * (full - fy) * corners[1] +
           (full - fx) * __int128(fy) * corners[2] + __int128(fx) * __int128(fy) * corners[3];
}

TEST_CASE("continuous: a read is exact bilinear interpolation at 8-bit weights, within 2^-8 (Lx + Ly) of the "
          "real one") {
    // The definition: each offset's fraction floored to 2^-8 texel, then exact bilinear interpolation.
    // So against the real interpolation at the unfloored offset, the error is below 2^-8 (Lx + Ly), Lx and
    // Ly the largest texel differences of the cell along x and y (the interpolation's slopes). The
    // offsets' low 24 bits are all ones (the farthest from the floor) or random.
    std::mt19937_64 random(256);
    uint64_t reads = 0, wrong = 0; // plain counts: doctest's per-assertion cost would dominate
    auto check = [&](const int32_t corners[4], uint32_t bits, uint32_t fx, uint32_t fy) {
        const __int128 read = __int128(read_cell(corners, bits, fx, fy)) * (__int128(1) << 32);
        const uint32_t floor_mask = 0xFF000000u;
        const int64_t across = std::max(std::llabs(int64_t(corners[1]) - corners[0]),
                                        std::llabs(int64_t(corners[3]) - corners[2]));
        const int64_t down = std::max(std::llabs(int64_t(corners[2]) - corners[0]),
                                      std::llabs(int64_t(corners[3]) - corners[1]));
        const __int128 error = exact_bilinear(corners, fx, fy) - read;
        const __int128 bound = __int128(across + down) << 56; // 2^-8 (Lx + Ly), in units of 2^-64
        const __int128 size = error < 0 ? -error : error;
        const bool right = read == exact_bilinear(corners, fx & floor_mask, fy & floor_mask) &&
                           (across + down ? size < bound : size == 0);
        reads++;
        if (!right && wrong++ == 0)
            FAIL_CHECK("first wrong read: corners " << corners[0] << " " << corners[1] << " " << corners[2]
                                                    << " " << corners[3] << ", " << bits << "-bit, fractions "
                                                    << fx << " " << fy);
    };
    SUBCASE("every pair of 8-bit texels along x, at every weight") {
        for (int32_t a = -128; a <= 127; a++)
            for (int32_t b = -128; b <= 127; b++) {
                const int32_t corners[4] = {a, b, 0, 0};
                for (uint32_t weight = 0; weight < 256; weight++)
                    check(corners, 8, weight << 24 | 0xFFFFFFu, 0);
            }
    }
    SUBCASE("16-bit pairs along x and y: the extremes and random ones, at every weight") {
        const int32_t extremes[] = {-32768, -32767, -1, 0, 1, 32766, 32767};
        std::vector<std::pair<int32_t, int32_t>> pairs;
        for (int32_t a : extremes)
            for (int32_t b : extremes) pairs.push_back({a, b});
        for (int k = 0; k < 1000; k++) pairs.push_back({int16_t(random()), int16_t(random())});
        for (const auto &pair : pairs)
            for (uint32_t weight = 0; weight < 256; weight++) {
                const int32_t along_x[4] = {pair.first, pair.second, 0, 0};
                const int32_t along_y[4] = {pair.first, 0, pair.second, 0};
                check(along_x, 16, weight << 24 | uint32_t(random() >> 40), 0);
                check(along_y, 16, 0, weight << 24 | uint32_t(random() >> 40));
            }
    }
    SUBCASE("random 2 x 2 cells, 8- and 16-bit, at every pair of weights") {
        for (uint32_t bits : {8u, 16u})
            for (int cell = 0; cell < 24; cell++) {
                int32_t corners[4];
                for (int32_t &corner : corners)
                    corner = bits == 8 ? int32_t(int8_t(random())) : int32_t(int16_t(random()));
                if (cell == 0)
                    corners[0] = corners[3] = -(1 << (bits - 1)), corners[1] = corners[2] = -corners[0] - 1;
                for (uint32_t wy = 0; wy < 256; wy++)
                    for (uint32_t wx = 0; wx < 256; wx++)
                        check(corners, bits, wx << 24 | 0xFFFFFFu, wy << 24 | uint32_t(random() >> 40));
            }
    }
    CHECK(wrong == 0);
    CHECK(reads > 0);
}

TEST_CASE("continuous: at 64x magnification each step between neighbouring pixels is within its derivative's "
          "bound") {
    // Pixels 2^-6 texel apart are 4 steps of the 8-bit weights apart: the sums change by 2^8 times the
    // slope sums at each of the 4 steps (2^-8 texel), so |f(x + h) - f(x)| <= h (max |d| over the steps +
    // 1/2) + 1 + 1/64 units, h = 1/64 texel (the two values' roundings, the derivatives' half units, the
    // sums' floored fractions). Along x and along y, grey and RGB, 8- and 16-bit textons.
    std::mt19937_64 random(64);
    const int64_t pixel = one >> 6, weight_step = one >> 8;
    double largest_step = 0, largest_share = 0;
    uint32_t steps = 0, flat = 0;
    for (uint32_t channels : {1u, 3u})
        for (uint32_t bits : {8u, 16u}) {
            const auto made = make_noise(random_texton_asset(channels, 5, bits, 11 + channels + bits), 3);
            const dsn_noise &noise = made->noise;
            for (uint32_t axis = 0; axis < 2; axis++)
                for (int row = 0; row < 4; row++) {
                    int64_t start[2] = {int64_t(random()) >> 4, int64_t(random()) >> 4};
                    int32_t previous[3];
                    REQUIRE(dsn_continuous_point_fixed(&noise, start[0], start[1], previous) == DSN_OK);
                    for (int i = 1; i <= 256; i++) {
                        int64_t at[2] = {start[0], start[1]};
                        int32_t largest_derivative[3] = {0, 0, 0};
                        for (int k = 0; k < 4; k++) { // the derivative at each weight step on the way
                            at[axis] =
                                int64_t(uint64_t(start[axis]) + uint64_t((i - 1) * pixel + k * weight_step));
                            int32_t value[3], dx[3], dy[3];
                            REQUIRE(dsn_continuous_gradient_fixed(&noise, at[0], at[1], value, dx, dy) ==
                                    DSN_OK);
                            for (uint32_t c = 0; c < channels; c++)
                                largest_derivative[c] =
                                    std::max(largest_derivative[c], std::abs(axis ? dy[c] : dx[c]));
                        }
                        at[axis] = int64_t(uint64_t(start[axis]) + uint64_t(i * pixel));
                        int32_t value[3];
                        REQUIRE(dsn_continuous_point_fixed(&noise, at[0], at[1], value) == DSN_OK);
                        for (uint32_t c = 0; c < channels; c++) {
                            const double step = std::fabs(double(value[c]) - previous[c]);
                            const double bound = (largest_derivative[c] + 0.5) / 64 + 1 + 1.0 / 64;
                            CHECK(step <= bound);
                            largest_step = std::max(largest_step, step);
                            largest_share = std::max(largest_share, step / bound);
                            steps++, flat += step == 0;
                            previous[c] = value[c];
                        }
                    }
                }
        }
    // No plateaus: a pixel equals its neighbour only where the noise is flat.
    CHECK(flat * 100 <= steps);
    MESSAGE("64x: largest step " << largest_step / 65536 << " (Q16.16 units / 65536), at most "
                                 << largest_share << " of its bound; " << flat << " of " << steps
                                 << " steps flat");
}

TEST_CASE("continuous: every kernel's per-point evaluator gives the default kernel's bits") {
    struct Case {
        uint32_t channels, radius, bits, impacts_q16, period_x, period_y;
    };
    // Every texton kind (the vector evaluators take 8-bit textons and cells of side <= 16: the others
    // check that they are left to the default evaluator), from the sparsest density to ones with more
    // candidates per point than a vector evaluator buffers, and periodic noises.
    const Case cases[] = {{3, 15, 8, 30u << 16, 0, 0},
                          {1, 15, 8, 30u << 16, 0, 0},
                          {3, 15, 16, 30u << 16, 0, 0},
                          {3, 0, 8, 1u << 14, 0, 0},
                          {1, 1, 8, 64u << 16, 0, 0},
                          {3, 10, 8, 1000u << 16, 0, 0},
                          {1, 20, 8, DSN_IMPACTS_MIN_Q16, 0, 0},
                          {3, 40, 8, 30u << 16, 0, 0},
                          {3, 9, 8, 30u << 16, 16, 13},
                          {1, 9, 8, 30u << 16, 37, 0},
                          {3, 9, 8, 30u << 16, 1, 1},
                          {3, 9, 8, 30u << 16, 3000, 77777},
                          {3, 9, 8, 30u << 16, 0xFFFFFFFFu, 1u << 31}};
    uint64_t seed = 7;
    for (const Case &c : cases) {
        CAPTURE(c.channels);
        CAPTURE(c.radius);
        CAPTURE(c.bits);
        CAPTURE(c.impacts_q16);
        CAPTURE(c.period_x);
        CAPTURE(c.period_y);
        auto noise = make_noise(random_texton_asset(c.channels, c.radius, c.bits, uint32_t(seed)),
                                uint32_t(seed * 31), c.impacts_q16, c.period_x, c.period_y);
        std::vector<int64_t> xs, ys;
        renderer_points(seed++, 400, &xs, &ys);
        dsn_noise reference = noise->noise;
        dsn_state(&reference)->tile_kernel = DSN_KERNEL_DEFAULT;
        size_t differences = 0;
        for (uint32_t kernel = DSN_KERNEL_DEFAULT + 1; kernel <= dsn_state(&noise->noise)->tile_kernel;
             kernel++) {
            CAPTURE(kernel);
            dsn_noise copy = noise->noise;
            dsn_state(&copy)->tile_kernel = kernel;
            for (size_t k = 0; k < xs.size(); k++) {
                int32_t expected[3] = {0, 0, 0}, got[3] = {0, 0, 0};
                REQUIRE(dsn_continuous_point_fixed(&reference, xs[k], ys[k], expected) == DSN_OK);
                REQUIRE(dsn_continuous_point_fixed(&copy, xs[k], ys[k], got) == DSN_OK);
                differences += std::memcmp(expected, got, sizeof got) != 0;
            }
        }
        CHECK(differences == 0);
    }
}

TEST_CASE("continuous: a grid tile gives exactly the per-point values, in every output type") {
    std::mt19937_64 random(9);
    auto rgb = make_noise(random_texton_asset(3, 5, 8, 3), 77);
    auto grey = make_noise(random_texton_asset(1, 4, 16, 4), 78, 12u << 16, 40, 24);
    auto dense = make_noise(random_texton_asset(3, 9, 16, 5), 79, 300u << 16);
    size_t splatted = 0;
    for (auto *noise : {&rgb->noise, &grey->noise, &dense->noise}) {
        const uint32_t channels = dsn_noise_channels(noise);
        for (int trial = 0; trial < 40; trial++) {
            const double angle = double(random() % 6283) / 1000, zoom = 0.25 + double(random() % 400) / 100;
            dsn_grid grid;
            grid.origin_x = random_coordinate(random);
            grid.origin_y = random_coordinate(random);
            grid.column_step_x = int64_t(std::llround(std::cos(angle) / zoom * 4294967296.0));
            grid.column_step_y = int64_t(std::llround(std::sin(angle) / zoom * 4294967296.0));
            grid.row_step_x = -grid.column_step_y;
            grid.row_step_y = grid.column_step_x;
            if (trial % 2 == 0) { // axis-aligned: the splatting path, from 1/65536 to 8 texels per pixel
                const int64_t steps[] = {65536, one / 16, one / 3, one, one + 12345, 3 * one, 8 * one};
                grid.column_step_x = steps[random() % 7];
                grid.row_step_y = trial % 4 == 0 ? grid.column_step_x : steps[random() % 7];
                grid.column_step_y = grid.row_step_x = 0;
            }
            const uint32_t width = 1 + uint32_t(random() % 40), height = 1 + uint32_t(random() % 30);
            std::vector<int32_t> tile(width * height * channels);
            std::vector<float> tile_float(tile.size());
            std::vector<uint8_t> tile_u8(tile.size());
            const size_t scratch_size = dsn_continuous_tile_scratch_size(noise, &grid, width, height);
            splatted += scratch_size != 0;
            if (scratch_size != 0) {
                CHECK(dsn_continuous_tile_fixed(noise, &grid, width, height, tile.data(), nullptr, 0) ==
                      DSN_ERR_SCRATCH);
            }
            // One byte more, used from an odd address: the scratch needs no alignment.
            std::vector<unsigned char> buffer(scratch_size + 1);
            unsigned char *scratch_bytes = buffer.data() + 1;
            REQUIRE(dsn_continuous_tile_fixed(noise, &grid, width, height, tile.data(), scratch_bytes,
                                              scratch_size) == DSN_OK);
            REQUIRE(dsn_continuous_tile_float(noise, &grid, width, height, tile_float.data(), scratch_bytes,
                                              scratch_size) == DSN_OK);
            REQUIRE(dsn_continuous_tile_u8(noise, &grid, width, height, tile_u8.data(), scratch_bytes,
                                           scratch_size) == DSN_OK);
            for (uint32_t j = 0; j < height; j++)
                for (uint32_t i = 0; i < width; i++) {
                    int64_t x = int64_t(uint64_t(grid.origin_x) + uint64_t(grid.column_step_x) * i +
                                        uint64_t(grid.row_step_x) * j);
                    int64_t y = int64_t(uint64_t(grid.origin_y) + uint64_t(grid.column_step_y) * i +
                                        uint64_t(grid.row_step_y) * j);
                    int32_t point[3];
                    dsn_continuous_point_fixed(noise, x, y, point);
                    for (uint32_t c = 0; c < channels; c++) {
                        size_t at = (size_t(j) * width + i) * channels + c;
                        REQUIRE(tile[at] == point[c]);
                        REQUIRE(tile_float[at] == dsn_fixed_to_float(point[c]));
                        REQUIRE(tile_u8[at] == dsn_fixed_to_u8(point[c]));
                    }
                }
        }
    }
#if DSN_SMALL_CODE
    CHECK(splatted == 0); // the small build (dsn.h) evaluates every grid point by point, without scratch
#else
    CHECK(splatted >= 30); // the axis-aligned, non-periodic grids took the splatting path
#endif
}

TEST_CASE("continuous: periodic mode repeats exactly at real-valued points") {
    std::mt19937_64 random(21);
    const uint32_t periods[][2] = {{64, 64}, {37, 11}, {1, 300}, {0, 50}};
    for (const auto &period : periods) {
        auto noise = make_noise(random_texton_asset(3, 4, 8, 6), 5, 0, period[0], period[1]);
        for (int i = 0; i < 300; i++) {
            // Away from the int32 wrap: a period that does not divide 2^32 cannot repeat across it.
            int64_t x = random_coordinate(random) / 2, y = random_coordinate(random) / 2;
            int32_t base[3], moved[3];
            dsn_continuous_point_fixed(&noise->noise, x, y, base);
            if (period[0]) {
                dsn_continuous_point_fixed(
                    &noise->noise, int64_t(uint64_t(x) + uint64_t(period[0]) * uint64_t(one)), y, moved);
                REQUIRE(std::memcmp(base, moved, sizeof base) == 0);
            }
            if (period[1]) {
                dsn_continuous_point_fixed(
                    &noise->noise, x, int64_t(uint64_t(y) - 3 * uint64_t(period[1]) * uint64_t(one)), moved);
                REQUIRE(std::memcmp(base, moved, sizeof base) == 0);
            }
        }
    }
}
