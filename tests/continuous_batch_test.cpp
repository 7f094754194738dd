// continuous_batch_test.cpp - batches of continuous points give exactly the per-point values, bit for bit,
// in every kernel this CPU runs: points anywhere (across the 32-bit wraps), periodic noises, densities
// from the sparsest to ones whose candidates overflow the kernel's arrays in the middle of a point, every
// cell size, 8- and 16-bit, grey and RGB textons, batches of every length around the chunk size and the
// size from which the texel table is built.
#include <doctest/doctest.h>

#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "fixtures/continuous_fixtures.h"
#include "runtime/kernels/kernels.h"

using namespace continuous_fixtures;

#if DSN_CONTINUOUS_BATCH

namespace {

const int64_t one = int64_t(1) << 32;

// The batch (fixed, float and u8), in every kernel this CPU runs, against the per-point functions of the
// default kernel; returns the number of values that differ.
size_t batch_differences(const dsn_noise &noise, const std::vector<int64_t> &xs,
                         const std::vector<int64_t> &ys) {
    const uint32_t channels = dsn_noise_channels(&noise);
    const uint32_t count = uint32_t(xs.size());
    std::vector<int32_t> expected(size_t(count) * channels);
    std::vector<float> expected_float(expected.size());
    std::vector<uint8_t> expected_u8(expected.size());
    std::vector<double> xs_double(count), ys_double(count);
    dsn_noise reference = noise; // the default kernel's per-point evaluator
    dsn_state(&reference)->tile_kernel = DSN_KERNEL_DEFAULT;
    for (uint32_t k = 0; k < count; k++) {
        REQUIRE(dsn_continuous_point_fixed(&reference, xs[k], ys[k], &expected[size_t(k) * channels]) ==
                DSN_OK);
        // Doubles with the same Q32.32 value (exact: at most 53 significant bits are kept)
        xs_double[k] = double(xs[k] >> 12) / double(1 << 20);
        ys_double[k] = double(ys[k] >> 12) / double(1 << 20);
        REQUIRE(dsn_continuous_point_float(&reference, xs_double[k], ys_double[k],
                                           &expected_float[size_t(k) * channels]) == DSN_OK);
        REQUIRE(dsn_continuous_point_u8(&reference, xs[k], ys[k], &expected_u8[size_t(k) * channels]) ==
                DSN_OK);
        for (uint32_t c = 0; c < channels; c++)
            REQUIRE(expected_u8[size_t(k) * channels + c] ==
                    dsn_fixed_to_u8(expected[size_t(k) * channels + c]));
    }
    const size_t scratch_size = dsn_continuous_batch_scratch_size(&noise);
    REQUIRE(scratch_size > 0);
    std::vector<unsigned char> buffer(scratch_size + 5);
    unsigned char *scratch = buffer.data() + 5; // no alignment needed
    size_t differences = 0;
    for (uint32_t kernel = DSN_KERNEL_DEFAULT; kernel <= dsn_state(&noise)->tile_kernel; kernel++) {
        dsn_noise copy = noise;
        dsn_state(&copy)->tile_kernel = kernel;
        CAPTURE(kernel);
        std::vector<int32_t> batch(expected.size(), 0x5A5A5A5A);
        std::vector<float> batch_float(expected.size(), -1.0f);
        std::vector<uint8_t> batch_u8(expected.size(), 0x5A);
        REQUIRE(dsn_continuous_batch_fixed(&copy, xs.data(), ys.data(), count, batch.data(), scratch,
                                           scratch_size) == DSN_OK);
        REQUIRE(dsn_continuous_batch_float(&copy, xs_double.data(), ys_double.data(), count,
                                           batch_float.data(), scratch, scratch_size) == DSN_OK);
        REQUIRE(dsn_continuous_batch_u8(&copy, xs.data(), ys.data(), count, batch_u8.data(), scratch,
                                        scratch_size) == DSN_OK);
        for (size_t i = 0; i < expected.size(); i++) {
            differences += batch[i] != expected[i];
            differences += std::memcmp(&batch_float[i], &expected_float[i], sizeof(float)) != 0;
            differences += batch_u8[i] != expected_u8[i];
        }
    }
    return differences;
}

} // namespace

TEST_CASE("continuous batch: equal to per point for every texton kind, density and cell size") {
    struct Case {
        uint32_t channels, radius, bits, impacts_q16;
    };
    // From the sparsest density (cells of 256 texels, fields of 16 bits) to dense ones (cells of 1 or 2
    // texels, several Poisson draws per cell, more candidates per point than the kernel's arrays hold).
    const Case cases[] = {{3, 15, 8, 30u << 16},           {1, 15, 8, 30u << 16},   {3, 15, 16, 30u << 16},
                          {1, 7, 16, 100u << 16},          {3, 2, 8, 1u << 16},     {3, 0, 8, 1u << 14},
                          {1, 20, 8, DSN_IMPACTS_MIN_Q16}, {3, 31, 16, 400u << 16}, {1, 1, 8, 64u << 16},
                          {3, 10, 8, 1000u << 16}};
    uint64_t seed = 1;
    for (const Case &c : cases) {
        CAPTURE(c.channels);
        CAPTURE(c.radius);
        CAPTURE(c.bits);
        CAPTURE(c.impacts_q16);
        auto noise = make_noise(random_texton_asset(c.channels, c.radius, c.bits, uint32_t(seed)),
                                uint32_t(seed * 77), c.impacts_q16);
        std::vector<int64_t> xs, ys;
        renderer_points(seed++, 101, &xs, &ys); // three chunks and a part
        CHECK(batch_differences(noise->noise, xs, ys) == 0);
    }
}

TEST_CASE("continuous batch: periodic noises, where points cross the int32 wrap too") {
    const uint32_t periods[][2] = {{16, 13}, {37, 0}, {0, 5}, {1, 1}, {3000, 77777}, {0xFFFFFFFFu, 1u << 31}};
    uint64_t seed = 100;
    for (const auto &period : periods) {
        CAPTURE(period[0]);
        CAPTURE(period[1]);
        auto noise = make_noise(random_texton_asset(3, 9, 8, 5), 9, 30u << 16, period[0], period[1]);
        std::vector<int64_t> xs, ys;
        renderer_points(seed++, 70, &xs, &ys);
        CHECK(batch_differences(noise->noise, xs, ys) == 0);
    }
}

TEST_CASE("continuous batch: every length around the chunk size, and points in any order") {
    auto noise = make_noise(random_texton_asset(3, 15, 8, 3), 4, 30u << 16);
    for (uint32_t count : {1u, 2u, 15u, 16u, 17u, 31u, 32u, 33u, 64u, 65u}) {
        CAPTURE(count);
        std::vector<int64_t> xs, ys;
        renderer_points(count, count, &xs, &ys);
        CHECK(batch_differences(noise->noise, xs, ys) == 0);
    }
    // The same point many times, and a dense run along a row (a renderer's coherent hits).
    std::vector<int64_t> xs(40, 12345 * one / 7), ys(40, -one / 3);
    for (uint32_t k = 0; k < 40; k++) xs.push_back(int64_t(k) * one / 5), ys.push_back(one / 9);
    CHECK(batch_differences(noise->noise, xs, ys) == 0);
}

TEST_CASE("continuous batch: batches large enough for the texel table the kernels build for them") {
    // continuous_batch.cpp builds its 2 x 2 texel table for 8-bit textons only from 512 points: batches
    // on both sides, grey and RGB, plain and periodic.
    auto rgb = make_noise(random_texton_asset(3, 15, 8, 8), 21, 30u << 16);
    auto grey = make_noise(random_texton_asset(1, 6, 8, 9), 22, 50u << 16, 0, 300);
    for (uint32_t count : {511u, 512u, 1100u}) {
        CAPTURE(count);
        std::vector<int64_t> xs, ys;
        renderer_points(count + 7, count, &xs, &ys);
        CHECK(batch_differences(rgb->noise, xs, ys) == 0);
        CHECK(batch_differences(grey->noise, xs, ys) == 0);
    }
}

TEST_CASE("continuous batch: points at the int64 extremes, in groups of every fill") {
    // Whole and fractional parts next to INT64_MIN and INT64_MAX, mixed with ordinary points so that the
    // kernels' groups of points hold both; lengths that leave a group partly filled.
    const int64_t most = INT64_MAX, least = INT64_MIN;
    const int64_t extremes[] = {
        most, least, most - one / 3, least + one / 7, most - 5 * one, least + 3 * one + 1,
        0,    -1,    one / 2,        -one / 2};
    auto noise = make_noise(random_texton_asset(3, 15, 8, 6), 11, 30u << 16);
    auto periodic = make_noise(random_texton_asset(1, 9, 8, 7), 12, 30u << 16, 37, 1000);
    for (uint32_t count : {3u, 9u, 23u, 40u}) {
        CAPTURE(count);
        std::vector<int64_t> xs, ys;
        for (uint32_t k = 0; k < count; k++) {
            xs.push_back(extremes[k % 10]);
            ys.push_back(extremes[(k * 7 + 3) % 10]);
        }
        CHECK(batch_differences(noise->noise, xs, ys) == 0);
        CHECK(batch_differences(periodic->noise, xs, ys) == 0);
    }
}

TEST_CASE("continuous batch: errors, and the output zeroed on an error") {
    auto noise = make_noise(random_texton_asset(3, 4, 8, 1), 1);
    const dsn_noise *n = &noise->noise;
    const size_t scratch_size = dsn_continuous_batch_scratch_size(n);
    std::vector<unsigned char> scratch(scratch_size);
    const int64_t xs[2] = {0, one}, ys[2] = {one / 2, -one};
    const double xs_double[2] = {0.0, 1.0}, ys_double[2] = {0.5, -1.0};
    int32_t out[6] = {7, 7, 7, 7, 7, 7};
    float out_float[6] = {7, 7, 7, 7, 7, 7};
    uint8_t out_u8[6] = {7, 7, 7, 7, 7, 7};
    CHECK(dsn_continuous_batch_fixed(n, xs, ys, 0, nullptr, nullptr, 0) == DSN_OK);
    CHECK(dsn_continuous_batch_fixed(n, nullptr, ys, 2, out, scratch.data(), scratch_size) == DSN_ERR_NULL);
    CHECK(dsn_continuous_batch_fixed(n, xs, nullptr, 2, out, scratch.data(), scratch_size) == DSN_ERR_NULL);
    CHECK(dsn_continuous_batch_fixed(n, xs, ys, 2, nullptr, scratch.data(), scratch_size) == DSN_ERR_NULL);
    CHECK(dsn_continuous_batch_fixed(n, xs, ys, 2, out, nullptr, scratch_size) == DSN_ERR_SCRATCH);
    CHECK(dsn_continuous_batch_fixed(n, xs, ys, 2, out, scratch.data(), scratch_size - 1) == DSN_ERR_SCRATCH);
    CHECK(dsn_continuous_batch_float(n, xs_double, ys_double, 2, out_float, scratch.data(),
                                     scratch_size - 1) == DSN_ERR_SCRATCH);
    CHECK(dsn_continuous_batch_u8(n, xs, ys, 2, out_u8, scratch.data(), scratch_size - 1) == DSN_ERR_SCRATCH);
    CHECK(dsn_continuous_batch_fixed(nullptr, xs, ys, 2, out, scratch.data(), scratch_size) == DSN_ERR_NULL);
    dsn_noise zeroed;
    std::memset(&zeroed, 0, sizeof zeroed);
    CHECK(dsn_continuous_batch_scratch_size(&zeroed) == 0);
    CHECK(dsn_continuous_batch_scratch_size(nullptr) == 0);
    CHECK(dsn_continuous_batch_float(&zeroed, xs_double, ys_double, 2, out_float, scratch.data(),
                                     scratch_size) == DSN_ERR_NULL);
    // Zeroed, not left as it was (api_edges_test.cpp checks how far, error by error).
    for (int i = 0; i < 6; i++) CHECK(out[i] == 0);
    for (int i = 0; i < 6; i++) CHECK(out_float[i] == 0.0f);
    for (int i = 0; i < 6; i++) CHECK(out_u8[i] == 0);
    // The per-point u8 function's errors zero its output likewise.
    uint8_t point_u8[3] = {7, 7, 7};
    CHECK(dsn_continuous_point_u8(n, xs[0], ys[0], nullptr) == DSN_ERR_NULL);
    CHECK(dsn_continuous_point_u8(&zeroed, xs[0], ys[0], point_u8) == DSN_ERR_NULL);
    CHECK(point_u8[0] == 0);
    // A lattice-baked asset is refused as by the per-point functions.
    dsn::AssetFields lattice = random_texton_asset(1, 3, 8, 2);
    lattice.interpolation = DSN_INTERPOLATION_LATTICE;
    auto lattice_noise = make_noise(lattice, 1);
    CHECK(dsn_continuous_batch_scratch_size(&lattice_noise->noise) == 0);
    CHECK(dsn_continuous_batch_fixed(&lattice_noise->noise, xs, ys, 2, out, scratch.data(), scratch_size) ==
          DSN_ERR_CONTINUOUS_MISMATCH);
    // Every kernel of the table has the batch entry and the splat's row loop.
    for (uint32_t i = 0; i < dsn_internal_kernel_count; i++) {
        const bool has_batch = dsn_internal_kernels[i].entries->continuous_batch != nullptr;
        const bool has_splat_row = dsn_internal_kernels[i].entries->continuous_splat_runs != nullptr;
        CHECK(has_batch);
        CHECK(has_splat_row);
    }
}

#endif
