// filtered_sift_test.cpp - the fast build's filtered sums (every tap and both levels from one sifted walk,
// runtime/evaluators/filtered_sift.cpp) against the tap-by-tap walk (runtime/evaluators/filtered_walk.cpp),
// bit for bit: the sums of every tap and level and the points' values, over 8- and 16-bit, grey and RGB
// assets, with and without a pyramid, periodic (periods shorter than a level's reach included) or not, for
// isotropic footprints across every level of detail and anisotropic ones of every tap count and direction, at
// ordinary points and where the taps straddle the seam of the int32 coordinates; and the levels read with
// their all-zero margins cut (a shorter reach) against the levels as stored; cells of every side the
// kernels' listing takes or leaves; in every kernel copy the CPU runs. And the listing alone (make bench's)
// lists at least the impulses that the walk reads. And the gradient's sums and slopes from the sifted
// walks of moved taps against the walk's.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "fixtures/test_assets.h"
#include "offline/bake_internal.h"
#include "runtime/core/filtered_internal.h"
#include "runtime/kernels/kernels.h"

using namespace dsn_test;

#if DSN_FILTERING && !DSN_SMALL_CODE

namespace {

int64_t q32(double texels) { return int64_t(std::floor(texels * 4294967296.0)); }

dsn_footprint slanted(double minor, double ratio, double angle, uint32_t max_taps) {
    const double c = std::cos(angle), s = std::sin(angle), major = minor * ratio;
    return dsn_footprint{q32(major * c), q32(major * s), q32(-minor * s), q32(minor * c), max_taps};
}

// The footprints compared: isotropic in 1/8 steps of level of detail up to the mean, rotated, and
// anisotropic of ratios 1.5 .. 40 with every tap count.
std::vector<dsn_footprint> footprints(TestRandom &random) {
    std::vector<dsn_footprint> list;
    for (int eighth = 0; eighth <= 8 * 7; eighth++) {
        const double side = std::pow(2.0, eighth / 8.0), angle = random.next() / 4294967296.0 * 6.2832;
        list.push_back(slanted(side, 1, angle, 1));
    }
    for (double minor : {0.4, 1.0, 2.0, 3.3, 8.0})
        for (double ratio : {1.5, 2.0, 4.0, 7.0, 16.0, 40.0})
            for (uint32_t max_taps : {2u, 4u, 16u}) {
                const double angle = random.next() / 4294967296.0 * 6.2832;
                list.push_back(slanted(minor, ratio, angle, max_taps));
            }
    return list;
}

// The listing alone (dsn_internal_filter_listing_only, make bench's) lists every impulse within reach of
// every tap's level: as many as the walk's reads of levels whose values are all 1, each of which adds at
// most 2^32 (the bilinear weights of an interior read sum to 2^32; a border read's to less).
void check_listing(const dsn_noise_state &state, uint64_t x, uint64_t y, const dsn_filter_plan &plan,
                   const dsn_walked_level *levels, uint32_t count) {
    const uint32_t bytes = state.asset.bits / 8;
    dsn_walked_level ones[2];
    std::vector<unsigned char> values[2];
    for (uint32_t l = 0; l < count; l++) {
        ones[l] = levels[l];
        values[l].assign((levels[l].width * levels[l].height * state.asset.channels + 8) * bytes, 0);
        for (size_t i = 0; i < values[l].size(); i += bytes) values[l][i] = 1; // 1 in i8 and in i16le
        ones[l].values = values[l].data();
        ones[l].stride = levels[l].width;
    }
    dsn_filter_sums reads;
    dsn_internal_filter_sums_walked(&state, x, y, &plan, ones, count, reads);
    const uint64_t listed = dsn_internal_filter_listing_only(&state, x, y, &plan, levels, count);
    for (uint32_t t = 0; t < plan.taps; t++)
        for (uint32_t l = 0; l < count; l++) REQUIRE(reads[t][l][0] <= listed << 32);
}

// Compares the sums and the values of one point under one footprint; counts the comparisons made.
void compare_point(const dsn_noise &noise, int64_t x, int64_t y, const dsn_footprint &f, size_t *compared) {
    const dsn_noise_state *state = dsn_state(&noise);
    dsn_filter_plan plan;
    REQUIRE(dsn_internal_filter_plan(&f, state->asset.pyramid_levels, &plan) == DSN_OK);
    const uint32_t lower = uint32_t(plan.lod_q8) >> 8;
    if (lower <= state->asset.pyramid_levels) {
        // The levels as stored, and as the evaluation reads them (their all-zero margins cut).
        dsn_walked_level stored_levels[2], cut_levels[2];
        uint32_t count = 0;
        for (uint32_t l = lower; l <= lower + 1 && l <= state->asset.pyramid_levels; l++) {
            dsn_level stored;
            REQUIRE(dsn_asset_level(&state->asset, l, &stored) == DSN_OK);
            stored_levels[count] = dsn_walked_level{stored.values,
                                                    stored.width,
                                                    stored.height,
                                                    stored.width,
                                                    (stored.width - 1) / 2,
                                                    (stored.height - 1) / 2,
                                                    l,
                                                    stored.exponent};
            cut_levels[count++] = dsn_internal_walked_level(state, l);
        }
        dsn_filter_sums walked, sifted, walked_cut, sifted_cut;
        std::memset(sifted, 0xA5, sizeof sifted); // every sum must be written
        std::memset(sifted_cut, 0xA5, sizeof sifted_cut);
        dsn_internal_filter_sums_walked(state, uint64_t(x), uint64_t(y), &plan, stored_levels, count, walked);
        dsn_internal_filter_sums_sifted(state, uint64_t(x), uint64_t(y), &plan, stored_levels, count, sifted);
        dsn_internal_filter_sums_walked(state, uint64_t(x), uint64_t(y), &plan, cut_levels, count,
                                        walked_cut);
        dsn_internal_filter_sums_sifted(state, uint64_t(x), uint64_t(y), &plan, cut_levels, count,
                                        sifted_cut);
        for (uint32_t t = 0; t < plan.taps; t++)
            for (uint32_t l = 0; l < count; l++)
                for (uint32_t c = 0; c < state->asset.channels; c++) {
                    INFO("tap " << t << " level " << stored_levels[l].level << " channel " << c << " LOD q8 "
                                << plan.lod_q8 << " taps " << plan.taps << " at " << x << ", " << y);
                    REQUIRE(sifted[t][l][c] == walked[t][l][c]);
                    REQUIRE(walked_cut[t][l][c] == walked[t][l][c]);
                    REQUIRE(sifted_cut[t][l][c] == walked[t][l][c]);
                }
        check_listing(*state, uint64_t(x), uint64_t(y), plan, cut_levels, count);
#if DSN_GRADIENTS
        // The gradient's sums and slopes: each tap's moved copies summed by the sift against the walk's
        // slopes, on the levels as stored and as read.
        for (const dsn_walked_level *levels : {&stored_levels[0], &cut_levels[0]}) {
            static dsn_filter_sums walked_sums, sifted_sums;
            static dsn_filter_slopes walked_slopes, sifted_slopes;
            std::memset(sifted_sums, 0xA5, sizeof sifted_sums);
            std::memset(sifted_slopes, 0xA5, sizeof sifted_slopes);
            dsn_internal_filter_slopes_walked(state, uint64_t(x), uint64_t(y), &plan, levels, count,
                                              walked_sums, &walked_slopes);
            dsn_internal_filter_slopes_sifted(state, uint64_t(x), uint64_t(y), &plan, levels, count,
                                              sifted_sums, &sifted_slopes);
            for (uint32_t t = 0; t < plan.taps; t++)
                for (uint32_t l = 0; l < count; l++)
                    for (uint32_t c = 0; c < state->asset.channels; c++) {
                        INFO("slopes: tap " << t << " level " << levels[l].level << " channel " << c
                                            << " LOD q8 " << plan.lod_q8 << " taps " << plan.taps << " at "
                                            << x << ", " << y);
                        REQUIRE(sifted_sums[t][l][c] == walked_sums[t][l][c]);
                        REQUIRE(sifted_slopes[t][l][0][c] == walked_slopes[t][l][0][c]);
                        REQUIRE(sifted_slopes[t][l][1][c] == walked_slopes[t][l][1][c]);
                    }
        }
#endif
    }
    int32_t reference[3] = {0, 0, 0}, fast[3] = {0, 0, 0};
    dsn_internal_filtered_point_walked(state, uint64_t(x), uint64_t(y), &plan, reference);
    dsn_internal_filtered_point(state, uint64_t(x), uint64_t(y), &plan, fast);
    for (uint32_t c = 0; c < state->asset.channels; c++) REQUIRE(fast[c] == reference[c]);
    ++*compared;
}

// The number of levels of the noise whose window the evaluation cuts (all-zero margins).
uint32_t cut_levels(const dsn_noise &noise) {
    const dsn_noise_state *state = dsn_state(&noise);
    uint32_t cut = 0;
    for (uint32_t l = 0; l <= state->asset.pyramid_levels; l++) {
        dsn_level stored;
        REQUIRE(dsn_asset_level(&state->asset, l, &stored) == DSN_OK);
        const dsn_walked_level read = dsn_internal_walked_level(state, l);
        REQUIRE(read.radius_x <= (stored.width - 1) / 2);
        REQUIRE(read.radius_y <= (stored.height - 1) / 2);
        cut += read.width < stored.width || read.height < stored.height ? 1 : 0;
    }
    return cut;
}

void compare_noise_in_kernel(const dsn_noise &noise, uint64_t seed) {
    TestRandom random(seed);
    const std::vector<dsn_footprint> list = footprints(random);
    size_t compared = 0;
    for (const dsn_footprint &f : list)
        for (int i = 0; i < 3; i++) {
            const int64_t x = q32(random.range(-100000, 100000) + random.next() / 4294967296.0);
            const int64_t y = q32(random.range(-100000, 100000) + random.next() / 4294967296.0);
            compare_point(noise, x, y, f, &compared);
        }
    // Around the int32 seam of the coordinates (the taps on both sides of it) and at the int64 ends.
    const int64_t top = INT64_MAX, bottom = INT64_MIN;
    const int64_t seams[][2] = {{top - q32(3.7), q32(5.2)},
                                {bottom + q32(2.1), top - q32(1.5)},
                                {q32(-0.3), bottom + q32(40.25)},
                                {top, bottom}};
    for (const dsn_footprint &f : list)
        for (const auto &point : seams) compare_point(noise, point[0], point[1], f, &compared);
    CHECK(compared == list.size() * 7);
}

// Every kernel copy this CPU runs (the vector reads of 8-bit levels in the AVX2 and AVX-512 ones).
void compare_noise(const dsn_noise &noise, uint64_t seed) {
    for (uint32_t kernel = DSN_KERNEL_DEFAULT; kernel <= dsn_state(&noise)->tile_kernel; kernel++) {
        CAPTURE(kernel);
        dsn_noise copy = noise;
        dsn_state(&copy)->tile_kernel = kernel;
        compare_noise_in_kernel(copy, seed);
    }
}

} // namespace

TEST_CASE("filtered sift: every tap and level summed at once equals the tap-by-tap walk, bit for bit") {
    uint64_t seed = 1;
    uint32_t cut = 0;
    for (uint32_t channels : {1u, 3u})
        for (uint32_t bits : {8u, 16u}) {
            dsn::AssetFields fields = synthetic_fields(channels, 31, bits, DSN_SHAPE_RECTANGLE, 40 + seed);
            fields.interpolation = DSN_INTERPOLATION_BILINEAR;
            fields.pyramid = dsn::texton_pyramid(fields);
            // Periods: none; one shorter than the coarsest level's reach on x; long ones on both axes.
            const uint32_t periods[][2] = {{0, 0}, {37, 0}, {0, 23}, {1000, 777}};
            for (const auto &period : periods) {
                INFO("channels " << channels << " bits " << bits << " period " << period[0] << " x "
                                 << period[1]);
                LoadedNoise loaded(fields, make_config(uint32_t(seed), 30, period[0], period[1]));
                compare_noise(loaded.noise, seed++);
                cut += cut_levels(loaded.noise);
            }
        }
    CHECK(cut > 0); // the baker's levels keep all-zero margins of their spill: cut ones were compared
}

TEST_CASE("filtered sift: a disk texton, an asset without a pyramid and a sparse noise") {
    uint64_t seed = 100;
    dsn::AssetFields disk = synthetic_fields(3, 23, 8, DSN_SHAPE_DISK, 7);
    disk.interpolation = DSN_INTERPOLATION_BILINEAR;
    disk.pyramid = dsn::texton_pyramid(disk);
    LoadedNoise disk_noise(disk, make_config(3, 5));
    compare_noise(disk_noise.noise, seed++);

    dsn::AssetFields plain = synthetic_fields(1, 15, 8, DSN_SHAPE_RECTANGLE, 8);
    plain.interpolation = DSN_INTERPOLATION_BILINEAR;
    LoadedNoise plain_noise(plain, make_config(4, 60));
    REQUIRE(plain_noise.asset.pyramid_levels == 0);
    compare_noise(plain_noise.noise, seed++);
}

// The kernels list the candidates of cells of side <= 16, 16 columns of cells at a time: small cells (the
// long footprints' boxes then span several such batches) and large ones (listed candidate by candidate,
// read by the kernels' vector reads).
TEST_CASE("filtered sift: cells of side 4 and 32") {
    uint64_t seed = 200;
    for (uint32_t channels : {1u, 3u}) {
        dsn::AssetFields small = synthetic_fields(channels, 7, 8, DSN_SHAPE_RECTANGLE, 9 + channels);
        small.interpolation = DSN_INTERPOLATION_BILINEAR;
        small.pyramid = dsn::texton_pyramid(small);
        LoadedNoise small_noise(small, make_config(5, 30));
        REQUIRE(dsn_state(&small_noise.noise)->cell_shift == 2);
        compare_noise(small_noise.noise, seed++);
    }
    dsn::AssetFields large = synthetic_fields(3, 31, 8, DSN_SHAPE_RECTANGLE, 12);
    large.interpolation = DSN_INTERPOLATION_BILINEAR;
    large.pyramid = dsn::texton_pyramid(large);
    LoadedNoise large_noise(large, make_config(6, 1));
    REQUIRE(dsn_state(&large_noise.noise)->cell_shift == 5);
    compare_noise(large_noise.noise, seed++);
}

// The kernels list 32-bit offsets (1/65536 texel) for boxes of up to 4096 texels along each axis, and the
// 64-bit ones beyond: plans (not reachable from a footprint below the mean colour's level of detail) whose
// two taps lie 1000 .. 100000 texels apart, at both levels of a half level.
TEST_CASE("filtered sift: taps thousands of texels apart") {
    for (uint32_t channels : {1u, 3u}) {
        dsn::AssetFields fields = synthetic_fields(channels, 15, 8, DSN_SHAPE_RECTANGLE, 20 + channels);
        fields.interpolation = DSN_INTERPOLATION_BILINEAR;
        fields.pyramid = dsn::texton_pyramid(fields);
        LoadedNoise loaded(fields, make_config(7, 30));
        const dsn_noise_state *state = dsn_state(&loaded.noise);
        REQUIRE(state->cell_shift <= 4); // listed by the kernels
        REQUIRE(state->asset.pyramid_levels >= 1);
        TestRandom random(300 + channels);
        size_t compared = 0;
        for (uint32_t kernel = DSN_KERNEL_DEFAULT; kernel <= state->tile_kernel; kernel++)
            for (double apart : {1000.0, 3000.0, 9000.0, 100000.0})
                for (int i = 0; i < 4; i++) {
                    CAPTURE(kernel);
                    CAPTURE(apart);
                    dsn_noise copy = loaded.noise;
                    dsn_state(&copy)->tile_kernel = kernel;
                    dsn_filter_plan plan;
                    std::memset(&plan, 0, sizeof plan);
                    plan.lod_q8 = 128;
                    plan.taps = 2;
                    const double angle = random.next() / 4294967296.0 * 6.2832;
                    plan.offset_x[0] = q32(-apart / 2 * std::cos(angle)),
                    plan.offset_x[1] = -plan.offset_x[0];
                    plan.offset_y[0] = q32(-apart / 2 * std::sin(angle)),
                    plan.offset_y[1] = -plan.offset_y[0];
                    dsn_walked_level levels[2] = {dsn_internal_walked_level(state, 0),
                                                  dsn_internal_walked_level(state, 1)};
                    const uint64_t x =
                        uint64_t(q32(random.range(-100000, 100000) + random.next() / 4294967296.0));
                    const uint64_t y =
                        uint64_t(q32(random.range(-100000, 100000) + random.next() / 4294967296.0));
                    dsn_filter_sums walked, sifted;
                    std::memset(sifted, 0xA5, sizeof sifted);
                    dsn_internal_filter_sums_walked(dsn_state(&copy), x, y, &plan, levels, 2, walked);
                    dsn_internal_filter_sums_sifted(dsn_state(&copy), x, y, &plan, levels, 2, sifted);
                    for (uint32_t t = 0; t < 2; t++)
                        for (uint32_t l = 0; l < 2; l++)
                            for (uint32_t c = 0; c < channels; c++)
                                REQUIRE(sifted[t][l][c] == walked[t][l][c]);
                    compared++;
                }
        CHECK(compared == (state->tile_kernel + 1u - DSN_KERNEL_DEFAULT) * 16u);
    }
}

// The kernels' reads of one 8-bit level (kernels.h's filter_level_reads) against the bilinear formula,
// on levels of random bytes (full range, or all at an extreme) of 1 .. 13 texels a side (the AVX-512
// kernel holds those of at most 7 across and 11 down in registers for calls of 64 candidates or more,
// the others it gathers), with a stride wider than the window, at levels 0 .. 4, for up to 600 candidates a
// call (several of the reads' blocks), a part of them beyond the level's reach; with the gradient's
// closed tests (bias 0) on every other trial, and their slopes against add_slopes's formula.
TEST_CASE("filtered sift: the kernels' level reads equal the bilinear formula on random levels") {
    dsn::AssetFields fields = synthetic_fields(3, 15, 8, DSN_SHAPE_RECTANGLE, 31);
    LoadedNoise loaded(fields, make_config(8, 30));
    const uint32_t cpu_kernel = dsn_state(&loaded.noise)->tile_kernel;
    TestRandom random(400);
    size_t compared = 0, in_registers = 0;
    for (uint32_t trial = 0; trial < 400; trial++) {
        const uint32_t channels = trial % 2 == 0 ? 1u : 3u;
        const uint32_t width = 1 + random.next() % 13, height = 1 + random.next() % 13;
        const uint32_t stride = width + random.next() % 3, level_index = random.next() % 5;
        const uint32_t fill = trial % 10; // 0: all -128, 1: all 127, else random
        std::vector<unsigned char> values(stride * height * channels + 16);
        for (unsigned char &v : values)
            v = (unsigned char)(fill == 0 ? 0x80 : fill == 1 ? 0x7F : random.next() & 0xFF);
        dsn_walked_level level{values.data(),    width,       height, stride, (width - 1) / 2,
                               (height - 1) / 2, level_index, 0};
        auto texel = [&](int64_t row, int64_t column, uint32_t c) -> int64_t {
            if (row < 0 || column < 0 || row >= int64_t(height) || column >= int64_t(width)) return 0;
            return int64_t(int8_t(values[(uint32_t(row) * stride + uint32_t(column)) * channels + c]));
        };
        // The level test of level_test (filtered_sift.cpp) with start 0: u = c in reach when below limit,
        // read at (u + bias) >> level; closed (the gradient's): the limit 2^level higher and the bias 0.
        const uint64_t spacing = uint64_t(1) << level_index;
        const bool closed = trial % 4 >= 2;
        const uint64_t bias = closed ? 0 : spacing;
        const uint64_t limit_x = uint64_t(2 * level.radius_x + 2) * (spacing << 32) - bias,
                       limit_y = uint64_t(2 * level.radius_y + 2) * (spacing << 32) - bias;
        const uint32_t count = random.next() % 601;
        std::vector<int64_t> xs(count), ys(count);
        for (uint32_t i = 0; i < count; i++) {
            // mostly in reach, some just outside either bound
            xs[i] = int64_t(uint64_t(random.next()) << 32 | random.next()) % int64_t(limit_x + limit_x / 8);
            ys[i] = int64_t(uint64_t(random.next()) << 32 | random.next()) % int64_t(limit_y + limit_y / 8);
        }
        uint64_t expected[3] = {0, 0, 0}, expected_slopes[2][DSN_MAX_CHANNELS] = {{0, 0, 0}, {0, 0, 0}};
        for (uint32_t i = 0; i < count; i++) {
            if (uint64_t(xs[i]) >= limit_x || uint64_t(ys[i]) >= limit_y) continue;
            const uint64_t shifted_x = (uint64_t(xs[i]) + bias) >> level_index,
                           shifted_y = (uint64_t(ys[i]) + bias) >> level_index;
            const int64_t column = int64_t(shifted_x >> 32) - 1, row = int64_t(shifted_y >> 32) - 1;
            const uint64_t across = (shifted_x >> 16) & 0xFF00,
                           down = (shifted_y >> 16) & 0xFF00; // 8-bit weights
            for (uint32_t c = 0; c < channels; c++)
                expected[c] += uint64_t(texel(row, column, c)) * ((65536 - across) * (65536 - down)) +
                               uint64_t(texel(row, column + 1, c)) * (across * (65536 - down)) +
                               uint64_t(texel(row + 1, column, c)) * ((65536 - across) * down) +
                               uint64_t(texel(row + 1, column + 1, c)) * (across * down);
            for (uint32_t c = 0; c < channels; c++) {
                const int64_t a = texel(row, column, c), b = texel(row, column + 1, c),
                              d = texel(row + 1, column, c), e = texel(row + 1, column + 1, c);
                expected_slopes[0][c] +=
                    uint64_t((65536 - int64_t(down)) * (b - a) + int64_t(down) * (e - d));
                expected_slopes[1][c] +=
                    uint64_t((65536 - int64_t(across)) * (d - a) + int64_t(across) * (e - b));
            }
        }
        const uint64_t tests[5] = {0, limit_x, 0, limit_y, bias};
        const uint32_t narrow_tests[6] = {0, 0, 0, 0, 0, 0};
        for (uint32_t kernel = DSN_KERNEL_DEFAULT; kernel <= cpu_kernel; kernel++) {
            dsn_filter_level_reads_entry *reads = dsn_kernel_entries_of(kernel)->filter_level_reads;
            if (reads == 0) continue;
            INFO("kernel " << kernel << " channels " << channels << " window " << width << " x " << height
                           << " stride " << stride << " level " << level_index << " count " << count);
            uint64_t sums[3] = {0, 0, 0}, slope_sums[3] = {0, 0, 0};
            uint64_t slopes[2][DSN_MAX_CHANNELS] = {{0, 0, 0}, {0, 0, 0}};
            reads(&level, channels, xs.data(), ys.data(), 0, 0, count, tests, narrow_tests, sums, 0);
            for (uint32_t c = 0; c < channels; c++) REQUIRE(sums[c] == expected[c]);
#if DSN_GRADIENTS
            reads(&level, channels, xs.data(), ys.data(), 0, 0, count, tests, narrow_tests, slope_sums,
                  slopes);
            for (uint32_t c = 0; c < channels; c++) {
                REQUIRE(slope_sums[c] == expected[c]);
                REQUIRE(slopes[0][c] == expected_slopes[0][c]);
                REQUIRE(slopes[1][c] == expected_slopes[1][c]);
            }
#endif
            compared++;
            in_registers += kernel >= DSN_KERNEL_AVX512 && width <= 7 && height <= 11 && count >= 64 ? 1 : 0;
        }
    }
    // Some CPUs run no kernel with these reads; where one runs, every trial was compared.
    if (compared != 0) CHECK(compared % 400 == 0);
    if (cpu_kernel >= DSN_KERNEL_AVX512) CHECK(in_registers > 100);
}

#endif
