// gradient_test.cpp - the gradient functions (dsn.h, "Gradients") against the values they differentiate:
// the continuous noise's exact derivative (its sums step by the slopes, bit for bit; normalized, finite
// differences within the rounding), the lattice noise's forward differences (the spot noise of the
// differenced texton, from a reference walk over the impulses), the histogram mapping's chain rule,
// tiles and batches against points (pixels exactly at an impulse's reach edges included), and the errors.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <random>
#include <vector>

#include "fixtures/continuous_fixtures.h"
#include "fixtures/test_assets.h"
#include "offline/bake_internal.h"
#include "runtime/core/continuous_internal.h"
#include "runtime/core/filtered_internal.h"
#include "runtime/core/gradient_output.h"
#include "runtime/core/histogram_map.h"
#include "runtime/kernels/kernels.h"

using namespace continuous_fixtures;

namespace {

const int64_t step = int64_t(1) << 24; // 2^-8 texel in Q32.32: one step of the 8-bit bilinear weights
const uint64_t step_slopes = 256;      // a step in slope units (2^-16 texel)

struct RawSums {
    uint64_t value[3], slope_x[3], slope_y[3];
};

// a + b modulo 2^64: coordinates live on the torus, and a signed overflow would be undefined.
int64_t moved(int64_t a, int64_t b) { return int64_t(uint64_t(a) + uint64_t(b)); }

RawSums raw_sums(const dsn_noise &noise, int64_t x, int64_t y) {
    RawSums sums;
    dsn_internal_continuous_slopes(dsn_state(&noise), uint64_t(x), uint64_t(y), sums.value, sums.slope_x,
                                   sums.slope_y);
    return sums;
}

// The assets every case runs on: grey and RGB, 8 and 16 bits, two texton sizes.
std::vector<dsn::AssetFields> assets() {
    std::vector<dsn::AssetFields> list;
    for (uint32_t channels : {1u, 3u})
        for (uint32_t bits : {8u, 16u})
            for (uint32_t radius : {3u, 9u})
                list.push_back(random_texton_asset(channels, radius, bits, 40 + radius));
    return list;
}

// Points with an impulse of the noise exactly at their reach's entry edge along x (even k) or y (odd k)
// (the texton's reach, or with `level` that of a pyramid level of radius `level_radius`),
// where its value is 0 and its slope is not: the impulse's position less radius + 1 texels along that
// axis, within reach along the other; non-periodic noises. Every second one's position along the edge's
// axis is a multiple of a sifting step (the low 16 - half bits of its 16-bit position zero), where the
// sift's bound on the field halves is tight: the fast walks' cell bounds must keep it.
void add_entry_edge_points(const dsn_noise &noise, std::mt19937_64 &random, uint32_t count,
                           std::vector<int64_t> *xs, std::vector<int64_t> *ys, uint32_t level = 0,
                           uint32_t level_radius = 0) {
    const dsn_noise_state *state = dsn_state(&noise);
    const uint32_t shift = state->cell_shift;
    const uint32_t below_half = dsn_field_shift(shift) == 3 ? 0xFFFu : 0xFFu;
    for (uint32_t k = 0; k < count;) {
        const uint32_t cell_x = uint32_t(random() % 4096), cell_y = uint32_t(random() % 4096);
        const uint32_t key = dsn_cell_key(state, cell_x, cell_y);
        const uint32_t impulses = dsn_cell_impulse_count(state, key);
        if (impulses == 0) continue;
        const uint32_t hash = dsn_impulse_hash(state, key, uint32_t(random() % impulses));
        const uint32_t edge = k % 2, across = 1 - edge;
        const uint32_t bits[2] = {dsn_impulse_bits_x(hash), dsn_impulse_bits_y(hash)};
        if ((k / 2) % 2 == 1 && (bits[edge] & below_half) != 0) continue;
        // the impulse at (cell << shift) texels plus its 16-bit position in units of 2^(shift - 16)
        const int64_t impulse[2] = {(int64_t(cell_x) << (32 + shift)) + (int64_t(bits[0]) << (16 + shift)),
                                    (int64_t(cell_y) << (32 + shift)) + (int64_t(bits[1]) << (16 + shift))};
        int64_t point[2];
        // a pyramid level's reach: its radius + 1 level texels, 2^level texels each
        const int64_t reach = level == 0 ? (int64_t(state->radius[edge]) + 1) * (int64_t(1) << 32)
                                         : (int64_t(level_radius) + 1) * (int64_t(1) << (32 + level));
        point[edge] = impulse[edge] - reach;
        // within radius + 1 texels along the other axis, on the 2^-16 grid
        const int64_t span = (2 * int64_t(state->radius[across]) + 1) * 65536;
        point[across] = impulse[across] + (int64_t(random() % uint64_t(span)) - span / 2) * 65536;
        xs->push_back(point[0]), ys->push_back(point[1]);
        k++;
    }
}

} // namespace

TEST_CASE("continuous gradient: the value is the point's; the sums step by the slopes exactly") {
    for (const dsn::AssetFields &fields : assets()) {
        for (uint32_t period : {0u, 37u}) {
            const auto made = make_noise(fields, 7, 0, period, period);
            const dsn_noise &noise = made->noise;
            const uint32_t shift = dsn_state(&noise)->cell_shift;
            std::vector<int64_t> xs, ys;
            renderer_points(91 + period, 60, &xs, &ys);
            for (size_t p = 0; p < xs.size(); p++) {
                int32_t value[3], dx[3], dy[3], expected[3];
                REQUIRE(dsn_continuous_gradient_fixed(&noise, xs[p], ys[p], value, dx, dy) == DSN_OK);
                REQUIRE(dsn_continuous_point_fixed(&noise, xs[p], ys[p], expected) == DSN_OK);
                for (uint32_t c = 0; c < fields.channels; c++) CHECK(value[c] == expected[c]);

                // One step of the weights: the sums move by 2^8 times the slopes, always (every weight
                // moves up one step; one that wraps moves to the next texel pair, where the interpolation
                // continues). Again from the point moved by one step of the impulses' positions
                // (2^(cell_shift - 16) texel), less than a weight step: some weights differ there.
                const RawSums here = raw_sums(noise, xs[p], ys[p]);
                const RawSums east = raw_sums(noise, moved(xs[p], step), ys[p]);
                const RawSums south = raw_sums(noise, xs[p], moved(ys[p], step));
                for (uint32_t c = 0; c < fields.channels; c++) {
                    CHECK(east.value[c] - here.value[c] == step_slopes * here.slope_x[c]);
                    CHECK(south.value[c] - here.value[c] == step_slopes * here.slope_y[c]);
                }
                const int64_t nudge = int64_t(1) << (16 + shift);
                const RawSums nudged = raw_sums(noise, moved(xs[p], nudge), ys[p]);
                const RawSums nudged_east = raw_sums(noise, moved(xs[p], nudge + step), ys[p]);
                for (uint32_t c = 0; c < fields.channels; c++)
                    CHECK(nudged_east.value[c] - nudged.value[c] == step_slopes * nudged.slope_x[c]);
            }
        }
    }
}

TEST_CASE("continuous gradient: every kernel's sums are the default kernel's, the vector ones included") {
    // Random points, and points with an impulse exactly at their reach's entry edge (where only the slope
    // is non-zero), at densities whose cells have up to 16 impulses and more, periodic too.
    std::mt19937_64 random(17);
    size_t vector_points = 0, differences = 0;
    for (uint32_t channels : {1u, 3u})
        for (uint32_t bits : {8u, 16u}) // the vector walk's, and the sifting walk's (every kernel has both)
            for (uint32_t impacts : {0u, 160u << 16}) // the default density, and cells past 16 impulses
                for (uint32_t period : {0u, 45u}) {
                    const auto made =
                        make_noise(random_texton_asset(channels, 9, bits, 7), 3, impacts, period, period);
                    dsn_noise_state *state = dsn_state(&made->noise);
                    const uint32_t chosen = state->tile_kernel;
                    std::vector<int64_t> xs, ys;
                    for (int k = 0; k < 400; k++)
                        xs.push_back(int64_t(random() & ~uint64_t(0xFFFF)) >> 8),
                            ys.push_back(int64_t(random() & ~uint64_t(0xFFFF)) >> 8);
                    if (period == 0) add_entry_edge_points(made->noise, random, 600, &xs, &ys);
                    for (size_t k = 0; k < xs.size(); k++) {
                        const int64_t x = xs[k], y = ys[k];
                        state->tile_kernel = DSN_KERNEL_DEFAULT;
                        const RawSums expected = raw_sums(made->noise, x, y);
                        for (uint32_t kernel = DSN_KERNEL_DEFAULT + 1; kernel <= chosen; kernel++) {
                            dsn_continuous_point_entry *entry =
                                dsn_kernel_entries_of(kernel)->continuous_point;
                            if (entry == nullptr) continue;
                            RawSums sums;
                            if (!entry(state, uint64_t(x), uint64_t(y), sums.value, sums.slope_x,
                                       sums.slope_y, nullptr))
                                continue;
                            vector_points++;
                            // the value alone too: the entry's other walk
                            uint64_t value[3];
                            REQUIRE(entry(state, uint64_t(x), uint64_t(y), value, nullptr, nullptr, nullptr));
                            for (uint32_t c = 0; c < 3; c++)
                                differences += (sums.value[c] != expected.value[c]) +
                                               (value[c] != expected.value[c]) +
                                               (sums.slope_x[c] != expected.slope_x[c]) +
                                               (sums.slope_y[c] != expected.slope_y[c]);
                        }
                    }
                    state->tile_kernel = chosen;
                }
    CHECK(differences == 0);
    // Where this CPU runs a kernel with the vector sums, they were compared.
    bool has_vector = false;
    for (uint32_t kernel = DSN_KERNEL_DEFAULT + 1; kernel < dsn_internal_kernel_count; kernel++)
        has_vector = has_vector || dsn_kernel_entries_of(kernel)->continuous_point != nullptr;
    if (has_vector && dsn_internal_choose_kernel() > DSN_KERNEL_DEFAULT) CHECK(vector_points > 0);
    MESSAGE("points through the kernels' vector sums: " << vector_points);
}

TEST_CASE("continuous gradient: across a whole texel the sums are the integral of the slopes") {
    // f(x + 1) - f(x) = sum over the 2^8 steps of 2^8 times the slope at each: every texel edge is crossed.
    const auto made = make_noise(random_texton_asset(3, 4, 8, 5), 3);
    const dsn_noise &noise = made->noise;
    const int64_t points[2][2] = {{int64_t(17) << 32 | 0x12345678, -(int64_t(5) << 32) + 0x0FEDCBA9},
                                  {int64_t(0x7FFFFFFF) << 32 | 0x80000000, 0}};
    for (const auto &point : points) {
        uint64_t integral_x[3] = {0, 0, 0}, integral_y[3] = {0, 0, 0};
        for (int64_t j = 0; j < 256; j++) {
            const RawSums along_x = raw_sums(noise, moved(point[0], j * step), point[1]);
            const RawSums along_y = raw_sums(noise, point[0], moved(point[1], j * step));
            for (int c = 0; c < 3; c++)
                integral_x[c] += step_slopes * along_x.slope_x[c],
                    integral_y[c] += step_slopes * along_y.slope_y[c];
        }
        const RawSums here = raw_sums(noise, point[0], point[1]);
        const RawSums east = raw_sums(noise, moved(point[0], int64_t(1) << 32), point[1]);
        const RawSums south = raw_sums(noise, point[0], moved(point[1], int64_t(1) << 32));
        for (int c = 0; c < 3; c++) {
            CHECK(east.value[c] - here.value[c] == integral_x[c]);
            CHECK(south.value[c] - here.value[c] == integral_y[c]);
        }
    }
}

TEST_CASE("continuous gradient: finite differences agree within the rounding") {
    // Over one step of the weights, h = 2^-8 texel, A(x + h) - A(x) = h D exactly for the unrounded
    // normalized value A and derivative D (every weight moves one step, within its piece or onto the
    // next, where the interpolation continues); the outputs round each once (half a unit) after flooring
    // the sums' fractions (below 2^-gain_shift each), so |f(x + h) - f(x) - h dx| <= 1 + h / 2 + 1/64
    // units. (A shorter move changes no weight: the read is constant between steps.)
    for (const dsn::AssetFields &fields : assets()) {
        const auto made = make_noise(fields, 12);
        const dsn_noise &noise = made->noise;
        REQUIRE(dsn_state(&noise)->gain_shift >= 6);
        std::vector<int64_t> xs, ys;
        renderer_points(5, 80, &xs, &ys);
        int checked = 0;
        for (size_t p = 0; p < xs.size(); p++) {
            const int64_t x = xs[p], y = ys[p];
            int32_t value[3], dx[3], dy[3], east[3], south[3];
            REQUIRE(dsn_continuous_gradient_fixed(&noise, x, y, value, dx, dy) == DSN_OK);
            REQUIRE(dsn_continuous_point_fixed(&noise, moved(x, step), y, east) == DSN_OK);
            REQUIRE(dsn_continuous_point_fixed(&noise, x, moved(y, step), south) == DSN_OK);
            const double h = 1.0 / 256, bound = 1.0 + h / 2 + 1.0 / 64;
            for (uint32_t c = 0; c < fields.channels; c++) {
                CHECK(std::fabs(double(east[c]) - value[c] - h * dx[c]) <= bound);
                CHECK(std::fabs(double(south[c]) - value[c] - h * dy[c]) <= bound);
                checked += dx[c] != 0;
            }
            float value_f[3], dx_f[3], dy_f[3];
            const double fx = double(x) / 4294967296.0, fy = double(y) / 4294967296.0;
            if (dsn_coordinate_from_double(fx) == x && dsn_coordinate_from_double(fy) == y) {
                REQUIRE(dsn_continuous_gradient_float(&noise, fx, fy, value_f, dx_f, dy_f) == DSN_OK);
                for (uint32_t c = 0; c < fields.channels; c++) {
                    CHECK(value_f[c] == dsn_fixed_to_float(value[c]));
                    CHECK(dx_f[c] == dsn_fixed_to_float(dx[c]));
                    CHECK(dy_f[c] == dsn_fixed_to_float(dy[c]));
                }
            }
        }
        CHECK(checked > 20); // the slopes are not all zero
    }
}

namespace {

// The lattice noise's sums of the texton differenced along one axis, t(o + e) - t(o), over every impulse
// whose differenced window holds (x, y): a walk of its own over the cells (no period), reading impulse
// positions from the cell hashes.
std::vector<uint32_t> differenced_sums(const dsn_noise &noise, uint32_t x, uint32_t y, bool along_x) {
    const dsn_noise_state *state = dsn_state(&noise);
    const dsn_asset &asset = state->asset;
    const uint32_t shift = state->cell_shift, radius_x = state->radius[0], radius_y = state->radius[1];
    const uint32_t half_bits = 1u << (dsn_field_shift(shift) - 1u), drop = half_bits - shift;
    auto texel = [&](int64_t row, int64_t column, uint32_t c) -> int64_t {
        if (row < 0 || column < 0 || row >= asset.height || column >= asset.width) return 0;
        return dsn_asset_texton_value(&asset, uint32_t(row), uint32_t(column), c);
    };
    std::vector<uint32_t> sums(asset.channels, 0);
    const uint32_t reach_x = radius_x + 1, reach_y = radius_y + 1;
    const uint32_t low_x = x - reach_x, low_y = y - reach_y, in_cell = (1u << shift) - 1u;
    const uint32_t first_x = low_x >> shift, first_y = low_y >> shift;
    const uint32_t cells_x = (((low_x & in_cell) + 2 * reach_x) >> shift) + 1;
    const uint32_t cells_y = (((low_y & in_cell) + 2 * reach_y) >> shift) + 1;
    for (uint32_t j = 0; j < cells_y; j++)
        for (uint32_t i = 0; i < cells_x; i++) {
            const uint32_t cell_x = (first_x + i) & (0xFFFFFFFFu >> shift),
                           cell_y = (first_y + j) & (0xFFFFFFFFu >> shift);
            const uint32_t key = dsn_cell_key(state, cell_x, cell_y);
            for (uint32_t k = 0; k < dsn_cell_impulse_count(state, key); k++) {
                const uint32_t field = dsn_impulse_field(state, key, k);
                const uint32_t px = (cell_x << shift) + ((field & ((1u << half_bits) - 1u)) >> drop);
                const uint32_t py = (cell_y << shift) + ((field >> half_bits) >> drop);
                const int64_t column = int64_t(int32_t(x - px)) + radius_x,
                              row = int64_t(int32_t(y - py)) + radius_y;
                for (uint32_t c = 0; c < asset.channels; c++) {
                    const int64_t next = along_x ? texel(row, column + 1, c) : texel(row + 1, column, c);
                    sums[c] += uint32_t(next - texel(row, column, c));
                }
            }
        }
    return sums;
}

} // namespace

TEST_CASE("lattice gradient: the spot noise of the differenced texton, normalized once") {
    for (const dsn::AssetFields &fields : assets()) {
        const auto made = make_noise(fields, 21, 0, 0, 0, DSN_FLAG_ALLOW_LATTICE_CONTINUOUS);
        const dsn_noise &noise = made->noise;
        std::mt19937 random(77);
        for (int p = 0; p < 60; p++) {
            // anywhere, and near the 32-bit wrap of the lattice
            const uint32_t x = p % 3 == 0 ? 0xFFFFFFF0u + uint32_t(p % 32) : uint32_t(random());
            const uint32_t y = p % 5 == 0 ? 0x7FFFFFF8u + uint32_t(p % 16) : uint32_t(random());
            int32_t value[3], dx[3], dy[3], expected[3], east[3], south[3];
            REQUIRE(dsn_lattice_gradient_fixed(&noise, int32_t(x), int32_t(y), value, dx, dy) == DSN_OK);
            dsn_lattice_point_fixed(&noise, int32_t(x), int32_t(y), expected);
            dsn_lattice_point_fixed(&noise, int32_t(x + 1u), int32_t(y), east);
            dsn_lattice_point_fixed(&noise, int32_t(x), int32_t(y + 1u), south);
            int32_t reference_x[3], reference_y[3];
            dsn_normalize_from(dsn_state(&noise), dsn_no_offset, differenced_sums(noise, x, y, true).data(),
                               reference_x);
            dsn_normalize_from(dsn_state(&noise), dsn_no_offset, differenced_sums(noise, x, y, false).data(),
                               reference_y);
            for (uint32_t c = 0; c < fields.channels; c++) {
                CHECK(value[c] == expected[c]);
                CHECK(dx[c] == reference_x[c]);
                CHECK(dy[c] == reference_y[c]);
                // each of the three rounded once: the difference of two values is within one unit
                CHECK(std::abs(int64_t(east[c]) - expected[c] - dx[c]) <= 1);
                CHECK(std::abs(int64_t(south[c]) - expected[c] - dy[c]) <= 1);
            }
        }
    }
}

TEST_CASE("lattice gradient: the vector walk sums the point and its neighbours at once, full cells too") {
    // 31 x 31 textons at the default density and at one whose 16 x 16 cells often hold more than 16
    // impulses (the walk's rest path), grey and RGB, 8 and 16 bits, against the reference walk.
    size_t fast = 0;
    for (uint32_t channels : {1u, 3u})
        for (uint32_t bits : {8u, 16u})
            for (uint32_t impacts : {0u, 52u << 16}) {
                const auto made = make_noise(random_texton_asset(channels, 15, bits, 70 + channels + bits),
                                             23, impacts, 0, 0, DSN_FLAG_ALLOW_LATTICE_CONTINUOUS);
                const dsn_noise &noise = made->noise;
                const dsn_noise_state *state = dsn_state(&noise);
                fast += state->cell_shift == 4 && state->poisson_parts == 1;
                std::mt19937 random(91);
                size_t differences = 0;
                dsn_noise_state *kernel_state = const_cast<dsn_noise_state *>(state);
                const uint32_t chosen = kernel_state->tile_kernel;
                for (int p = 0; p < 200; p++) {
                    // every kernel this CPU runs, in turn: each has its copy of the walk
                    kernel_state->tile_kernel = uint32_t(p) % (chosen + 1);
                    const uint32_t x = p % 7 == 0 ? 0xFFFFFFF0u + uint32_t(p % 32) : uint32_t(random());
                    const uint32_t y = p % 11 == 0 ? 0xFFFFFFF8u + uint32_t(p % 16) : uint32_t(random());
                    int32_t value[3], dx[3], dy[3], expected[3], reference_x[3], reference_y[3];
                    REQUIRE(dsn_lattice_gradient_fixed(&noise, int32_t(x), int32_t(y), value, dx, dy) ==
                            DSN_OK);
                    dsn_lattice_point_fixed(&noise, int32_t(x), int32_t(y), expected);
                    dsn_normalize_from(state, dsn_no_offset, differenced_sums(noise, x, y, true).data(),
                                       reference_x);
                    dsn_normalize_from(state, dsn_no_offset, differenced_sums(noise, x, y, false).data(),
                                       reference_y);
                    for (uint32_t c = 0; c < channels; c++)
                        differences +=
                            (value[c] != expected[c]) + (dx[c] != reference_x[c]) + (dy[c] != reference_y[c]);
                }
                kernel_state->tile_kernel = chosen;
                CHECK(differences == 0);
            }
    MESSAGE("noises through the vector walk: " << fast << " of 8");
    CHECK(fast >= 4); // the vector walk's conditions held for the default density at least
}

TEST_CASE("lattice gradient: periodic noises, the int32 wrap of a reduced coordinate included") {
    const auto made = make_noise(random_texton_asset(3, 5, 8, 9), 4, 0, 37, 1000);
    const dsn_noise &noise = made->noise;
    const int32_t xs[] = {0, 36, 37, -1, INT32_MAX, INT32_MIN, 123456};
    for (int32_t x : xs)
        for (int32_t y : xs) {
            int32_t value[3], dx[3], dy[3], here[3], east[3], south[3];
            REQUIRE(dsn_lattice_gradient_fixed(&noise, x, y, value, dx, dy) == DSN_OK);
            dsn_lattice_point_fixed(&noise, x, y, here);
            dsn_lattice_point_fixed(&noise, int32_t(uint32_t(x) + 1u), y, east);
            dsn_lattice_point_fixed(&noise, x, int32_t(uint32_t(y) + 1u), south);
            for (int c = 0; c < 3; c++) {
                CHECK(value[c] == here[c]);
                CHECK(std::abs(int64_t(east[c]) - here[c] - dx[c]) <= 1);
                CHECK(std::abs(int64_t(south[c]) - here[c] - dy[c]) <= 1);
            }
        }
}

namespace {

// A smooth increasing table over [-4, 4] per channel with a full rotation and a centre: the chain rule
// sees every part of the mapping.
dsn::HistogramMapping gradient_mapping(uint32_t channels) {
    dsn::HistogramMapping m;
    for (uint32_t k = 0; k < channels; k++)
        for (uint32_t i = 0; i < m.entry_count; i++) {
            const double x = -4.0 + i / 8.0;
            m.tables.push_back(int32_t(std::lround((0.3 * x + 0.05 * x * x * x + 0.1 * k) * 4096)));
        }
    if (channels == 3) {
        const double P[9] = {0.8, -0.3, 0.2, 0.35, 0.9, -0.1, -0.25, 0.15, 1.05};
        for (int i = 0; i < 9; i++) m.rotation[i] = int32_t(std::lround(P[i] * DSN_Q24_ONE));
    } else {
        m.rotation[0] = int32_t(std::lround(1.3 * DSN_Q24_ONE));
        for (int i = 1; i < 9; i++) m.rotation[i] = 0;
    }
    for (uint32_t c = 0; c < channels; c++)
        m.centre[c] = int32_t(std::lround((0.45 + 0.05 * c) * DSN_Q24_ONE));
    return m;
}

int64_t round_half_up(int64_t value, int64_t divisor) {
    const int64_t shifted = value + divisor / 2;
    return shifted >= 0 ? shifted / divisor : -((-shifted + divisor - 1) / divisor);
}

// dsn.h's chain rule from the mapping's fields: v_k' = round(slope_k d_k / 2^d), saturated to +-2^29, then
// out_c' = round(sum_k P[c][k] v_k' / 2^24).
std::vector<int32_t> reference_chain(const dsn::HistogramMapping &m, uint32_t channels, const int32_t *g,
                                     const int32_t *d) {
    const int64_t unit = int64_t(1) << (16 - m.step_shift), limit = int64_t(1) << 29;
    int64_t v[3] = {0, 0, 0};
    for (uint32_t k = 0; k < channels; k++) {
        const int64_t u = int64_t(g[k]) - m.input_low_q16;
        int64_t slope = 0;
        if (u >= 0 && u < int64_t(m.entry_count - 1) * unit) {
            const size_t i = size_t(u / unit) + k * m.entry_count;
            slope = (int64_t(m.tables[i + 1]) - m.tables[i]) * 16;
        }
        v[k] = std::max(-limit, std::min(limit, round_half_up(slope * d[k], unit)));
    }
    std::vector<int32_t> out(channels);
    for (uint32_t c = 0; c < channels; c++) {
        int64_t sum = 0;
        for (uint32_t k = 0; k < channels; k++) sum += int64_t(m.rotation[c * 3 + k]) * v[k];
        out[c] = int32_t(round_half_up(sum, int64_t(1) << 24));
    }
    return out;
}

} // namespace

TEST_CASE("gradient with a histogram mapping: the chain rule at the Gaussian-space value") {
    for (uint32_t channels : {1u, 3u}) {
        dsn::AssetFields fields = random_texton_asset(channels, 6, 8, 13);
        fields.histogram = gradient_mapping(channels);
        const auto mapped = make_noise(fields, 8);
        const auto gaussian = make_noise(fields, 8, 0, 0, 0, DSN_FLAG_NO_HISTOGRAM);
        std::vector<int64_t> xs, ys;
        renderer_points(17, 60, &xs, &ys);
        int sloped = 0;
        for (size_t p = 0; p < xs.size(); p++) {
            int32_t value[3], dx[3], dy[3], g[3], gx[3], gy[3], expected[3];
            REQUIRE(dsn_continuous_gradient_fixed(&mapped->noise, xs[p], ys[p], value, dx, dy) == DSN_OK);
            REQUIRE(dsn_continuous_gradient_fixed(&gaussian->noise, xs[p], ys[p], g, gx, gy) == DSN_OK);
            REQUIRE(dsn_continuous_point_fixed(&mapped->noise, xs[p], ys[p], expected) == DSN_OK);
            const std::vector<int32_t> chain_x = reference_chain(fields.histogram, channels, g, gx);
            const std::vector<int32_t> chain_y = reference_chain(fields.histogram, channels, g, gy);
            for (uint32_t c = 0; c < channels; c++) {
                CHECK(value[c] == expected[c]);
                CHECK(dx[c] == chain_x[c]);
                CHECK(dy[c] == chain_y[c]);
                sloped += dx[c] != gx[c];
            }
            // lattice: the same rule on the forward differences
            const int32_t lx = int32_t(xs[p] >> 32), ly = int32_t(ys[p] >> 32);
            REQUIRE(dsn_lattice_gradient_fixed(&mapped->noise, lx, ly, value, dx, dy) == DSN_OK);
            REQUIRE(dsn_lattice_gradient_fixed(&gaussian->noise, lx, ly, g, gx, gy) == DSN_OK);
            dsn_lattice_point_fixed(&mapped->noise, lx, ly, expected);
            const std::vector<int32_t> lattice_chain = reference_chain(fields.histogram, channels, g, gx);
            for (uint32_t c = 0; c < channels; c++) {
                CHECK(value[c] == expected[c]);
                CHECK(dx[c] == lattice_chain[c]);
            }
        }
        CHECK(sloped > 10); // the mapping changed the derivatives
    }
}

TEST_CASE("gradient tiles and batches are their points") {
    const auto made = make_noise(random_texton_asset(3, 7, 16, 2), 6, 0, 0, 19);
    const dsn_noise &noise = made->noise;
    const uint32_t width = 9, height = 7, values = width * height * 3;
    // a rotated, scaled grid across the int32 wrap of x
    const dsn_grid grid = {
        (int64_t(INT32_MAX) - 3) << 32, int64_t(5) << 31, 3000000000, 1100000000, -1100000000, 3000000000};
    std::vector<int32_t> out(values), dx(values), dy(values);
    std::vector<float> out_f(values), dx_f(values), dy_f(values);
    REQUIRE(dsn_continuous_tile_gradient_fixed(&noise, &grid, width, height, out.data(), dx.data(),
                                               dy.data()) == DSN_OK);
    REQUIRE(dsn_continuous_tile_gradient_float(&noise, &grid, width, height, out_f.data(), dx_f.data(),
                                               dy_f.data()) == DSN_OK);
    std::vector<int64_t> xs, ys;
    for (uint32_t j = 0; j < height; j++)
        for (uint32_t i = 0; i < width; i++) {
            int64_t x, y;
            dsn_test::grid_point(grid, i, j, &x, &y);
            xs.push_back(x), ys.push_back(y);
            int32_t value[3], gx[3], gy[3];
            REQUIRE(dsn_continuous_gradient_fixed(&noise, x, y, value, gx, gy) == DSN_OK);
            for (uint32_t c = 0; c < 3; c++) {
                const size_t at = (j * width + i) * 3 + c;
                CHECK(out[at] == value[c]);
                CHECK(dx[at] == gx[c]);
                CHECK(dy[at] == gy[c]);
                CHECK(dx_f[at] == dsn_fixed_to_float(gx[c]));
            }
        }
    std::vector<int32_t> batch(values), batch_dx(values), batch_dy(values);
    REQUIRE(dsn_continuous_batch_gradient_fixed(&noise, xs.data(), ys.data(), width * height, batch.data(),
                                                batch_dx.data(), batch_dy.data()) == DSN_OK);
    CHECK(batch == out);
    CHECK(batch_dx == dx);
    CHECK(batch_dy == dy);

    // lattice: a tile across both wraps of the periodic y (period 19) and the 2^32 wrap of x
    const int32_t x0 = -4, y0 = INT32_MAX - 2;
    REQUIRE(dsn_lattice_tile_gradient_fixed(&noise, x0, y0, width, height, out.data(), dx.data(),
                                            dy.data()) == DSN_OK);
    for (uint32_t j = 0; j < height; j++)
        for (uint32_t i = 0; i < width; i++) {
            int32_t value[3], gx[3], gy[3];
            REQUIRE(dsn_lattice_gradient_fixed(&noise, int32_t(uint32_t(x0) + i), int32_t(uint32_t(y0) + j),
                                               value, gx, gy) == DSN_OK);
            for (uint32_t c = 0; c < 3; c++) {
                const size_t at = (j * width + i) * 3 + c;
                CHECK(out[at] == value[c]);
                CHECK(dx[at] == gx[c]);
                CHECK(dy[at] == gy[c]);
            }
        }
}

namespace {

// The three planes (values, then x and y derivatives) of a width x height gradient tile from its points:
// point(i, j, value, dx, dy) returns the per-point function's code.
template <typename Point>
std::vector<int32_t> gradient_planes(uint32_t width, uint32_t height, uint32_t channels, const Point &point) {
    const size_t values = size_t(width) * height * channels;
    std::vector<int32_t> planes(3 * values);
    size_t failed = 0;
    for (uint32_t j = 0; j < height; j++)
        for (uint32_t i = 0; i < width; i++) {
            int32_t value[3], gx[3], gy[3];
            failed += point(i, j, value, gx, gy) != DSN_OK;
            for (uint32_t c = 0; c < channels; c++) {
                const size_t at = (size_t(j) * width + i) * channels + c;
                planes[at] = value[c];
                planes[values + at] = gx[c];
                planes[2 * values + at] = gy[c];
            }
        }
    REQUIRE(failed == 0);
    return planes;
}

// The values of every kernel's fixed and float gradient tiles (tile(out, dx, dy) of both types returns
// the call's code) that differ from `expected`'s planes (the floats: exactly the fixed / 65536).
template <typename Tile>
size_t kernel_tile_differences(const dsn_noise &noise, const std::vector<int32_t> &expected,
                               const Tile &tile) {
    dsn_noise_state *state = const_cast<dsn_noise_state *>(dsn_state(&noise));
    const uint32_t chosen = state->tile_kernel;
    const size_t values = expected.size() / 3;
    size_t differences = 0;
    for (uint32_t kernel = DSN_KERNEL_DEFAULT; kernel <= chosen; kernel++) {
        state->tile_kernel = kernel;
        std::vector<int32_t> fixed(expected.size());
        std::vector<float> floats(expected.size());
        REQUIRE(tile(fixed.data(), fixed.data() + values, fixed.data() + 2 * values) == DSN_OK);
        REQUIRE(tile(floats.data(), floats.data() + values, floats.data() + 2 * values) == DSN_OK);
        for (size_t k = 0; k < fixed.size(); k++)
            differences += (fixed[k] != expected[k]) + (floats[k] != dsn_fixed_to_float(expected[k]));
    }
    state->tile_kernel = chosen;
    return differences;
}

// dsn_*_tile_gradient_fixed or _float by the outputs' type.
struct LatticeGradientTile {
    const dsn_noise &noise;
    int32_t x0, y0;
    uint32_t width, height;
    int operator()(int32_t *out, int32_t *dx, int32_t *dy) const {
        return dsn_lattice_tile_gradient_fixed(&noise, x0, y0, width, height, out, dx, dy);
    }
    int operator()(float *out, float *dx, float *dy) const {
        return dsn_lattice_tile_gradient_float(&noise, x0, y0, width, height, out, dx, dy);
    }
};

struct ContinuousGradientTile {
    const dsn_noise &noise;
    const dsn_grid &grid;
    uint32_t width, height;
    int operator()(int32_t *out, int32_t *dx, int32_t *dy) const {
        return dsn_continuous_tile_gradient_fixed(&noise, &grid, width, height, out, dx, dy);
    }
    int operator()(float *out, float *dx, float *dy) const {
        return dsn_continuous_tile_gradient_float(&noise, &grid, width, height, out, dx, dy);
    }
};

// dsn_continuous_batch_gradient_fixed or _float (float64 coordinates, exact here) by the outputs' type.
struct ContinuousGradientBatch {
    const dsn_noise &noise;
    const std::vector<int64_t> &xs, &ys;
    int operator()(int32_t *out, int32_t *dx, int32_t *dy) const {
        return dsn_continuous_batch_gradient_fixed(&noise, xs.data(), ys.data(), uint32_t(xs.size()), out, dx,
                                                   dy);
    }
    int operator()(float *out, float *dx, float *dy) const {
        std::vector<double> real_xs, real_ys;
        for (size_t k = 0; k < xs.size(); k++)
            real_xs.push_back(std::ldexp(double(xs[k]), -32)),
                real_ys.push_back(std::ldexp(double(ys[k]), -32));
        return dsn_continuous_batch_gradient_float(&noise, real_xs.data(), real_ys.data(),
                                                   uint32_t(xs.size()), out, dx, dy);
    }
};

#if DSN_FILTERING
struct FilteredGradientTile {
    const dsn_noise &noise;
    const dsn_grid &grid;
    uint32_t max_taps, width, height;
    int operator()(int32_t *out, int32_t *dx, int32_t *dy) const {
        return dsn_filtered_tile_gradient_fixed(&noise, &grid, max_taps, width, height, out, dx, dy);
    }
    int operator()(float *out, float *dx, float *dy) const {
        return dsn_filtered_tile_gradient_float(&noise, &grid, max_taps, width, height, out, dx, dy);
    }
};
#endif

// Differences between every kernel's continuous gradient tile of `grid` and its points' gradients.
size_t continuous_tile_differences(const dsn_noise &noise, uint32_t channels, const dsn_grid &grid,
                                   uint32_t width, uint32_t height) {
    const std::vector<int32_t> expected = gradient_planes(
        width, height, channels, [&](uint32_t i, uint32_t j, int32_t *v, int32_t *gx, int32_t *gy) {
            int64_t x, y;
            dsn_test::grid_point(grid, i, j, &x, &y);
            return dsn_continuous_gradient_fixed(&noise, x, y, v, gx, gy);
        });
    const ContinuousGradientTile tile = {noise, grid, width, height};
    return kernel_tile_differences(noise, expected, tile);
}

#if DSN_FILTERING
// The same for the filtered gradient tile, its footprint the grid's steps.
size_t filtered_tile_differences(const dsn_noise &noise, uint32_t channels, const dsn_grid &grid,
                                 uint32_t max_taps, uint32_t width, uint32_t height) {
    const dsn_footprint footprint = {grid.column_step_x, grid.column_step_y, grid.row_step_x, grid.row_step_y,
                                     max_taps};
    const std::vector<int32_t> expected = gradient_planes(
        width, height, channels, [&](uint32_t i, uint32_t j, int32_t *v, int32_t *gx, int32_t *gy) {
            int64_t x, y;
            dsn_test::grid_point(grid, i, j, &x, &y);
            return dsn_filtered_gradient_fixed(&noise, x, y, &footprint, v, gx, gy);
        });
    const FilteredGradientTile tile = {noise, grid, max_taps, width, height};
    return kernel_tile_differences(noise, expected, tile);
}
#endif

// The grid of steps (column x, column y, row x, row y) whose pixel (5, 2) lies at (x, y).
dsn_grid grid_through(int64_t x, int64_t y, const int64_t *steps) {
    const dsn_grid grid = {x - 5 * steps[0] - 2 * steps[2],
                           y - 5 * steps[1] - 2 * steps[3],
                           steps[0],
                           steps[1],
                           steps[2],
                           steps[3]};
    return grid;
}

} // namespace

TEST_CASE("lattice gradient tiles: every kernel's, by strips or 32-bit sums, are their points") {
    // Tiles of several rectangles (the strips' rectangles are at most 128 x 128 sums), grey and RGB, a
    // histogram mapping (its chain rule point by point), a dense noise (short rectangles), and periods
    // whose int32 wrap cuts rectangles (those take the 32-bit path).
    size_t differences = 0;
    for (uint32_t channels : {1u, 3u})
        for (bool mapped : {false, true})
            for (uint32_t impacts : {0u, 100u << 16})
                for (uint32_t period : {0u, 37u}) {
                    dsn::AssetFields fields = random_texton_asset(channels, 9, 8, 50 + channels);
                    if (mapped) fields.histogram = gradient_mapping(channels);
                    const auto made =
                        make_noise(fields, 5, impacts, period, period, DSN_FLAG_ALLOW_LATTICE_CONTINUOUS);
                    const uint32_t width = 260, height = 130;
                    const int32_t x0 = period ? INT32_MAX - 200 : -150, y0 = period ? INT32_MAX - 60 : 7;
                    const std::vector<int32_t> expected = gradient_planes(
                        width, height, channels,
                        [&](uint32_t i, uint32_t j, int32_t *v, int32_t *gx, int32_t *gy) {
                            return dsn_lattice_gradient_fixed(&made->noise, int32_t(uint32_t(x0) + i),
                                                              int32_t(uint32_t(y0) + j), v, gx, gy);
                        });
                    const LatticeGradientTile tile = {made->noise, x0, y0, width, height};
                    differences += kernel_tile_differences(made->noise, expected, tile);
                }
    CHECK(differences == 0);
}

TEST_CASE("continuous gradient tiles: every kernel's, splatted or point by point, are their points") {
    // Rotated, magnified (axis-aligned: the runs share their columns), minified and mirrored grids, across
    // the 2^32 wrap of the torus and a periodic axis's int32 wrap, and at that wrap's seam, over several
    // blocks; grey and RGB, 8 and 16 bits, a histogram mapping (the chain rule).
    const int64_t one = int64_t(1) << 32;
    const dsn_grid grids[] = {
        {one / 3, one / 7, int64_t(0.6062 * double(one)), int64_t(0.35 * double(one)),
         -int64_t(0.35 * double(one)), int64_t(0.6062 * double(one))},
        {(int64_t(5) << 32) + 12345, -(int64_t(9) << 32), one / 8, 0, 0, one / 8},
        {-(int64_t(40) << 32) + 777, one / 5, -int64_t(1.7 * double(one)), 0, 0, int64_t(1.7 * double(one))},
        {(int64_t(INT32_MAX) - 20) << 32, (int64_t(INT32_MAX) - 2) << 32, one / 2 + 3, one / 9, -one / 9,
         one / 2 + 3},
        // x constant, 2^-32 texel below the int32 wrap of its start X - 1: moved by 2^-16 it wraps, where a
        // period of 37 makes the sums jump (point by point then); y likewise
        {int64_t((uint64_t(0x80000000u) << 32) | 0xFFFFFFFFu), one / 3, 0, one / 4, 0, one / 4 + 1},
        {one / 3, int64_t((uint64_t(0x80000000u) << 32) | 0xFFFFFFFFu), one / 4, 0, one / 4 + 1, 0},
    };
    size_t differences = 0, splatted = 0;
    for (uint32_t channels : {1u, 3u})
        for (uint32_t bits : {8u, 16u})
            for (bool mapped : {false, true})
                for (uint32_t period : {0u, 37u}) {
                    dsn::AssetFields fields = random_texton_asset(channels, 9, bits, 60 + channels);
                    if (mapped) fields.histogram = gradient_mapping(channels);
                    const auto made = make_noise(fields, 9, 0, period, period);
                    for (const dsn_grid &grid : grids) {
                        const uint32_t width = 150, height = 21;
                        splatted += dsn_continuous_tile_scratch_size(&made->noise, &grid, width, height) != 0;
                        differences +=
                            continuous_tile_differences(made->noise, channels, grid, width, height);
                    }
                }
    MESSAGE("continuous gradient tiles: " << splatted << " grids of 96 splatted");
    CHECK(splatted >= 48);
    CHECK(differences == 0);
}

TEST_CASE("continuous gradient tiles: pixels with an impulse exactly at the edges of their reach") {
    // At the entry edge only the impulse's slope counts (its value is 0), at the other edge neither: a grid
    // tile's runs must cover the first, as the per-point walk does, and read nothing at the second.
    // Axis-aligned (magnified, minified) and rotated grids placed so that an inner pixel lies on an edge
    // along x or y; grey and RGB, 8 and 16 bits.
    const int64_t one = int64_t(1) << 32, radius = 9;
    // column step x, y; row step x, y
    const int64_t steps[][4] = {{one / 8, 0, 0, one / 8},
                                {int64_t(0.6062 * double(one)), int64_t(0.35 * double(one)),
                                 -int64_t(0.35 * double(one)), int64_t(0.6062 * double(one))},
                                {int64_t(1.3 * double(one)), 0, 0, int64_t(1.3 * double(one))}};
    std::mt19937_64 random(71);
    size_t differences = 0, tiles = 0, splatted = 0;
    for (uint32_t channels : {1u, 3u})
        for (uint32_t bits : {8u, 16u}) {
            const auto made =
                make_noise(random_texton_asset(channels, radius, bits, 70 + channels + bits), 13);
            std::vector<int64_t> xs, ys;
            add_entry_edge_points(made->noise, random, 24, &xs, &ys);
            for (size_t k = 0; k < xs.size(); k++)
                for (bool exit : {false, true})
                    for (const auto &grid_steps : steps) {
                        // the point (even k: an edge along x, odd k: along y), or across the reach from it
                        const int64_t across = exit ? 2 * (radius + 1) * one : 0;
                        const dsn_grid grid = grid_through(xs[k] + (k % 2 == 0 ? across : 0),
                                                           ys[k] + (k % 2 == 1 ? across : 0), grid_steps);
                        const uint32_t width = 16, height = 8;
                        splatted += dsn_continuous_tile_scratch_size(&made->noise, &grid, width, height) != 0;
                        differences +=
                            continuous_tile_differences(made->noise, channels, grid, width, height);
                        tiles++;
                    }
        }
    CHECK(tiles == 4 * 24 * 2 * 3);
    CHECK(splatted == tiles);
    CHECK(differences == 0);
}

TEST_CASE("continuous gradient batches: every kernel's, 8 points a group or one by one, are their points") {
    // Points on the 2^-16 grid, a sixth of them beside the int32 wrap of x or y, and (non-periodic noises)
    // as many with an impulse exactly at their reach's entry edge (only its slope is non-zero); the default
    // density and cells past 16 impulses; periodic axes; grey and RGB, 8 bits (the groups) and 16 (one by
    // one); a histogram mapping; a large radius (points with more cells than a group holds, one by one).
    std::mt19937_64 random(29);
    size_t differences = 0;
    for (uint32_t channels : {1u, 3u})
        for (uint32_t bits : {8u, 16u})
            for (uint32_t impacts : {0u, 160u << 16})
                for (uint32_t period : {0u, 45u})
                    for (uint32_t radius : {4u, 40u}) {
                        if (bits == 16 && (impacts != 0 || radius != 4)) continue;
                        dsn::AssetFields fields = random_texton_asset(channels, radius, bits, 70 + channels);
                        if (period != 0 && impacts == 0) fields.histogram = gradient_mapping(channels);
                        const auto made = make_noise(fields, 3, impacts, period, period);
                        std::vector<int64_t> xs, ys;
                        for (int k = 0; k < 203; k++) {
                            // within 128 texels of 0, on the 2^-16 grid (float64 holds them exactly)
                            int64_t x = (int64_t(random()) >> 40) * 65536,
                                    y = (int64_t(random()) >> 40) * 65536;
                            if (k % 6 == 1) x = moved(x, (int64_t(INT32_MAX) - 2) << 32);
                            if (k % 6 == 4) y = moved(y, -((int64_t(INT32_MAX) - 2) << 32));
                            xs.push_back(x), ys.push_back(y);
                        }
                        if (period == 0) add_entry_edge_points(made->noise, random, 406, &xs, &ys);
                        const std::vector<int32_t> expected = gradient_planes(
                            uint32_t(xs.size()), 1, channels,
                            [&](uint32_t i, uint32_t, int32_t *v, int32_t *gx, int32_t *gy) {
                                return dsn_continuous_gradient_fixed(&made->noise, xs[i], ys[i], v, gx, gy);
                            });
                        const ContinuousGradientBatch batch = {made->noise, xs, ys};
                        differences += kernel_tile_differences(made->noise, expected, batch);
                    }
    CHECK(differences == 0);
}

#if DSN_FILTERING
TEST_CASE("filtered gradient tiles: every kernel's are their points, splatted where the value's tile is") {
    // Magnified and axis-aligned grids (level of detail 0, one tap: the continuous gradient's splat), a
    // minified, a rotated and a stretched one (filtered: the taps' grids and their copies moved one step of
    // each level splatted; the stretched one transposed), and on a periodic noise a grid whose move
    // carries x's int32 start across its wrap (point by point); grey and RGB, 8 and 16 bits, with and
    // without a mapping.
    const int64_t one = int64_t(1) << 32;
    const dsn_grid grids[] = {
        {one / 3, one / 7, one / 4, one / 16, -one / 16, one / 4},
        {(int64_t(7) << 32) + 99, -(int64_t(3) << 32), one / 2, 0, 0, one / 2},
        {one / 5, one / 9, 3 * one, 0, 0, 3 * one},
        {one / 3, one / 7, int64_t(1.3 * double(one)), int64_t(0.75 * double(one)),
         -int64_t(0.75 * double(one)), int64_t(1.3 * double(one))},
        {-(int64_t(11) << 32) + 12345, one / 9, 6 * one, one / 5, 0, int64_t(0.8 * double(one))},
        // x constant, 2^-32 texel below the int32 wrap of its start X - 1 (the continuous tiles' seam)
        {int64_t((uint64_t(0x80000000u) << 32) | 0xFFFFFFFFu), one / 3, 0, 2 * one, 0, 3 * one},
    };
    size_t differences = 0, unfiltered = 0, splatted = 0;
    for (uint32_t channels : {1u, 3u})
        for (uint32_t bits : {8u, 16u})
            for (bool mapped : {false, true})
                for (uint32_t period : {0u, 37u}) {
                    if (bits == 16 && (mapped || period != 0)) continue;
                    dsn::AssetFields fields = random_texton_asset(channels, 9, bits, 80 + channels);
                    fields.pyramid = dsn::texton_pyramid(fields);
                    if (mapped) fields.histogram = gradient_mapping(channels);
                    const auto made = make_noise(fields, 4, 0, period, period);
                    for (const dsn_grid &grid : grids) {
                        // the seam's grid with one tap (at its origin; 16 would make short runs there)
                        const uint32_t width = 90, height = 20, max_taps = &grid == &grids[5] ? 1 : 16;
                        dsn_filter_plan plan;
                        const dsn_footprint footprint = {grid.column_step_x, grid.column_step_y,
                                                         grid.row_step_x, grid.row_step_y, max_taps};
                        REQUIRE(dsn_internal_filter_plan(&footprint, made->asset.pyramid_levels, &plan) ==
                                DSN_OK);
                        const bool filtered = !(plan.lod_q8 == 0 && plan.taps == 1);
                        unfiltered += !filtered;
                        splatted += filtered && dsn_filtered_tile_scratch_size(&made->noise, &grid, max_taps,
                                                                               width, height) != 0;
                        differences +=
                            filtered_tile_differences(made->noise, channels, grid, max_taps, width, height);
                    }
                }
    MESSAGE("filtered gradient tiles: " << splatted << " filtered grids whose value tile splats");
    CHECK(unfiltered == 20); // the two magnified grids, ten noises each
    CHECK(splatted >= 20);
    CHECK(differences == 0);
}

TEST_CASE("filtered gradient tiles: pixels with an impulse exactly at the entry edge of a level's reach") {
    // As the continuous tiles (above), at the levels a minified grid reads: one tap, an axis-aligned grid of
    // 1.6 texels per pixel and a rotated one of 2.5, placed so that an inner pixel lies on the entry edge
    // of level 1's or 2's reach along x or y; grey and RGB, 8 bits (whose levels have records).
    const int64_t one = int64_t(1) << 32;
    // column step x, y; row step x, y
    const int64_t steps[][4] = {{int64_t(1.6 * double(one)), 0, 0, int64_t(1.6 * double(one))},
                                {int64_t(2.2 * double(one)), int64_t(1.27 * double(one)),
                                 -int64_t(1.27 * double(one)), int64_t(2.2 * double(one))}};
    std::mt19937_64 random(73);
    size_t differences = 0, splatted_by_step[2] = {0, 0}, tiles = 0;
    for (uint32_t channels : {1u, 3u}) {
        dsn::AssetFields fields = random_texton_asset(channels, 9, 8, 90 + channels);
        fields.pyramid = dsn::texton_pyramid(fields);
        const auto made = make_noise(fields, 6);
        for (uint32_t level = 1; level <= 2; level++) {
            dsn_level info;
            REQUIRE(dsn_asset_level(&made->asset, level, &info) == DSN_OK);
            std::vector<int64_t> xs, ys;
            add_entry_edge_points(made->noise, random, 16, &xs, &ys, level, (info.width - 1) / 2);
            for (size_t k = 0; k < xs.size(); k++)
                for (uint32_t s = 0; s < 2; s++) {
                    const dsn_grid grid = grid_through(xs[k], ys[k], steps[s]);
                    const uint32_t width = 40, height = 8, max_taps = 1;
                    splatted_by_step[s] +=
                        dsn_filtered_tile_scratch_size(&made->noise, &grid, max_taps, width, height) != 0;
                    differences +=
                        filtered_tile_differences(made->noise, channels, grid, max_taps, width, height);
                    tiles++;
                }
        }
    }
    CHECK(tiles == 2 * 2 * 16 * 2);
    CHECK(splatted_by_step[0] == tiles / 2);
    CHECK(splatted_by_step[1] == tiles / 2);
    CHECK(differences == 0);
}

#endif

TEST_CASE("gradient errors: every output zeroed, the value functions' codes") {
    const auto made = make_noise(random_texton_asset(3, 3, 8, 1), 1);
    const dsn_noise &noise = made->noise;
    int32_t out[3] = {7, 7, 7}, dx[3] = {7, 7, 7}, dy[3] = {7, 7, 7};
    CHECK(dsn_continuous_gradient_fixed(&noise, 0, 0, out, dx, nullptr) == DSN_ERR_NULL);
    CHECK((out[0] == 0 && out[2] == 0 && dx[0] == 0 && dx[2] == 0));
    for (int c = 0; c < 3; c++) out[c] = dx[c] = dy[c] = 7;
    CHECK(dsn_lattice_gradient_fixed(nullptr, 0, 0, out, dx, dy) == DSN_ERR_NULL);
    CHECK((out[0] == 0 && dx[0] == 0 && dy[0] == 0 && out[1] == 7)); // one value: the channels are unknown
    dsn_noise zeroed{};
    CHECK(dsn_continuous_gradient_fixed(&zeroed, 0, 0, out, dx, dy) == DSN_ERR_NULL);

    dsn::AssetFields lattice_fields = random_texton_asset(1, 3, 8, 1);
    lattice_fields.interpolation = DSN_INTERPOLATION_LATTICE;
    const auto lattice = make_noise(lattice_fields, 1);
    dx[0] = 7;
    CHECK(dsn_continuous_gradient_fixed(&lattice->noise, 0, 0, out, dx, dy) == DSN_ERR_CONTINUOUS_MISMATCH);
    CHECK(dx[0] == 0);
    CHECK(dsn_lattice_gradient_fixed(&lattice->noise, 0, 0, out, dx, dy) == DSN_OK);

    std::vector<int32_t> tile(12, 5);
    CHECK(dsn_lattice_tile_gradient_fixed(&noise, 0, 0, 0, 4, tile.data(), tile.data(), tile.data()) ==
          DSN_ERR_TILE_SIZE);
    CHECK(tile[0] == 5); // a size refused is not written
    const dsn_grid grid = {0, 0, 1 << 30, 0, 0, 1 << 30};
    std::vector<float> values(12, 5.0f), slopes(12, 5.0f);
    CHECK(dsn_continuous_tile_gradient_float(&noise, &grid, 2, 2, values.data(), slopes.data(), nullptr) ==
          DSN_ERR_NULL);
    CHECK((values[11] == 0.0f && slopes[11] == 0.0f));
    CHECK(dsn_continuous_batch_gradient_fixed(&noise, nullptr, nullptr, 0, nullptr, nullptr, nullptr) ==
          DSN_OK);
}

namespace {

// A bilinear asset with its baked pyramid (filtered evaluation).
dsn::AssetFields pyramid_asset(uint32_t channels, uint32_t bits) {
    dsn::AssetFields fields = random_texton_asset(channels, 8, bits, 31);
    fields.pyramid = dsn::texton_pyramid(fields);
    return fields;
}

dsn_footprint footprint_of(int64_t column_x, int64_t column_y, int64_t row_x, int64_t row_y, uint32_t taps) {
    const dsn_footprint footprint = {column_x, column_y, row_x, row_y, taps};
    return footprint;
}

} // namespace

TEST_CASE("filtered gradient: the filtered value, the continuous gradient unfiltered, no slope faded") {
    const int64_t one = int64_t(1) << 32;
    const dsn_footprint footprints[] = {
        footprint_of(3 * one, one / 2, -one / 2, 3 * one, 1),      // isotropic, level of detail about 1.6
        footprint_of(2 * one, 0, 0, 2 * one, 1),                   // exactly level 1
        footprint_of(12 * one, 5 * one, one / 2, -3 * one / 2, 8), // anisotropic, several taps
        footprint_of(one / 2, 0, 0, one / 2, 16),                  // unfiltered
        footprint_of(INT64_MAX / 3, 0, 0, INT64_MAX / 3, 1),       // the mean colour
    };
    for (uint32_t channels : {1u, 3u})
        for (uint32_t bits : {8u, 16u}) {
            const auto made = make_noise(pyramid_asset(channels, bits), 3);
            const dsn_noise &noise = made->noise;
            std::vector<int64_t> xs, ys;
            renderer_points(23, 12, &xs, &ys);
            for (const dsn_footprint &footprint : footprints)
                for (size_t p = 0; p < xs.size(); p++) {
                    int32_t value[3], dx[3], dy[3], expected[3], gradient[3][3];
                    REQUIRE(dsn_filtered_gradient_fixed(&noise, xs[p], ys[p], &footprint, value, dx, dy) ==
                            DSN_OK);
                    REQUIRE(dsn_filtered_point_fixed(&noise, xs[p], ys[p], &footprint, expected) == DSN_OK);
                    int32_t lod = 0;
                    uint32_t taps = 0;
                    REQUIRE(dsn_filter_level(&noise, &footprint, &lod, &taps) == DSN_OK);
                    const bool faded = uint32_t(lod) >> 8 > dsn_state(&noise)->asset.pyramid_levels;
                    if (lod == 0 && taps == 1)
                        REQUIRE(dsn_continuous_gradient_fixed(&noise, xs[p], ys[p], gradient[0], gradient[1],
                                                              gradient[2]) == DSN_OK);
                    for (uint32_t c = 0; c < channels; c++) {
                        CHECK(value[c] == expected[c]);
                        if (faded) CHECK((dx[c] == 0 && dy[c] == 0));
                        if (lod == 0 && taps == 1)
                            CHECK((dx[c] == gradient[1][c] && dy[c] == gradient[2][c]));
                    }
                }
        }
}

TEST_CASE("filtered gradient: each level's sums step by its slopes, one weight step of the level at a time") {
    const int64_t one = int64_t(1) << 32;
    const auto made = make_noise(pyramid_asset(3, 8), 5);
    const dsn_noise_state *noise = dsn_state(&made->noise);
    const dsn_footprint footprint = footprint_of(5 * one, one, -one, 5 * one / 2, 4);
    dsn_filter_plan plan;
    REQUIRE(dsn_internal_filter_plan(&footprint, noise->asset.pyramid_levels, &plan) == DSN_OK);
    dsn_walked_level walked[2];
    const uint32_t count = dsn_internal_filter_walked_levels(noise, &plan, walked);
    REQUIRE(count == 2);
    std::vector<int64_t> xs, ys;
    renderer_points(29, 40, &xs, &ys);
    int sloped = 0;
    for (size_t p = 0; p < xs.size(); p++) {
        static dsn_filter_sums sums, east, south;
        static dsn_filter_slopes slopes, unused;
        dsn_internal_filter_slopes_walked(noise, uint64_t(xs[p]), uint64_t(ys[p]), &plan, walked, count, sums,
                                          &slopes);
        for (uint32_t l = 0; l < count; l++) {
            // a weight step of level l, 2^-8 of its texels, is 2^(level + 24) in Q32.32
            const int64_t level_step = int64_t(1) << (24 + walked[l].level);
            dsn_internal_filter_slopes_walked(noise, uint64_t(moved(xs[p], level_step)), uint64_t(ys[p]),
                                              &plan, walked, count, east, &unused);
            dsn_internal_filter_slopes_walked(noise, uint64_t(xs[p]), uint64_t(moved(ys[p], level_step)),
                                              &plan, walked, count, south, &unused);
            for (uint32_t tap = 0; tap < plan.taps; tap++)
                for (uint32_t c = 0; c < 3; c++) {
                    CHECK(east[tap][l][c] - sums[tap][l][c] == step_slopes * slopes[tap][l][0][c]);
                    CHECK(south[tap][l][c] - sums[tap][l][c] == step_slopes * slopes[tap][l][1][c]);
                    sloped += slopes[tap][l][0][c] != 0;
                }
        }
    }
    CHECK(sloped > 100);
}

namespace {

// The filtered gradient as first defined (the fast build's before it took its slopes from sifted walks of
// moved taps): the tap-by-tap walk's sums and slopes, normalized per level, blended, rounded, and the
// histogram mapping's chain rule.
void walked_filtered_gradient(const dsn_noise_state *noise, uint64_t x, uint64_t y,
                              const dsn_filter_plan *plan, int32_t *values) {
    int32_t *dx = values + DSN_MAX_CHANNELS, *dy = values + 2 * DSN_MAX_CHANNELS;
    for (uint32_t c = 0; c < DSN_MAX_CHANNELS; c++) dx[c] = dy[c] = 0;
    if (dsn_internal_filter_fade(noise, plan, values)) return;
    if (plan->lod_q8 == 0 && plan->taps == 1) {
        dsn_internal_continuous_gradient(noise, x, y, values);
        return;
    }
    dsn_walked_level walked[2];
    const uint32_t count = dsn_internal_filter_walked_levels(noise, plan, walked);
    static dsn_filter_sums sums;
    static dsn_filter_slopes slopes;
    dsn_internal_filter_slopes_walked(noise, x, y, plan, walked, count, sums, &slopes);
    int64_t totals[3][DSN_MAX_CHANNELS] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    for (uint32_t tap = 0; tap < plan->taps; tap++) {
        for (uint32_t l = 0; l < count; l++) {
            int64_t level[3][DSN_MAX_CHANNELS] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
            dsn_internal_filter_level_values(noise, &walked[l], sums[tap][l], level[0]);
            dsn_internal_filter_level_slopes(noise, &walked[l], slopes[tap][l][0], level[1]);
            dsn_internal_filter_level_slopes(noise, &walked[l], slopes[tap][l][1], level[2]);
            for (uint32_t output = 0; output < 3; output++)
                dsn_internal_filter_add_level(noise, plan, l, level[output], totals[output]);
        }
        if (count == 1) dsn_internal_filter_add_mean(noise, plan, totals[0]);
    }
    for (uint32_t output = 0; output < 3; output++)
        dsn_internal_filter_round(noise, plan, totals[output], values + output * DSN_MAX_CHANNELS);
    if (noise->asset.histogram_table != 0) {
        const uint32_t level = uint32_t(plan->lod_q8) >> 8, blend = plan->lod_q8 & 255;
        dsn_internal_histogram_map_gradient(&noise->asset, values, level, blend, dx, dy);
        dsn_internal_histogram_map(&noise->asset, values, level, blend);
    }
}

// A mapping of two levels (the filtered evaluation blends their tables), the second moved up.
dsn::HistogramMapping two_level_mapping(uint32_t channels) {
    dsn::HistogramMapping m = gradient_mapping(channels);
    const size_t one_level = m.tables.size();
    m.level_count = 2;
    for (size_t i = 0; i < one_level; i++) m.tables.push_back(m.tables[i] + 300);
    return m;
}

} // namespace

TEST_CASE("filtered gradient: every kernel's equals the tap-by-tap walk's definition, bit for bit") {
    // Isotropic footprints from unfiltered past the coarsest level (the fade), rotated and anisotropic ones
    // of 2 .. 16 taps, at points across the torus and the int32 wraps (where the sift's moved taps cross
    // the walk's seam); grey and RGB, 8 and 16 bits, a
    // two-level histogram mapping, periods (one shorter than a coarse level's reach).
    const int64_t one = int64_t(1) << 32;
    std::vector<dsn_footprint> footprints;
    for (int eighth = 0; eighth <= 8 * 6; eighth += 3) {
        const double side = std::pow(2.0, eighth / 8.0), angle = 0.37 * eighth;
        footprints.push_back(footprint_of(int64_t(side * std::cos(angle) * double(one)),
                                          int64_t(side * std::sin(angle) * double(one)),
                                          -int64_t(side * std::sin(angle) * double(one)),
                                          int64_t(side * std::cos(angle) * double(one)), 1));
    }
    footprints.push_back(footprint_of(12 * one, 5 * one, one / 2, -3 * one / 2, 8));
    footprints.push_back(footprint_of(3 * one, -one, one / 3, one, 2));
    footprints.push_back(footprint_of(-20 * one, 9 * one, one, 2 * one, 16));
    footprints.push_back(footprint_of(2 * one, 7 * one, -one / 2, one / 7, 4));
    footprints.push_back(footprint_of(40 * one, 0, 0, 3 * one, 16));
    size_t compared = 0, sloped = 0;
    for (uint32_t channels : {1u, 3u})
        for (uint32_t bits : {8u, 16u})
            for (bool mapped : {false, true})
                for (uint32_t period : {0u, 13u, 300u}) {
                    dsn::AssetFields fields = pyramid_asset(channels, bits);
                    if (mapped) fields.histogram = two_level_mapping(channels);
                    const auto made = make_noise(fields, 7 + period, 0, period, period == 13 ? 0 : period);
                    const dsn_noise_state *state = dsn_state(&made->noise);
                    std::vector<int64_t> xs, ys;
                    renderer_points(41 + period, 10, &xs, &ys);
                    // A step of a level from the point moves the walk's int32 start, X - 1, across its wrap.
                    const int64_t seam = int64_t((uint64_t(0x80000000u) << 32) | 0xFFFFFF00u);
                    xs.push_back(seam), ys.push_back(int64_t(777) << 30);
                    xs.push_back(-(int64_t(5) << 29)), ys.push_back(seam);
                    for (uint32_t kernel = DSN_KERNEL_DEFAULT; kernel <= state->tile_kernel; kernel++) {
                        dsn_noise copy = made->noise;
                        dsn_state(&copy)->tile_kernel = kernel;
                        for (const dsn_footprint &footprint : footprints)
                            for (size_t p = 0; p < xs.size(); p++) {
                                INFO("channels " << channels << " bits " << bits << " mapped " << mapped
                                                 << " period " << period << " kernel " << kernel << " at "
                                                 << xs[p] << ", " << ys[p]);
                                dsn_filter_plan plan;
                                REQUIRE(dsn_internal_filter_plan(&footprint, state->asset.pyramid_levels,
                                                                 &plan) == DSN_OK);
                                int32_t value[3], dx[3], dy[3], expected[3 * DSN_MAX_CHANNELS];
                                REQUIRE(dsn_filtered_gradient_fixed(&copy, xs[p], ys[p], &footprint, value,
                                                                    dx, dy) == DSN_OK);
                                walked_filtered_gradient(dsn_state(&copy), uint64_t(xs[p]), uint64_t(ys[p]),
                                                         &plan, expected);
                                for (uint32_t c = 0; c < channels; c++) {
                                    CHECK(value[c] == expected[c]);
                                    CHECK(dx[c] == expected[DSN_MAX_CHANNELS + c]);
                                    CHECK(dy[c] == expected[2 * DSN_MAX_CHANNELS + c]);
                                    sloped += dx[c] != 0 && dy[c] != 0;
                                }
                                compared++;
                            }
                    }
                }
    CHECK(compared >= 24 * footprints.size() * 12);
    CHECK(sloped > compared / 2);
}

TEST_CASE(
    "filtered gradient: points exactly at the entry edge of a level's reach, every kernel's as the walk's") {
    // Points placed so that an impulse lies exactly at the entry edge of level 1's or 2's reach along x or y
    // (its value there 0, its slope not), read through footprints whose levels include that level, one tap
    // and several; grey and RGB, 8 bits (whose levels the vector kernels read with their slopes).
    const int64_t one = int64_t(1) << 32;
    const std::vector<dsn_footprint> footprints = {
        footprint_of(2 * one, 0, 0, 2 * one, 1),                   // level 1 (blended with none)
        footprint_of(3 * one, one / 2, -one / 2, 3 * one, 1),      // levels 1 and 2
        footprint_of(5 * one, 0, 0, 5 * one, 1),                   // levels 2 and 3
        footprint_of(12 * one, 5 * one, one / 2, -3 * one / 2, 8), // anisotropic, levels 1 and 2
    };
    std::mt19937_64 random(79);
    size_t compared = 0, sloped = 0;
    for (uint32_t channels : {1u, 3u}) {
        dsn::AssetFields fields = random_texton_asset(channels, 9, 8, 95 + channels);
        fields.pyramid = dsn::texton_pyramid(fields);
        const auto made = make_noise(fields, 6);
        const dsn_noise_state *state = dsn_state(&made->noise);
        for (uint32_t level = 1; level <= 2; level++) {
            dsn_level info;
            REQUIRE(dsn_asset_level(&made->asset, level, &info) == DSN_OK);
            std::vector<int64_t> xs, ys;
            add_entry_edge_points(made->noise, random, 24, &xs, &ys, level, (info.width - 1) / 2);
            for (uint32_t kernel = DSN_KERNEL_DEFAULT; kernel <= state->tile_kernel; kernel++) {
                dsn_noise copy = made->noise;
                dsn_state(&copy)->tile_kernel = kernel;
                for (const dsn_footprint &footprint : footprints)
                    for (size_t p = 0; p < xs.size(); p++) {
                        INFO("channels " << channels << " level " << level << " kernel " << kernel << " at "
                                         << xs[p] << ", " << ys[p]);
                        dsn_filter_plan plan;
                        REQUIRE(dsn_internal_filter_plan(&footprint, state->asset.pyramid_levels, &plan) ==
                                DSN_OK);
                        int32_t value[3], dx[3], dy[3], expected[3 * DSN_MAX_CHANNELS];
                        REQUIRE(dsn_filtered_gradient_fixed(&copy, xs[p], ys[p], &footprint, value, dx, dy) ==
                                DSN_OK);
                        walked_filtered_gradient(dsn_state(&copy), uint64_t(xs[p]), uint64_t(ys[p]), &plan,
                                                 expected);
                        for (uint32_t c = 0; c < channels; c++) {
                            CHECK(value[c] == expected[c]);
                            CHECK(dx[c] == expected[DSN_MAX_CHANNELS + c]);
                            CHECK(dy[c] == expected[2 * DSN_MAX_CHANNELS + c]);
                            sloped += dx[c] != 0 || dy[c] != 0;
                        }
                        compared++;
                    }
            }
        }
    }
    CHECK(compared >= 2 * 2 * 24 * footprints.size());
    CHECK(sloped > compared / 2);
}

namespace {

// Sample statistics of a series: mean, variance and excess kurtosis.
struct Moments {
    double mean = 0, variance = 0, kurtosis = 0;
};

Moments moments_of(const std::vector<double> &values) {
    Moments m;
    for (double v : values) m.mean += v;
    m.mean /= double(values.size());
    double second = 0, fourth = 0;
    for (double v : values) {
        const double d = (v - m.mean) * (v - m.mean);
        second += d, fourth += d * d;
    }
    m.variance = second / double(values.size());
    m.kurtosis = fourth / double(values.size()) / (m.variance * m.variance) - 3;
    return m;
}

// The relative standard deviation of the ratio of two sample variances of `count` points, from their
// excess kurtoses (the variance of a sample variance is (2 + kurtosis) sigma^4 / count), taken as
// independent: a bound, since the two are positively correlated.
double ratio_deviation(const Moments &a, const Moments &b, size_t count) {
    return std::sqrt((2 + a.kurtosis + 2 + b.kurtosis) / double(count));
}

} // namespace

TEST_CASE("gradient statistics: the derivatives' variance over the value's is the texton's, by theory") {
    // F = sum_i t(x - x_i) over a Poisson process: Var F = lambda integral t^2, and its derivative is the
    // spot noise of the texton's derivative, Var dF/dx = lambda integral (dt/dx)^2; the ratio needs no gain
    // or density. Continuous: t the bilinear interpolant, integral t^2 = sum t[a] t[b] B(bx - ax) B(by - ay)
    // and integral (dt/dx)^2 = sum t[a] t[b] A(bx - ax) B(by - ay), B the cubic B-spline (the tent's
    // autocorrelation: 2/3, 1/6) and A the tent derivative's (2, -1). Lattice: sum (t(p + 1) - t(p))^2 over
    // sum t(p)^2. Points a texton apart (independent), with deterministic sub-texel offsets.
    const uint32_t radius = 6, side = 2 * radius + 1;
    const dsn::AssetFields fields = random_texton_asset(1, radius, 8, 77);
    const std::vector<double> t = texton_values(fields)[0];
    auto at = [&](int x, int y) {
        return x < 0 || y < 0 || x >= int(side) || y >= int(side) ? 0.0 : t[size_t(y * int(side) + x)];
    };
    const double tent_derivative[3] = {-1, 2, -1};
    double value_theory = 0, slope_theory = 0, slope_theory_y = 0, lattice_value = 0, lattice_slope = 0;
    for (int ay = 0; ay < int(side); ay++)
        for (int ax = 0; ax < int(side); ax++)
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    const double product = at(ax, ay) * at(ax + dx, ay + dy);
                    value_theory += product * cubic_bspline(dx) * cubic_bspline(dy);
                    slope_theory += product * tent_derivative[dx + 1] * cubic_bspline(dy);
                    slope_theory_y += product * cubic_bspline(dx) * tent_derivative[dy + 1];
                }
    for (int y = -1; y <= int(side); y++)
        for (int x = -1; x <= int(side); x++) {
            lattice_value += at(x, y) * at(x, y);
            lattice_slope += (at(x + 1, y) - at(x, y)) * (at(x + 1, y) - at(x, y));
        }
    const auto made = make_noise(fields, 2024);
    const dsn_noise &noise = made->noise;
    std::mt19937 random(5);
    const size_t count = 40000;
    std::vector<double> values, slopes_x, slopes_y, lattice_values, lattice_slopes;
    for (size_t k = 0; k < count; k++) {
        const int64_t cell_x = int64_t(k % 200) * (side + 2), cell_y = int64_t(k / 200) * (side + 2);
        const int64_t x = (cell_x << 32) + int64_t(random()), y = (cell_y << 32) + int64_t(random());
        int32_t value[1], dx[1], dy[1];
        REQUIRE(dsn_continuous_gradient_fixed(&noise, x, y, value, dx, dy) == DSN_OK);
        values.push_back(value[0]), slopes_x.push_back(dx[0]), slopes_y.push_back(dy[0]);
        REQUIRE(dsn_lattice_gradient_fixed(&noise, int32_t(cell_x), int32_t(cell_y), value, dx, dy) ==
                DSN_OK);
        lattice_values.push_back(value[0]), lattice_slopes.push_back(dx[0]);
    }
    const Moments value = moments_of(values), along_x = moments_of(slopes_x), along_y = moments_of(slopes_y);
    const Moments lattice = moments_of(lattice_values), lattice_x = moments_of(lattice_slopes);
    const double ratio_x = along_x.variance / value.variance, ratio_y = along_y.variance / value.variance;
    const double expected = slope_theory / value_theory, lattice_expected = lattice_slope / lattice_value;
    const double tolerance = 5 * ratio_deviation(along_x, value, count);
    MESSAGE("continuous: var dx / var F " << ratio_x << ", dy " << ratio_y << " (theory " << expected
                                          << ", tolerance " << tolerance << ")");
    CHECK(std::fabs(ratio_x / expected - 1) < tolerance);
    CHECK(std::fabs(ratio_y / (slope_theory_y / value_theory) - 1) <
          5 * ratio_deviation(along_y, value, count));
    const double lattice_ratio = lattice_x.variance / lattice.variance;
    MESSAGE("lattice: var dx / var F " << lattice_ratio << " (theory " << lattice_expected << ")");
    CHECK(std::fabs(lattice_ratio / lattice_expected - 1) < 5 * ratio_deviation(lattice_x, lattice, count));
    // the derivatives have mean zero: within 5 standard errors
    CHECK(std::fabs(along_x.mean) < 5 * std::sqrt(along_x.variance / double(count)));
    CHECK(std::fabs(along_y.mean) < 5 * std::sqrt(along_y.variance / double(count)));
}
